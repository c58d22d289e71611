// libFuzzer target for the tracker CSV reader: any input ends in a table that
// satisfies the documented invariants (and writes back) or a legwork::Error.
#include <legwork/io/tracker_csv.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace legwork;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const io::TrackerTable t = io::parse_tracker_csv(text, "fuzz.csv");
    for (std::size_t i = 1; i < t.time.size(); ++i)
      if (!(t.time[i] > t.time[i - 1])) std::abort();
    for (const auto& p : t.points) {
      if (p.position.size() != t.time.size() || p.valid.size() != t.time.size()) std::abort();
      for (std::size_t i = 0; i < p.valid.size(); ++i)
        if (p.valid[i] && !p.position[i].allFinite()) std::abort();
    }
    const io::TrackerTable back = io::parse_tracker_csv(io::format_tracker_csv(t), "back.csv");
    if (back.sample_count() != t.sample_count() || back.points.size() != t.points.size()) std::abort();
  } catch (const Error&) {
  }
  return 0;
}
