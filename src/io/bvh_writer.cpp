#include <legwork/io/bvh.hpp>
#include <legwork/io/file_writer.hpp>
#include <legwork/io/text.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace legwork::io {

namespace {

const char* channel_name(Channel c) {
  static const char* names[] = {"Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation"};
  return names[static_cast<int>(c)];
}

void append_number(std::string& out, double v) {
  char buf[64];
  if (std::abs(v) < 5e-7) v = 0.0;  // no "-0.000000"
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 6);
  if (ec != std::errc())  // too large for fixed notation: shortest exact form instead
    ptr = std::to_chars(buf, buf + sizeof buf, v).ptr;
  out.append(buf, ptr);
}

// True if joint j's translation leaves its rest offset in some frame (a
// translating joint needs position channels to round-trip).
bool translates(const Motion& m, int j) {
  const Vec3& rest = m.skeleton.rest_offsets[static_cast<std::size_t>(j)];
  for (int f = 0; f < m.frame_count(); ++f)
    if ((m.frame(f).translations[static_cast<std::size_t>(j)] - rest).cwiseAbs().maxCoeff() > 1e-9) return true;
  return false;
}

std::vector<JointChannels> default_layout(const Motion& m) {
  const Skeleton& s = m.skeleton;
  std::vector<JointChannels> out(static_cast<std::size_t>(s.joint_count()));
  for (int j = 0; j < s.joint_count(); ++j) {
    auto& c = out[static_cast<std::size_t>(j)].channels;
    if (j == 0 || translates(m, j)) c = {Channel::Xposition, Channel::Yposition, Channel::Zposition};
    c.insert(c.end(), {Channel::Zrotation, Channel::Yrotation, Channel::Xrotation});
  }
  return out;
}

// Children of every joint, in order (one pass, not one scan per joint).
std::vector<std::vector<int>> children_lists(const Skeleton& s) {
  std::vector<std::vector<int>> kids(s.parents.size());
  for (int j = 1; j < s.joint_count(); ++j) {
    const int p = s.parents[static_cast<std::size_t>(j)];
    if (p >= 0 && p < j) kids[static_cast<std::size_t>(p)].push_back(j);
  }
  return kids;
}

// Deeper nesting than the reader accepts is refused (and would overflow the stack here).
constexpr int kMaxWriteDepth = 256;

void write_joint(std::string& out, const Skeleton& s, const std::vector<JointChannels>& layout,
                 const std::vector<std::vector<int>>& kids, int j, int depth, double scale) {
  if (depth > kMaxWriteDepth)
    throw Error("write_bvh: joint '" + s.names[static_cast<std::size_t>(j)] + "' is nested more than " +
                std::to_string(kMaxWriteDepth) + " deep");
  const std::string ind(static_cast<std::size_t>(depth), '\t');
  out += ind + (j == 0 ? "ROOT " : "JOINT ") + s.names[static_cast<std::size_t>(j)] + "\n" + ind + "{\n";
  out += ind + "\tOFFSET";
  for (int k = 0; k < 3; ++k) out += ' ', append_number(out, s.rest_offsets[static_cast<std::size_t>(j)][k] * scale);
  const auto& ch = layout[static_cast<std::size_t>(j)].channels;
  out += "\n" + ind + "\tCHANNELS " + std::to_string(ch.size());
  for (Channel c : ch) out += ' ', out += channel_name(c);
  out += '\n';
  for (int c : kids[static_cast<std::size_t>(j)]) write_joint(out, s, layout, kids, c, depth + 1, scale);
  if (s.has_end_site[static_cast<std::size_t>(j)]) {
    out += ind + "\tEnd Site\n" + ind + "\t{\n" + ind + "\t\tOFFSET";
    for (int k = 0; k < 3; ++k) out += ' ', append_number(out, s.end_sites[static_cast<std::size_t>(j)][k] * scale);
    out += "\n" + ind + "\t}\n";
  }
  out += ind + "}\n";
}

}  // namespace

void quat_to_euler(const Quat& q, const Channel* order, double* degrees) {
  // R = Ri(a) Rj(b) Rk(c) with distinct axes i, j, k (Tait-Bryan).
  const int i = static_cast<int>(order[0]) - 3, j = static_cast<int>(order[1]) - 3, k = static_cast<int>(order[2]) - 3;
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  const double s = ((j - i + 3) % 3 == 1) ? 1.0 : -1.0;  // even permutation of (0,1,2)?
  const double sb = std::clamp(s * R(i, k), -1.0, 1.0);
  const double b = std::asin(sb);
  double a, c;
  if (std::abs(sb) < 1.0 - 1e-12) {
    a = std::atan2(-s * R(j, k), R(k, k));
    c = std::atan2(-s * R(i, j), R(i, i));
  } else {  // gimbal lock: put all of the remaining rotation into a
    c = 0.0;
    a = std::atan2(s * R(k, j), R(j, j));
  }
  degrees[0] = rad2deg(a);
  degrees[1] = rad2deg(b);
  degrees[2] = rad2deg(c);
}

namespace {

// Refuses a motion the file could not hold faithfully (before anything is written).
void check_writable(const Motion& m, const std::vector<JointChannels>& layout) {
  const Skeleton& s = m.skeleton;
  if (!(m.fps > 0) || !std::isfinite(m.fps)) throw Error("write_bvh: frame rate must be positive, got " + std::to_string(m.fps));
  for (const Vec3& t : m.all_translations())
    if (!t.allFinite()) throw Error("write_bvh: the motion has a non-finite joint translation");
  for (const Quat& q : m.all_rotations())
    if (!q.coeffs().allFinite()) throw Error("write_bvh: the motion has a non-finite joint rotation");
  if (layout.size() != static_cast<std::size_t>(s.joint_count()))
    throw Error("write_bvh: channel layout has " + std::to_string(layout.size()) + " joints, skeleton has " +
                std::to_string(s.joint_count()));
  for (int j = 0; j < s.joint_count(); ++j) {
    const std::string& name = s.names[static_cast<std::size_t>(j)];
    const auto& ch = layout[static_cast<std::size_t>(j)].channels;
    int rot = 0;
    for (Channel c : ch) rot += c >= Channel::Xrotation;
    if (rot != 3 && rot != 0)
      throw Error("write_bvh: joint '" + name + "' has a layout with " + std::to_string(rot) + " rotation channels; legwork writes 0 or 3");
    // A layout that cannot hold the motion would lose data silently.
    const int pos = static_cast<int>(ch.size()) - rot;
    if (pos != 0 && pos != 3)
      throw Error("write_bvh: joint '" + name + "' has a layout with " + std::to_string(pos) + " position channels; legwork writes 0 or 3");
    if (pos == 0 && translates(m, j))
      throw Error("write_bvh: joint '" + name + "' moves away from its rest offset but its layout has no position channels");
    if (rot == 0) {
      for (int f = 0; f < m.frame_count(); ++f)
        if (m.frame(f).rotations[static_cast<std::size_t>(j)].angularDistance(Quat::Identity()) > 1e-9)
          throw Error("write_bvh: joint '" + name + "' rotates but its layout has no rotation channels");
    }
  }
}

// HIERARCHY ... "Frame Time: x\n".
std::string bvh_header(const Motion& m, const std::vector<JointChannels>& layout, double scale) {
  std::string out = "HIERARCHY\n";
  write_joint(out, m.skeleton, layout, children_lists(m.skeleton), 0, 0, scale);
  out += "MOTION\nFrames: " + std::to_string(m.frame_count()) + "\nFrame Time: ";
  char buf[64];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, 1.0 / m.fps, std::chars_format::general, 10);
  out.append(buf, ptr);
  out += '\n';
  return out;
}

// One motion line.
void append_frame(std::string& out, const Motion& m, int f, const std::vector<JointChannels>& layout, double scale) {
  auto pose = m.frame(f);
  bool first = true;
  for (int j = 0; j < m.skeleton.joint_count(); ++j) {
    const auto& ch = layout[static_cast<std::size_t>(j)].channels;
    Channel rot_order[3];
    int nr = 0;
    for (Channel c : ch)
      if (c >= Channel::Xrotation) rot_order[nr++] = c;
    double euler[3] = {0, 0, 0};
    if (nr == 3) quat_to_euler(pose.rotations[static_cast<std::size_t>(j)], rot_order, euler);
    int r = 0;
    for (Channel c : ch) {
      if (!first) out += ' ';
      first = false;
      if (c >= Channel::Xrotation) append_number(out, euler[r++]);
      else append_number(out, pose.translations[static_cast<std::size_t>(j)][static_cast<int>(c)] * scale);
    }
  }
  out += '\n';
}

// The file text in pieces of about kChunkBytes, each passed to `sink` (the
// whole text never has to be held: a long walk's file is ~100 MB).
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

template <class Sink>
void emit_bvh(const Motion& m, const BvhWriteOptions& opt, std::string header, const std::vector<JointChannels>& layout,
              Sink&& sink) {
  std::string out = std::move(header);
  for (int f = 0; f < m.frame_count(); ++f) {
    append_frame(out, m, f, layout, opt.scale);
    if (out.size() >= kChunkBytes) sink(out), out.clear();
  }
  sink(out);
}

std::vector<JointChannels> checked_layout(const Motion& m, const BvhWriteOptions& opt) {
  m.skeleton.validate();
  auto layout = opt.channels.empty() ? default_layout(m) : opt.channels;
  check_writable(m, layout);
  return layout;
}

}  // namespace

std::string format_bvh(const Motion& m, const BvhWriteOptions& opt) {
  const auto layout = checked_layout(m, opt);
  std::string header = bvh_header(m, layout, opt.scale);
  std::string all;
  all.reserve(header.size() + static_cast<std::size_t>(m.frame_count()) * static_cast<std::size_t>(m.skeleton.joint_count()) * 40);
  emit_bvh(m, opt, std::move(header), layout, [&](const std::string& piece) { all += piece; });
  return all;
}

void write_bvh(const std::string& path, const Motion& m, const BvhWriteOptions& opt) {
  // Everything that can refuse the motion runs before the file is opened.
  const auto layout = checked_layout(m, opt);
  std::string header = bvh_header(m, layout, opt.scale);
  TextFileWriter file(path);
  emit_bvh(m, opt, std::move(header), layout, [&](const std::string& piece) { file.write(piece); });
  file.close();
}

}  // namespace legwork::io
