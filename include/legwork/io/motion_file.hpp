#pragma once
// Motion files by extension (.bvh, .glb): reading with the shared options,
// writing, converting, and describing a file (what `legwork info` prints).
#include <legwork/io/bvh.hpp>

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace legwork::io {

struct MotionReadOptions {
  double scale = 0;         // file units -> metres; 0 = detect (BVH) / metres (glTF)
  bool drop_first = false;  // drop frame 0 (the CMU T-pose)
  bool lenient = false;     // BVH: accept more motion lines than 'Frames:' declares
};

// A .bvh (read_bvh) or a .glb written by legwork (read_glb; metres already,
// roles resolved). Throws legwork::Error naming the file.
BvhFile read_motion(const std::string& path, const MotionReadOptions& opt = {});

// Writes `m` as .bvh or .glb by the path's extension (`animation_name` names
// the glTF animation); anything else is refused naming `option`.
void write_motion(const std::string& path, const Motion& m, const std::string& animation_name = "motion",
                  const std::string& option = "output");

// `legwork convert`: trim (frames "A:B", see parse_frame_range), mirror and
// resample (rate > 0, at most kMaxConvertRate Hz and kMaxConvertJointPoses
// frames x joints, checked before any work), then write by extension; a BVH
// keeps the source's channel layout and units when it can hold the data.
inline constexpr double kMaxConvertRate = 1000.0;
inline constexpr double kMaxConvertJointPoses = 16777216.0;  // 2^24: 0.9 GB of poses
struct ConvertOptions {
  double rate = 0;     // Hz; 0 = keep
  bool mirror = false;
  std::string frames;  // "A:B"; empty = all
};
Motion convert_motion(const BvhFile& source, const ConvertOptions& opt, const std::string& out);

// What `legwork info` shows: joints, frames, rate, units, body measures,
// roles, hierarchy and warnings, as text or JSON (numbers rounded to what
// the file can hold: fps to 1e-6, lengths to 0.1 mm).
std::string motion_info_text(const BvhFile& f);
nlohmann::json motion_info_json(const BvhFile& f);

}  // namespace legwork::io
