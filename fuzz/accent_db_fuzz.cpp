// libFuzzer target for the accent database file (load + validate) and what
// consumes a loaded database: its KD-trees, an accentuation model and a few
// frames of a real head-and-hands stream through accent::update().
// Before loading, the header's file size and checksum are set to match the
// input (a mutation would otherwise almost always stop at the checksum), so
// mutations reach the layout checks, the JSON metadata and the content checks.
// Any input ends in a database whose poses stay finite through update(), or
// in a legwork::Error: never a crash, a sanitizer report or a hang.
#include "database_impl.hpp"
#include "fuzz_body.hpp"

#include <legwork/accent/accent.hpp>
#include <legwork/io/bvh.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

using namespace legwork;

// 12 frames of the head and wrists of a real walk (data/cmu/bvh/walking/07_02.bvh) at 90 Hz.
const std::vector<TrackerFrame>& stream() {
  static const std::vector<TrackerFrame> frames = fuzz::sample_frames("cmu/bvh/walking/07_02.bvh", 90.0, 12);
  return frames;
}

void accentuate(const accent::Database& db) {
  accent::Settings s;
  s.search = accent::SearchMode::Exact;
  const accent::Model model = accent::make_model(db, s);
  accent::State state(model);
  Pose pose(model.skeleton());
  for (const TrackerFrame& f : stream()) {
    accent::update(model, f, state, pose.ref());
    for (std::size_t j = 0; j < pose.rotations.size(); ++j)
      if (!pose.rotations[j].coeffs().allFinite() || !pose.translations[j].allFinite()) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::byte> block(size);
  if (size) std::memcpy(block.data(), data, size);
  if (size >= sizeof(accent::FileHeader)) {
    const std::uint64_t n = size;
    std::memcpy(block.data() + offsetof(accent::FileHeader, file_bytes), &n, sizeof n);
    const std::uint64_t sum = accent::block_checksum(block);
    std::memcpy(block.data() + offsetof(accent::FileHeader, checksum), &sum, sizeof sum);
  }
  try {
    accent::Database db = accent::Database::from_bytes(std::move(block), "fuzz.lwdb");
    db.build_index();
    accentuate(db);
  } catch (const Error&) {
  }
  return 0;
}
