// libFuzzer target for walk files (key-pose JSON, legwork-walk/1) and what
// consumes them: the cycle builder, every frame of the baked cycle and a
// short straight walk. Any input ends in a cycle whose poses are finite or in
// a legwork::Error: never a crash, a sanitizer report or a hang.
#include "fuzz_body.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/keys.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/walk.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

namespace {

using namespace legwork;

void check_motion(const Motion& m) {
  for (int f = 0; f < m.frame_count(); ++f)
    for (const Vec3& p : joint_positions(m.skeleton, m.frame(f)))
      if (!p.allFinite()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Skeleton& skel = fuzz::sample_skeleton();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    walkcycle::WalkKeys keys = walkcycle::parse_walk_keys(text, skel, "fuzz.json");
    // The harness's cap (not the reader's): a cycle of up to 1000 frames (the
    // file limit) made every execution bake and walk thousands of frames,
    // 135 exec/s. Longer cycles are retimed to kMaxFuzzCycleFrames, the same
    // code `walkcycle --frames` runs; the parser still sees the full range.
    constexpr int kMaxFuzzCycleFrames = 64;
    if (keys.frames_per_cycle > kMaxFuzzCycleFrames) keys = walkcycle::retime(keys, kMaxFuzzCycleFrames);
    const walkcycle::CycleModel cycle = walkcycle::build_cycle(skel, keys);
    check_motion(walkcycle::bake_cycle(cycle));
    walkcycle::WalkOptions o;
    o.steps = 3;
    check_motion(walkcycle::walk_path(cycle, walkcycle::straight_path(2.0), o).motion);
  } catch (const Error&) {
  }
  return 0;
}
