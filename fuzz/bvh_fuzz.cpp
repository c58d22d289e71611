// libFuzzer target for the BVH reader and what consumes a parsed file:
// forward kinematics of every frame and the writer.
// Any input must end in a parsed motion or a legwork::Error: never a crash,
// a sanitizer report, a hang or an unbounded allocation.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>

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
    for (int fr = 0; fr < m.frame_count(); ++fr)
      for (const Vec3& p : joint_positions(m.skeleton, m.frame(fr)))
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) std::abort();
    io::BvhWriteOptions w;
    w.channels = f.channels;
    (void)io::format_bvh(f.motion, w);
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
