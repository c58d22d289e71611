// libFuzzer target for the .glb reader (tinygltf + legwork's checks) and
// what consumes its result: forward kinematics of every frame and the BVH
// writer. Any input ends in a motion that satisfies the model's invariants
// or in a legwork::Error: never a crash, a sanitizer report, a hang or an
// allocation the input's size does not justify.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

namespace {

// Inputs are a .glb as is, or "<JSON text>\0<BIN bytes>", which is wrapped
// here into a well-formed GLB container: mutations of the JSON then reach
// the reader instead of dying on the container's length fields.
std::string as_glb(std::string_view in) {
  if (in.substr(0, 4) == "glTF") return std::string(in);
  const std::size_t nul = in.find('\0');
  std::string json(in.substr(0, nul));
  const std::string_view bin = nul == std::string_view::npos ? std::string_view() : in.substr(nul + 1);
  while (json.size() % 4) json += ' ';
  std::string out;
  auto put = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  out += "glTF";
  put(2);
  put(static_cast<std::uint32_t>(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  put(static_cast<std::uint32_t>(json.size()));
  out += "JSON";
  out += json;
  if (!bin.empty()) {
    put(static_cast<std::uint32_t>(bin.size()));
    out += std::string("BIN\0", 4);
    out += bin;
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace legwork;
  const std::string bytes = as_glb(std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    // A low rate keeps each execution short; the sample count bound is the same code at any rate.
    const Motion m = io::parse_glb(bytes, "fuzz.glb", 5.0);
    m.skeleton.validate();
    if (m.frame_count() < 1 || !(m.fps > 0)) std::abort();
    if (static_cast<double>(m.frame_count()) * m.joint_count() > io::kMaxGlbJointPoses) std::abort();
    // FK of the first frames and the last (all of them would turn long clips into timeouts, not findings).
    auto fk = [&](int f) {
      for (const Vec3& p : joint_positions(m.skeleton, m.frame(f)))
        if (!p.allFinite()) std::abort();  // values are checked finite and bounded at read
    };
    for (int f = 0; f < m.frame_count() && f < 64; ++f) fk(f);
    fk(m.frame_count() - 1);
    // The writer too, on motions of a size a test file has.
    if (static_cast<double>(m.frame_count()) * m.joint_count() <= 1e5) (void)io::format_bvh(m);
  } catch (const Error&) {
  }
  return 0;
}
