// libFuzzer target for the BVH reader and what consumes a parsed file:
// forward kinematics and the writer (of up to 4096 joint poses per file).
// Any input must end in a parsed motion or a legwork::Error: never a crash,
// a sanitizer report, a hang or an unbounded allocation.
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/bvh.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

namespace {

void parse_and_write(std::string_view text, const legwork::io::BvhReadOptions& opt) {
  using namespace legwork;
  try {
    io::BvhFile f = io::parse_bvh(text, "fuzz.bvh", opt);
    // A parsed file must satisfy the model's invariants.
    f.motion.skeleton.validate();
    if (f.motion.frame_count() < 1 || !(f.motion.fps > 0)) std::abort();
    // Past parsing: FK of every frame must stay finite (values are finite at
    // read; a parsed-but-absurd file is exercised here, not just read), and
    // the writer (which may refuse layouts it cannot express, e.g. 1 or 2
    // rotation channels).
    const Motion& m = f.motion;
    if (static_cast<double>(m.frame_count()) * m.joint_count() > static_cast<double>(1 << 26)) std::abort();
    // The harness's cap (not the reader's): FK and the writer see at most
    // kFuzzJointPoses joint poses, the first frames and the last (a 16 KB
    // input may legally hold millions of joint poses, each FK'd and written
    // twice per execution). The reader still parses and stores all of them.
    constexpr int kFuzzJointPoses = 4096;
    const int keep = std::max(1, std::min(m.frame_count(), kFuzzJointPoses / std::max(1, m.joint_count())));
    auto fk = [&](int fr) {
      for (const Vec3& p : joint_positions(m.skeleton, m.frame(fr)))
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) std::abort();
    };
    for (int fr = 0; fr < keep; ++fr) fk(fr);
    fk(m.frame_count() - 1);
    io::BvhWriteOptions w;
    w.channels = f.channels;
    (void)io::format_bvh(keep == m.frame_count() ? m : trim(m, 0, keep - 1), w);
  } catch (const Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  legwork::io::BvhReadOptions detect;  // unit detection, strict frame count
  parse_and_write(text, detect);
  legwork::io::BvhReadOptions lenient;
  lenient.scale = 1.0;
  lenient.strict_frame_count = false;
  lenient.drop_first_frame = true;
  parse_and_write(text, lenient);
  return 0;
}
