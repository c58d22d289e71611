// glTF 2.0 binary import: legwork's own files exactly, other tools' skins
// and animations when the rig resolves to roles (see gltf.hpp).
#include <tiny_gltf.h>

#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

namespace legwork::io {

namespace {

// Float elements of an accessor (any stride), checked against the expected
// shape. Every size comes from the file, so the accessor must fit its buffer
// view and the view its buffer, with arithmetic that cannot wrap (tinygltf
// does not check `count`: 2^62 + 1 elements must not become a small vector).
std::vector<float> read_floats(const tinygltf::Model& model, int accessor, int type, const std::string& path,
                               const char* what) {
  if (accessor < 0 || static_cast<std::size_t>(accessor) >= model.accessors.size())
    throw Error(path + ": " + what + " refers to a missing accessor");
  const auto& acc = model.accessors[static_cast<std::size_t>(accessor)];
  if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || acc.type != type || acc.bufferView < 0 ||
      static_cast<std::size_t>(acc.bufferView) >= model.bufferViews.size())
    throw Error(path + ": " + what + " is not a float accessor of the expected type");
  const auto& view = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    throw Error(path + ": " + what + " refers to a missing buffer");
  const auto& buf = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  const auto comps = static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
  const int stride_int = acc.ByteStride(view);
  const std::size_t element = comps * sizeof(float);
  const auto fail = [&] {
    throw Error(path + ": " + what + " (" + std::to_string(acc.count) + " elements) reaches past the end of its buffer");
  };
  if (stride_int <= 0) fail();
  const auto stride = static_cast<std::size_t>(stride_int);
  // The view lies in the buffer, the accessor's first element in the view.
  if (view.byteOffset > buf.size() || view.byteLength > buf.size() - view.byteOffset) fail();
  if (acc.count == 0) return {};
  if (acc.byteOffset > view.byteLength || element > view.byteLength - acc.byteOffset) fail();
  // Last element: byteOffset + (count - 1) * stride + element <= byteLength, without overflow.
  if (acc.count - 1 > (view.byteLength - acc.byteOffset - element) / stride) fail();
  const std::size_t start = view.byteOffset + acc.byteOffset;
  std::vector<float> out(acc.count * comps);  // count * element <= buffer bytes: no overflow
  for (std::size_t i = 0; i < acc.count; ++i)
    std::memcpy(&out[i * comps], buf.data() + start + i * stride, element);
  return out;
}

// Index of the key segment [k, k+1] holding t and the blend factor in it.
// Times are floats: compare in float, so a t just below the last key that
// rounds up to it never makes upper_bound return end(). `times` is strictly
// increasing (read_glb checks it).
std::pair<std::size_t, double> locate(const std::vector<float>& times, double t) {
  const auto tf = static_cast<float>(t);
  if (times.size() < 2 || !(tf > times.front())) return {0, 0.0};
  if (tf >= times.back()) return {times.size() - 1, 0.0};
  const auto it = std::upper_bound(times.begin(), times.end(), tf);  // in (begin, end)
  const std::size_t k = static_cast<std::size_t>(it - times.begin()) - 1;
  const double span = static_cast<double>(times[k + 1]) - times[k];
  return {k, span > 0 ? std::clamp((t - times[k]) / span, 0.0, 1.0) : 0.0};
}

// Key times must be finite, non-negative and strictly increasing (glTF 2.0, 3.11).
void check_key_times(const std::vector<float>& times, const std::string& path, const std::string& joint) {
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]) || times[i] < 0)
      throw Error(path + ": animation key time " + std::to_string(i) + " of '" + joint + "' is not a finite time >= 0");
    if (i > 0 && !(times[i] > times[i - 1]))
      throw Error(path + ": animation key times of '" + joint + "' are not strictly increasing (key " +
                  std::to_string(i) + ")");
  }
}

// glb files are self-contained: never let a crafted buffer URI read another
// file (/dev/zero, /etc/...) on the reader's machine. tinygltf asks whether
// the file exists first, so that answer ("File not found") is what refuses.
bool refuse_external_file(std::vector<unsigned char>*, std::string* err, const std::string& file, void*) {
  if (err) *err += "external file '" + file + "' refused: legwork reads only self-contained .glb files\n";
  return false;
}
bool no_file_exists(const std::string&, void*) { return false; }
std::string same_path(const std::string& p, void*) { return p; }
bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing files is disabled\n";
  return false;
}

// Deeper nesting than this is not a body (the BVH reader's limit too).
constexpr int kMaxGlbDepth = 256;

using Mat4 = Eigen::Matrix4d;

// A node's local transform (matrix, or T * R * S).
Mat4 local_matrix(const tinygltf::Node& node) {
  Mat4 m = Mat4::Identity();
  if (node.matrix.size() == 16) {
    for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = node.matrix[static_cast<std::size_t>(k)];
    return m;
  }
  if (node.scale.size() == 3) m.topLeftCorner<3, 3>() = Vec3(node.scale[0], node.scale[1], node.scale[2]).asDiagonal();
  if (node.rotation.size() == 4) {
    const Quat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    if (q.coeffs().allFinite() && q.norm() > 1e-12) m.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix() * m.topLeftCorner<3, 3>();
  }
  if (node.translation.size() == 3) m.topRightCorner<3, 1>() = Vec3(node.translation[0], node.translation[1], node.translation[2]);
  return m;
}

// The skeleton of the first skin, with where each joint came from.
struct Rig {
  Skeleton skel;
  std::vector<int> node_of_joint;
  std::map<int, int> joint_of_node;
  bool skin_order = true;  // joints kept in the skin's order (legwork's own files)
  // Transform of the nodes above the root joint: uniform scale, rotation, translation.
  double scale = 1.0;
  Quat rotation = Quat::Identity();
  Vec3 offset = Vec3::Zero();
};

// Parent node of every node; children must exist and have one parent.
std::vector<int> node_parents(const tinygltf::Model& model, const std::string& path) {
  const auto node_count = static_cast<int>(model.nodes.size());
  std::vector<int> parent(model.nodes.size(), -1);
  for (int n = 0; n < node_count; ++n)
    for (int c : model.nodes[static_cast<std::size_t>(n)].children) {
      if (c < 0 || c >= node_count)
        throw Error(path + ": node '" + model.nodes[static_cast<std::size_t>(n)].name + "' has a missing child " + std::to_string(c));
      if (parent[static_cast<std::size_t>(c)] >= 0 || c == n)
        throw Error(path + ": node " + std::to_string(c) + " has more than one parent");
      parent[static_cast<std::size_t>(c)] = n;
    }
  return parent;
}

// Skin joints (node indices), checked; fills rig.joint_of_node with skin indices.
const std::vector<int>& skin_joints(const tinygltf::Model& model, const std::string& path, std::map<int, int>& skin_index) {
  if (model.skins.empty()) throw Error(path + ": no skin (legwork reads skeletons from the first skin)");
  const auto& joints = model.skins[0].joints;
  if (joints.empty()) throw Error(path + ": skin 0 has no joints");
  for (int node : joints)
    if (node < 0 || node >= static_cast<int>(model.nodes.size()))
      throw Error(path + ": skin joint refers to missing node " + std::to_string(node));
  for (std::size_t j = 0; j < joints.size(); ++j)
    if (!skin_index.emplace(joints[j], static_cast<int>(j)).second)
      throw Error(path + ": skin lists node " + std::to_string(joints[j]) + " twice");
  return joints;
}

// Joint nodes in depth-first order under the root joint with the most
// descendants (others, e.g. IK targets, are dropped); the skin's own order
// when it already is parent-before-child with a single root.
std::vector<int> joint_order(const tinygltf::Model& model, const std::vector<int>& joints, const std::vector<int>& node_parent,
                             const std::map<int, int>& skin_index, std::vector<int>& joint_parent) {
  joint_parent.assign(joints.size(), -1);  // skin index of the nearest joint ancestor
  for (std::size_t j = 0; j < joints.size(); ++j) {
    int n = node_parent[static_cast<std::size_t>(joints[j])];
    for (std::size_t steps = 0; n >= 0 && steps < model.nodes.size(); ++steps, n = node_parent[static_cast<std::size_t>(n)])
      if (auto it = skin_index.find(n); it != skin_index.end()) {
        joint_parent[j] = it->second;
        break;
      }
  }
  bool in_order = true;
  for (std::size_t j = 0; j < joints.size(); ++j)
    in_order = in_order && (j == 0 ? joint_parent[j] < 0 : joint_parent[j] >= 0 && joint_parent[j] < static_cast<int>(j));
  if (in_order) return joints;
  std::vector<std::vector<int>> kids(joints.size());
  std::vector<int> roots;
  for (std::size_t j = 0; j < joints.size(); ++j)
    (joint_parent[j] < 0 ? roots : kids[static_cast<std::size_t>(joint_parent[j])]).push_back(static_cast<int>(j));
  // Siblings in node order (the order the hierarchy was authored in), not skin order.
  const auto by_node = [&](int a, int b) { return joints[static_cast<std::size_t>(a)] < joints[static_cast<std::size_t>(b)]; };
  for (auto& k : kids) std::sort(k.begin(), k.end(), by_node);
  std::sort(roots.begin(), roots.end(), by_node);
  auto subtree = [&](int root) {
    std::vector<int> order, stack{root};
    while (!stack.empty()) {
      const int j = stack.back();
      stack.pop_back();
      order.push_back(joints[static_cast<std::size_t>(j)]);
      const auto& k = kids[static_cast<std::size_t>(j)];
      stack.insert(stack.end(), k.rbegin(), k.rend());
    }
    return order;
  };
  std::vector<int> best;
  for (int r : roots)
    if (auto o = subtree(r); o.size() > best.size()) best = std::move(o);
  return best;
}

Vec3 checked_vec3(const Vec3& v, const std::string& path, const std::string& name) {
  if (!v.allFinite() || v.cwiseAbs().maxCoeff() > 1e6)
    throw Error(path + ": node '" + name + "' has a translation that is not finite or beyond 1000 km");
  return v;
}

// The transform of the nodes above the root joint, as uniform scale, rotation and offset.
void read_root_frame(const tinygltf::Model& model, const std::vector<int>& node_parent, int root_node, const std::string& path,
                     Rig& rig) {
  Mat4 above = Mat4::Identity();
  std::size_t steps = 0;
  for (int n = node_parent[static_cast<std::size_t>(root_node)]; n >= 0 && steps < model.nodes.size();
       n = node_parent[static_cast<std::size_t>(n)], ++steps)
    above = local_matrix(model.nodes[static_cast<std::size_t>(n)]) * above;
  const Eigen::Matrix3d m = above.topLeftCorner<3, 3>();
  const Vec3 norms(m.col(0).norm(), m.col(1).norm(), m.col(2).norm());
  if (!above.allFinite() || norms.minCoeff() < 1e-9 || norms.maxCoeff() > 1e-3 + 1.001 * norms.minCoeff() || m.determinant() < 0)
    throw Error(path + ": the nodes above the root joint '" + model.nodes[static_cast<std::size_t>(root_node)].name +
                "' scale it unevenly or mirror it (legwork reads uniform scale, rotation and translation)");
  rig.scale = norms.mean();
  rig.rotation = Quat(Eigen::Matrix3d(m / rig.scale)).normalized();
  rig.offset = above.topRightCorner<3, 1>();
}

// Skeleton of the first skin: joints in depth-first order with a single root.
Rig read_rig(const tinygltf::Model& model, const std::string& path) {
  std::map<int, int> skin_index;
  const auto& joints = skin_joints(model, path, skin_index);
  const std::vector<int> node_parent = node_parents(model, path);
  std::vector<int> joint_parent;
  Rig rig;
  rig.node_of_joint = joint_order(model, joints, node_parent, skin_index, joint_parent);
  rig.skin_order = rig.node_of_joint == joints;
  for (std::size_t j = 0; j < rig.node_of_joint.size(); ++j) rig.joint_of_node[rig.node_of_joint[j]] = static_cast<int>(j);
  std::vector<int> depth(rig.node_of_joint.size(), 0);
  for (std::size_t j = 0; j < rig.node_of_joint.size(); ++j) {
    const int n = rig.node_of_joint[j];
    const auto& node = model.nodes[static_cast<std::size_t>(n)];
    const std::string name = node.name.empty() ? "joint" + std::to_string(j) : node.name;
    const int ps = joint_parent[static_cast<std::size_t>(skin_index.at(n))];
    const int p = j == 0 || ps < 0 ? -1 : rig.joint_of_node.at(joints[static_cast<std::size_t>(ps)]);
    if (j > 0 && (depth[j] = depth[static_cast<std::size_t>(p)] + 1) > kMaxGlbDepth)
      throw Error(path + ": joint '" + name + "' is nested more than " + std::to_string(kMaxGlbDepth) + " deep");
    rig.skel.add_joint(name, p, checked_vec3(local_matrix(node).topRightCorner<3, 1>(), path, name));
    // A childless, mesh-less node under a joint is an End Site (write_glb's "<joint>_end").
    for (int c : node.children) {
      const auto& end = model.nodes[static_cast<std::size_t>(c)];
      if (!skin_index.count(c) && end.mesh < 0 && end.children.empty()) {
        rig.skel.end_sites[j] = checked_vec3(local_matrix(end).topRightCorner<3, 1>(), path, end.name);
        rig.skel.has_end_site[j] = 1;
      }
    }
  }
  read_root_frame(model, node_parent, rig.node_of_joint[0], path, rig);
  rig.skel.scale(rig.scale);
  rig.skel.rest_offsets[0] = rig.rotation * rig.skel.rest_offsets[0] + rig.offset;
  return rig;
}

enum class Interp { Step, Linear, Cubic };

struct Track {
  std::vector<float> times, values;  // cubic: in-tangent, value, out-tangent per key
  Interp interp = Interp::Linear;
  int accessor = -1;  // key time accessor (shared keys are one accessor)
};

Interp interpolation_of(const std::string& name, const std::string& path, const std::string& joint) {
  if (name == "STEP") return Interp::Step;
  if (name == "CUBICSPLINE") return Interp::Cubic;
  if (name.empty() || name == "LINEAR") return Interp::Linear;
  throw Error(path + ": animation channel of '" + joint + "' has unknown interpolation '" + printable_text(name) + "'");
}

// Keys and values of one channel, checked.
Track read_track(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler, bool is_tr, const std::string& path,
                 const std::string& joint) {
  Track t;
  t.interp = interpolation_of(sampler.interpolation, path, joint);
  t.accessor = sampler.input;
  t.times = read_floats(model, sampler.input, TINYGLTF_TYPE_SCALAR, path, "animation input");
  t.values = read_floats(model, sampler.output, is_tr ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, path, "animation output");
  const std::size_t per_key = (is_tr ? 3u : 4u) * (t.interp == Interp::Cubic ? 3u : 1u);
  if (t.values.size() != t.times.size() * per_key)
    throw Error(path + ": animation channel of '" + joint + "' has " + std::to_string(t.times.size()) + " key times but " +
                std::to_string(t.values.size() / (is_tr ? 3u : 4u)) + " values" +
                (t.interp == Interp::Cubic ? " (CUBICSPLINE needs 3 per key)" : ""));
  check_key_times(t.times, path, joint);
  for (float v : t.values)
    if (!std::isfinite(v) || std::abs(v) > 1e6f)
      throw Error(path + ": animation channel of '" + joint + "' has a value that is not finite or beyond 1e6");
  return t;
}

struct Tracks {
  std::vector<Track> tr, rot;
  double start = 0, end = 0;  // first and last key time over all channels
};

// Translation and rotation keys per joint of the first animation. Joints
// without a channel keep their node TRS; scale and morph weights are ignored.
Tracks read_tracks(const tinygltf::Model& model, const Rig& rig, const std::string& path) {
  Tracks out;
  out.tr.assign(static_cast<std::size_t>(rig.skel.joint_count()), {});
  out.rot.assign(static_cast<std::size_t>(rig.skel.joint_count()), {});
  if (model.animations.empty()) return out;
  const auto& anim = model.animations[0];
  out.start = std::numeric_limits<double>::infinity();
  for (const auto& ch : anim.channels) {
    auto it = rig.joint_of_node.find(ch.target_node);
    if (it == rig.joint_of_node.end() || ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size()) continue;
    const bool is_tr = ch.target_path == "translation";
    if (!is_tr && ch.target_path != "rotation") continue;
    Track& t = (is_tr ? out.tr : out.rot)[static_cast<std::size_t>(it->second)];
    t = read_track(model, anim.samplers[static_cast<std::size_t>(ch.sampler)], is_tr, path,
                   rig.skel.names[static_cast<std::size_t>(it->second)]);
    if (t.times.empty()) continue;
    out.start = std::min(out.start, static_cast<double>(t.times.front()));
    out.end = std::max(out.end, static_cast<double>(t.times.back()));
  }
  if (!(out.end >= out.start)) out.start = out.end = 0;
  return out;
}

// Value of a channel at `time`: `comps` numbers into `out`.
void eval_track(const Track& t, double time, int comps, double* out) {
  auto [k, a] = locate(t.times, time);
  const std::size_t k1 = std::min(k + 1, t.times.size() - 1);
  const auto c = static_cast<std::size_t>(comps);
  if (t.interp == Interp::Cubic) {  // glTF 2.0 Appendix C: Hermite with tangents scaled by the key spacing
    const double td = k1 > k ? static_cast<double>(t.times[k1]) - t.times[k] : 0.0;
    const double s = a, s2 = s * s, s3 = s2 * s;
    const float* v0 = &t.values[(3 * k + 1) * c];
    const float* b0 = &t.values[(3 * k + 2) * c];
    const float* v1 = &t.values[(3 * k1 + 1) * c];
    const float* a1 = &t.values[3 * k1 * c];
    for (std::size_t i = 0; i < c; ++i)
      out[i] = (2 * s3 - 3 * s2 + 1) * v0[i] + td * (s3 - 2 * s2 + s) * b0[i] + (-2 * s3 + 3 * s2) * v1[i] +
               td * (s3 - s2) * a1[i];
    return;
  }
  const float* v0 = &t.values[k * c];
  const float* v1 = &t.values[k1 * c];
  const double w = t.interp == Interp::Step ? 0.0 : a;
  if (comps == 4 && w > 0) {  // rotations: slerp
    Quat q0(v0[3], v0[0], v0[1], v0[2]), q1(v1[3], v1[0], v1[1], v1[2]);
    if (!(q0.norm() > 1e-12)) q0 = Quat::Identity();
    if (!(q1.norm() > 1e-12)) q1 = Quat::Identity();
    const Quat q = q0.normalized().slerp(w, q1.normalized());
    out[0] = q.x(), out[1] = q.y(), out[2] = q.z(), out[3] = q.w();
    return;
  }
  for (std::size_t i = 0; i < c; ++i) out[i] = (1 - w) * v0[i] + w * v1[i];
}

// Pose of every joint at `time`; joints without a channel keep their node
// pose (`pose` starts as the rest pose). The nodes above the root joint
// scale every keyed translation and move the root.
void sample_tracks(const tinygltf::Model& model, const Rig& rig, const Tracks& tracks, double time, PoseRef pose) {
  for (std::size_t ju = 0; ju < tracks.tr.size(); ++ju) {
    double v[4];
    if (!tracks.tr[ju].times.empty()) {
      eval_track(tracks.tr[ju], time, 3, v);
      pose.translations[ju] = rig.scale * Vec3(v[0], v[1], v[2]);
      if (ju == 0) pose.translations[0] = rig.rotation * pose.translations[0] + rig.offset;
    }
    if (!tracks.rot[ju].times.empty()) {
      eval_track(tracks.rot[ju], time, 4, v);
      const Quat q(v[3], v[0], v[1], v[2]);
      pose.rotations[ju] = q.coeffs().allFinite() && q.norm() > 1e-12 ? q.normalized() : Quat::Identity();
    } else {
      const auto& node = model.nodes[static_cast<std::size_t>(rig.node_of_joint[ju])];
      const Eigen::Matrix3d r = local_matrix(node).topLeftCorner<3, 3>();
      const Vec3 norms(r.col(0).norm(), r.col(1).norm(), r.col(2).norm());
      if (norms.minCoeff() > 1e-12) pose.rotations[ju] = Quat(Eigen::Matrix3d(r * norms.cwiseInverse().asDiagonal())).normalized();
    }
  }
  pose.rotations[0] = rig.rotation * pose.rotations[0];
}

// legwork's extras: {frame_rate, frames, joints, exact_view}; frame_rate 0 if absent.
struct LegworkExtras {
  double frame_rate = 0;
  int frames = 0, joints = 0, exact_view = -1;
};

LegworkExtras legwork_extras(const tinygltf::Model& model) {
  LegworkExtras out;
  if (model.animations.empty() || !model.animations[0].extras.Has("legwork")) return out;
  const auto& v = model.animations[0].extras.Get("legwork");
  auto number = [&](const char* key) { return v.Has(key) && v.Get(key).IsNumber() ? v.Get(key).GetNumberAsDouble() : -1.0; };
  const double rate = number("frame_rate"), frames = number("frames"), joints = number("joints"), view = number("exact_view");
  if (!(rate > 0 && rate <= kMaxGlbFps) || !(frames >= 1 && frames <= kMaxGlbJointPoses) || !(joints >= 1 && joints <= 65535))
    return out;
  out.frame_rate = rate;
  out.frames = static_cast<int>(frames);
  out.joints = static_cast<int>(joints);
  out.exact_view = view >= 0 && view < static_cast<double>(model.bufferViews.size()) ? static_cast<int>(view) : -1;
  return out;
}

// Key times shared by every channel (one accessor or equal values), or empty.
const std::vector<float>* shared_keys(const Tracks& tracks) {
  const std::vector<float>* keys = nullptr;
  for (const auto* list : {&tracks.tr, &tracks.rot})
    for (const Track& t : *list) {
      if (t.times.empty()) continue;
      if (!keys) keys = &t.times;
      else if (*keys != t.times) return nullptr;
    }
  return keys;
}

// Rate of evenly spaced keys (to within float rounding), or 0. A rate that a
// round number per thousand explains as well as the keys do is snapped to it.
double even_key_rate(const std::vector<float>& keys) {
  if (keys.size() < 2) return 0;
  const double t0 = keys.front(), span = static_cast<double>(keys.back()) - t0;
  const double rate = static_cast<double>(keys.size() - 1) / span;
  const double slack = 4 * std::numeric_limits<float>::epsilon() * keys.back() + 1e-9;  // float rounding of the keys
  for (std::size_t k = 0; k < keys.size(); ++k)
    if (std::abs(keys[k] - (t0 + static_cast<double>(k) / rate)) > std::max(slack, 1e-3 / rate)) return 0;
  const double snapped = std::round(rate * 1000) / 1000;
  return std::abs(snapped - rate) * span <= slack * rate ? snapped : rate;
}

// The motion from legwork's exact copy (doubles), if the file has one that fits.
bool read_exact_copy(const tinygltf::Model& model, const LegworkExtras& extras, const Rig& rig, Motion& m) {
  if (extras.exact_view < 0 || !rig.skin_order || extras.joints != rig.skel.joint_count() || extras.frames != m.frame_count())
    return false;
  const auto& view = model.bufferViews[static_cast<std::size_t>(extras.exact_view)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) return false;
  const auto& buf = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  const std::size_t poses = static_cast<std::size_t>(extras.frames) * static_cast<std::size_t>(extras.joints);
  if (view.byteOffset > buf.size() || buf.size() - view.byteOffset < view.byteLength || view.byteLength != poses * 7 * sizeof(double))
    return false;
  std::vector<double> v(poses * 7);
  std::memcpy(v.data(), buf.data() + view.byteOffset, view.byteLength);
  for (double x : v)
    if (!std::isfinite(x) || std::abs(x) > 1e6) return false;
  auto tr = m.all_translations();
  auto rot = m.all_rotations();
  for (std::size_t i = 0; i < poses; ++i) {
    const double* p = &v[7 * i];
    tr[i] = Vec3(p[0], p[1], p[2]);
    const Quat q(p[6], p[3], p[4], p[5]);
    rot[i] = q.norm() > 1e-12 ? q.normalized() : Quat::Identity();
  }
  return true;
}

tinygltf::Model load_model(std::string_view bytes, const std::string& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  gltf.SetFsCallbacks({&no_file_exists, &same_path, &refuse_external_file, &refuse_write, nullptr});
  std::string err, warn;
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw Error(path + ": larger than 4 GB");
  if (!gltf.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                 static_cast<unsigned int>(bytes.size()), "")) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw Error(path + ": cannot read glTF binary: " + printable_text(err));
  }
  return model;
}

// Sample times: the shared keys themselves when they are the frames, else
// an even grid at `fps` from the first to the last key.
struct Sampling {
  double fps = 30;
  const std::vector<float>* keys = nullptr;  // one frame per key
  double start = 0;
  double frames = 1;
};

Sampling choose_sampling(const Tracks& tracks, const LegworkExtras& extras, double fps) {
  Sampling s;
  s.start = tracks.start;
  const std::vector<float>* keys = shared_keys(tracks);
  const double key_rate = keys ? even_key_rate(*keys) : 0.0;
  const double own = extras.frame_rate > 0 ? extras.frame_rate : key_rate;
  if ((fps <= 0 || fps == own) && keys && key_rate > 0) {
    s.fps = own;
    s.keys = keys;
    s.frames = static_cast<double>(keys->size());
    return s;
  }
  s.fps = fps > 0 ? fps : own > 0 ? own : 30.0;
  s.frames = std::floor((tracks.end - tracks.start) * s.fps + 1e-3) + 1;
  return s;
}

}  // namespace

Motion parse_glb(std::string_view bytes, const std::string& path, double fps) {
  if (!(fps >= 0) || !(fps <= kMaxGlbFps)) throw Error("read_glb: fps must be 0 (the file's own) or in (0, " + std::to_string(kMaxGlbFps) + "]");
  const tinygltf::Model model = load_model(bytes, path);
  Rig rig = read_rig(model, path);
  if (model.asset.generator == "legwork") resolve_roles(rig.skel);
  else require_roles(rig.skel, path);
  const Tracks tracks = read_tracks(model, rig, path);
  const LegworkExtras extras = legwork_extras(model);
  const Sampling s = choose_sampling(tracks, extras, fps);
  // The sample count comes from the file: bound it before allocating.
  if (s.frames * rig.skel.joint_count() > kMaxGlbJointPoses)
    throw Error(path + ": the animation lasts " + std::to_string(tracks.end - tracks.start) + " s: at " + std::to_string(s.fps) +
                " fps x " + std::to_string(rig.skel.joint_count()) + " joints that is more than legwork reads (" +
                std::to_string(static_cast<long long>(kMaxGlbJointPoses)) + " joint poses)");
  const int frames = static_cast<int>(s.frames);
  Motion m(rig.skel, s.fps, frames);
  if (s.keys && extras.frame_rate == s.fps && read_exact_copy(model, extras, rig, m)) return m;
  for (int f = 0; f < frames; ++f)
    sample_tracks(model, rig, tracks, s.keys ? (*s.keys)[static_cast<std::size_t>(f)] : s.start + f / s.fps, m.frame(f));
  return m;
}

Motion read_glb(const std::string& path, double fps) { return parse_glb(read_binary_file(path), path, fps); }

}  // namespace legwork::io
