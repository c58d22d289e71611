// libFuzzer target for the tracker CSV reader and what consumes it: any input
// ends in a table that satisfies the documented invariants (and writes back),
// then in TrackerFrames that the per-frame time and device rules accept or
// reject cleanly, or in a legwork::Error. Never a crash, a sanitizer report,
// a hang or an unbounded allocation.
#include <legwork/core/tracker.hpp>
#include <legwork/io/tracker_csv.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

namespace {

using namespace legwork;

void check_table(const io::TrackerTable& t) {
  for (std::size_t i = 1; i < t.time.size(); ++i)
    if (!(t.time[i] > t.time[i - 1])) std::abort();
  for (const auto& p : t.points) {
    if (p.position.size() != t.time.size() || p.valid.size() != t.time.size()) std::abort();
    for (std::size_t i = 0; i < p.valid.size(); ++i)
      if (p.valid[i] && !p.position[i].allFinite()) std::abort();
  }
  const io::TrackerTable back = io::parse_tracker_csv(io::format_tracker_csv(t), "back.csv");
  if (back.sample_count() != t.sample_count() || back.points.size() != t.points.size()) std::abort();
}

// The frames as a runtime sees them: the clock's verdict for every time, and
// usable() for every device (a usable device is finite and in range).
void consume_frames(const io::TrackerTable& t) {
  const std::vector<TrackerFrame> frames = io::frames_from_table(t, "fuzz.csv");
  if (frames.size() != t.time.size()) std::abort();
  FrameClock clock;
  for (const TrackerFrame& f : frames) {
    const bool running = clock.started();
    const FrameClock::Step step = clock.advance(f.time);
    // The first accepted frame has dt = 0, every later one a positive finite dt.
    if (step.verdict == FrameClock::Verdict::Accept &&
        !(std::isfinite(step.dt) && (running ? step.dt > 0 : step.dt == 0)))
      std::abort();
    for (const DevicePose& d : f.devices)
      if (usable(d) && (!d.position.allFinite() || d.position.cwiseAbs().maxCoeff() > kMaxCoordinate ||
                        !d.rotation.coeffs().allFinite()))
        std::abort();
  }
  // The inverse keeps one point per device seen.
  (void)io::table_from_frames(frames);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const io::TrackerTable t = io::parse_tracker_csv(text, "fuzz.csv");
    check_table(t);
    consume_frames(t);
  } catch (const Error&) {
  }
  return 0;
}
