#pragma once
// BVH (Biovision hierarchy) reading and writing.
// Reading converts to legwork conventions at the file boundary: file units are
// scaled to metres (auto-detected or given), Euler channels become local
// quaternions. Errors throw legwork::Error naming file, line and what was
// expected.
#include <legwork/core/motion.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace legwork::io {

enum class Channel : unsigned char { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

// Channels of one joint in file order (0, 3 or 6 of them).
struct JointChannels {
  std::vector<Channel> channels;
};

struct BvhReadOptions {
  // File units -> metres. 0 = detect from the rest-pose standing height.
  double scale = 0.0;
  // Drop frame 0 (CMU files start with a synthetic T-pose).
  bool drop_first_frame = false;
  // Replace all-zero motion lines (a CMU export glitch) by the nearest real frame.
  bool repair_zero_frames = true;
  // Resolve joint roles; missing roles are reported, not an error.
  bool resolve_roles = true;
  // A 'Frames:' count that disagrees with the motion lines is an error; when
  // false, extra lines are ignored with a warning (fewer lines stay an error).
  bool strict_frame_count = true;
};

struct BvhReport {
  double scale = 1.0;            // units -> metres factor applied
  std::string scale_reason;      // how it was chosen
  int declared_frames = 0;       // the Frames: value
  int repaired_zero_frames = 0;  // all-zero lines replaced
  bool dropped_first_frame = false;
  std::vector<Role> missing_roles;
  std::vector<std::string> warnings;
};

struct BvhFile {
  Motion motion;
  std::vector<JointChannels> channels;  // per joint, as in the file
  BvhReport report;
};

// Parses BVH text. `source` names the file in error messages
// ("source:line: what was expected"). Accepts any channel order, 0-6 channels
// on any joint (position channels replace the OFFSET), End Sites, tabs, CRLF,
// scientific notation, a UTF-8 byte-order mark. Limits (each an error naming
// file and line): joints nested <= 256 deep; frames x joints <= 2^21 + 8 per
// byte of text and <= 2^26 (joints without channels cost memory but no text);
// Frame Time in [1e-4, 10] s; offsets and positions within 1e9 file units;
// joint names UTF-8; UTF-16/UTF-32 text is named. Thread-safe (no shared
// state). See docs/io.md and docs/reliability.md.
BvhFile parse_bvh(std::string_view text, std::string_view source, const BvhReadOptions& opt = {});
BvhFile read_bvh(const std::string& path, const BvhReadOptions& opt = {});
// Convenience: the motion only.
Motion load_bvh(const std::string& path, const BvhReadOptions& opt = {});

struct BvhWriteOptions {
  // Metres -> file units (1 = metres; 1/kCmuUnitMetres to write CMU units).
  double scale = 1.0;
  // Channel layout per joint; empty = root "Xposition Yposition Zposition
  // Zrotation Yrotation Xrotation", others "Zrotation Yrotation Xrotation"
  // (plus the three position channels first if the joint's translation
  // leaves its rest offset in any frame, so translating joints round-trip).
  std::vector<JointChannels> channels;
};
std::string format_bvh(const Motion& m, const BvhWriteOptions& opt = {});
void write_bvh(const std::string& path, const Motion& m, const BvhWriteOptions& opt = {});

// Euler helpers (degrees, channel order as listed, applied left to right:
// e.g. Z,Y,X means R = Rz * Ry * Rx).
Quat euler_to_quat(const Channel* order, const double* degrees, int n);
void quat_to_euler(const Quat& q, const Channel* order, double* degrees);

}  // namespace legwork::io
