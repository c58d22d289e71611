// glTF 2.0 binary export/import of a skeleton + animation via tinygltf.
// Layout written (and expected back by read_glb):
//   nodes 0..n-1   joints, in skeleton order, TRS = rest pose
//   nodes n..      "<joint>_end" leaves for BVH End Sites (not skin joints;
//                  they give viewers the direction of leaf bones)
//   last node      the skinned bone mesh (no transform, as glTF requires)
//   skin 0         all joints, inverse bind matrices of the rest pose
//   animation 0    one shared time input, translation + rotation per joint
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <legwork/core/fk.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <limits>
#include <map>
#include <sstream>

namespace legwork::io {

namespace {

// Appends typed arrays to the single binary buffer, one buffer view each.
class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& model) : model_(model) {
    model_.buffers.emplace_back();
  }

  // Adds `count` elements of `type` (float or unsigned short components).
  template <typename T>
  int add_accessor(const std::vector<T>& data, int component_type, int type, std::size_t count, int target = 0) {
    auto& buf = model_.buffers[0].data;
    while (buf.size() % 4 != 0) buf.push_back(0);  // accessors must be aligned to their component size
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = data.size() * sizeof(T);
    view.target = target;
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
    buf.insert(buf.end(), bytes, bytes + view.byteLength);
    model_.bufferViews.push_back(view);

    tinygltf::Accessor acc;
    acc.bufferView = static_cast<int>(model_.bufferViews.size()) - 1;
    acc.byteOffset = 0;
    acc.componentType = component_type;
    acc.type = type;
    acc.count = count;
    model_.accessors.push_back(acc);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  // Float accessor with min/max per component (required for POSITION and animation inputs).
  int add_floats(const std::vector<float>& data, int type, int components, int target = 0, bool bounds = false) {
    const std::size_t count = data.size() / static_cast<std::size_t>(components);
    const int a = add_accessor(data, TINYGLTF_COMPONENT_TYPE_FLOAT, type, count, target);
    if (bounds && count > 0) {
      auto& acc = model_.accessors[static_cast<std::size_t>(a)];
      acc.minValues.assign(static_cast<std::size_t>(components), 1e300);
      acc.maxValues.assign(static_cast<std::size_t>(components), -1e300);
      for (std::size_t i = 0; i < data.size(); ++i) {
        const auto c = i % static_cast<std::size_t>(components);
        acc.minValues[c] = std::min(acc.minValues[c], static_cast<double>(data[i]));
        acc.maxValues[c] = std::max(acc.maxValues[c], static_cast<double>(data[i]));
      }
    }
    return a;
  }

 private:
  tinygltf::Model& model_;
};

void push(std::vector<float>& out, const Vec3& v) {
  for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(v[k]));
}

// A slim double pyramid ("octahedral bone") from head to tail, flat-shaded
// (vertices duplicated per face), skinned 100% to `joint`.
struct BoneMesh {
  std::vector<float> positions, normals, weights;
  std::vector<unsigned short> joints;

  void add_bone(const Vec3& head, const Vec3& tail, int joint) {
    const Vec3 d = tail - head;
    const double len = d.norm();
    if (len < 1e-4) return;  // zero-length bones (CMU's branch points) show nothing
    const Vec3 dir = d / len;
    const Vec3 u = dir.unitOrthogonal();
    const Vec3 v = dir.cross(u);
    const double r = std::min(0.1 * len, 0.03);
    const Vec3 mid = head + 0.2 * d;
    const Vec3 ring[4] = {mid + r * u, mid + r * v, mid - r * u, mid - r * v};
    for (int k = 0; k < 4; ++k) {
      const Vec3& a = ring[k];
      const Vec3& b = ring[(k + 1) % 4];
      add_triangle(head, b, a, joint);
      add_triangle(a, b, tail, joint);
    }
  }

  void add_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int joint) {
    Vec3 n = (b - a).cross(c - a);
    n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitY();
    for (const Vec3* p : {&a, &b, &c}) {
      push(positions, *p);
      push(normals, n);
      joints.insert(joints.end(), {static_cast<unsigned short>(joint), 0, 0, 0});
      weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    }
  }
  std::size_t vertex_count() const { return positions.size() / 3; }
};

void check_writable(const Motion& m) {
  if (m.frame_count() == 0) throw Error("write_glb: the motion has no frames");
  if (m.joint_count() == 0) throw Error("write_glb: the skeleton has no joints");
  if (m.joint_count() > 65535) throw Error("write_glb: more than 65535 joints");
  if (!(m.fps > 0) || !std::isfinite(m.fps)) throw Error("write_glb: frame rate must be positive");
  m.skeleton.validate();
  for (const Vec3& t : m.all_translations())
    if (!t.allFinite()) throw Error("write_glb: the motion has a non-finite joint translation");
  for (const Quat& q : m.all_rotations())
    if (!q.coeffs().allFinite() || q.norm() < 1e-9) throw Error("write_glb: the motion has an invalid joint rotation");
}

// Joint nodes in skeleton order (rest pose TRS), then one tip node per end site.
void add_joint_nodes(tinygltf::Model& model, const Skeleton& s) {
  const int n = s.joint_count();
  for (int j = 0; j < n; ++j) {
    tinygltf::Node node;
    node.name = s.names[static_cast<std::size_t>(j)];
    const Vec3& o = s.rest_offsets[static_cast<std::size_t>(j)];
    node.translation = {o.x(), o.y(), o.z()};
    model.nodes.push_back(node);
  }
  for (int j = 1; j < n; ++j) model.nodes[static_cast<std::size_t>(s.parents[static_cast<std::size_t>(j)])].children.push_back(j);
  for (int j = 0; j < n; ++j) {
    if (!s.has_end_site[static_cast<std::size_t>(j)]) continue;
    tinygltf::Node tip;
    tip.name = s.names[static_cast<std::size_t>(j)] + "_end";
    const Vec3& e = s.end_sites[static_cast<std::size_t>(j)];
    tip.translation = {e.x(), e.y(), e.z()};
    model.nodes.push_back(tip);
    model.nodes[static_cast<std::size_t>(j)].children.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
}

// Skin: the inverse bind matrix of a joint in the rest pose (identity
// rotations) is a pure translation by minus its model-space position.
void add_skin(tinygltf::Model& model, BufferBuilder& buffers, const Skeleton& s, std::span<const Transform> bind) {
  const int n = s.joint_count();
  std::vector<float> ibm;
  ibm.reserve(static_cast<std::size_t>(n) * 16);
  for (int j = 0; j < n; ++j) {
    const Vec3 p = bind[static_cast<std::size_t>(j)].translation;
    const float col_major[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0,
                                 static_cast<float>(-p.x()), static_cast<float>(-p.y()), static_cast<float>(-p.z()), 1};
    ibm.insert(ibm.end(), col_major, col_major + 16);
  }
  tinygltf::Skin skin;
  skin.name = "skeleton";
  skin.skeleton = 0;
  for (int j = 0; j < n; ++j) skin.joints.push_back(j);
  skin.inverseBindMatrices = buffers.add_floats(ibm, TINYGLTF_TYPE_MAT4, 16);
  model.skins.push_back(skin);
}

// A skinned bone mesh (one pyramid pair per bone) so viewers show a body.
void add_bone_mesh(tinygltf::Model& model, BufferBuilder& buffers, const Skeleton& s, std::span<const Transform> bind,
                   tinygltf::Scene& scene) {
  const int n = s.joint_count();
  BoneMesh mesh;
  for (int j = 1; j < n; ++j) {
    const int p = s.parents[static_cast<std::size_t>(j)];
    mesh.add_bone(bind[static_cast<std::size_t>(p)].translation, bind[static_cast<std::size_t>(j)].translation, p);
  }
  for (int j = 0; j < n; ++j)
    if (s.has_end_site[static_cast<std::size_t>(j)])
      mesh.add_bone(bind[static_cast<std::size_t>(j)].translation, bind[static_cast<std::size_t>(j)].apply(s.end_sites[static_cast<std::size_t>(j)]), j);
  if (mesh.vertex_count() == 0) return;
  tinygltf::Material mat;
  mat.name = "bone";
  mat.pbrMetallicRoughness.baseColorFactor = {0.8, 0.55, 0.3, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 0.7;
  model.materials.push_back(mat);

  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = 0;
  prim.attributes["POSITION"] = buffers.add_floats(mesh.positions, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  prim.attributes["NORMAL"] = buffers.add_floats(mesh.normals, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["JOINTS_0"] = buffers.add_accessor(mesh.joints, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4,
                                                     mesh.vertex_count(), TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["WEIGHTS_0"] = buffers.add_floats(mesh.weights, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER);
  tinygltf::Mesh gm;
  gm.name = "bones";
  gm.primitives.push_back(prim);
  model.meshes.push_back(gm);

  tinygltf::Node mesh_node;
  mesh_node.name = "bones";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  model.nodes.push_back(mesh_node);
  scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
}

// Animation: one time input shared by every sampler; per joint a translation
// and a rotation channel.
void add_animation(tinygltf::Model& model, BufferBuilder& buffers, const Motion& m, const std::string& name) {
  const int n = m.joint_count();
  const int frames = m.frame_count();
  std::vector<float> times(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) times[static_cast<std::size_t>(f)] = static_cast<float>(f / m.fps);
  tinygltf::Animation anim;
  anim.name = name;
  const int input = buffers.add_floats(times, TINYGLTF_TYPE_SCALAR, 1, 0, true);
  for (int j = 0; j < n; ++j) {
    std::vector<float> tr, rot;
    tr.reserve(static_cast<std::size_t>(frames) * 3);
    rot.reserve(static_cast<std::size_t>(frames) * 4);
    Quat prev = Quat::Identity();
    for (int f = 0; f < frames; ++f) {
      auto pose = m.frame(f);
      push(tr, pose.translations[static_cast<std::size_t>(j)]);
      Quat q = pose.rotations[static_cast<std::size_t>(j)].normalized();
      if (f > 0 && q.dot(prev) < 0) q.coeffs() = -q.coeffs();  // same hemisphere: interpolation takes the short way
      prev = q;
      rot.insert(rot.end(), {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
                             static_cast<float>(q.w())});
    }
    for (const char* path : {"translation", "rotation"}) {
      tinygltf::AnimationSampler sampler;
      sampler.input = input;
      sampler.interpolation = "LINEAR";
      sampler.output = std::strcmp(path, "translation") == 0 ? buffers.add_floats(tr, TINYGLTF_TYPE_VEC3, 3)
                                                             : buffers.add_floats(rot, TINYGLTF_TYPE_VEC4, 4);
      anim.samplers.push_back(sampler);
      tinygltf::AnimationChannel ch;
      ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
      ch.target_node = j;
      ch.target_path = path;
      anim.channels.push_back(ch);
    }
  }
  model.animations.push_back(anim);
}

tinygltf::Model build_model(const Motion& m, const GltfOptions& opt) {
  const Skeleton& s = m.skeleton;
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "legwork";
  BufferBuilder buffers(model);
  add_joint_nodes(model, s);
  Pose rest(s);
  std::vector<Transform> bind(static_cast<std::size_t>(s.joint_count()));
  forward_kinematics(s, rest, bind);
  add_skin(model, buffers, s, bind);
  tinygltf::Scene scene;
  scene.name = "legwork";
  scene.nodes.push_back(0);
  if (opt.include_mesh) add_bone_mesh(model, buffers, s, bind, scene);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  add_animation(model, buffers, m, opt.animation_name);
  model.buffers[0].name = "data";
  return model;
}

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

}  // namespace

void write_glb(const std::string& path, const Motion& m, const GltfOptions& opt) {
  check_writable(m);
  const tinygltf::Model model = build_model(m, opt);
  tinygltf::TinyGLTF gltf;
  // Serialise to memory first: tinygltf's file writer does not report open failures.
  std::ostringstream bytes;
  if (!gltf.WriteGltfSceneToStream(&model, bytes, /*prettyPrint=*/false, /*writeBinary=*/true))
    throw Error(path + ": cannot encode the glTF binary");
  write_text_file(path, bytes.str());
}

namespace {

// Deeper nesting than this is not a body (the BVH reader's limit too).
constexpr int kMaxGlbDepth = 256;

// Skeleton of the first skin: joints in depth-first order with a single root.
Skeleton read_skin_skeleton(const tinygltf::Model& model, const std::string& path, std::map<int, int>& joint_of_node) {
  if (model.skins.empty()) throw Error(path + ": no skin (legwork reads skeletons from the first skin)");
  const auto& joints = model.skins[0].joints;
  if (joints.empty()) throw Error(path + ": skin 0 has no joints");
  const auto node_count = static_cast<int>(model.nodes.size());
  for (int node : joints)
    if (node < 0 || node >= node_count) throw Error(path + ": skin joint refers to missing node " + std::to_string(node));
  for (const auto& node : model.nodes)
    for (int c : node.children)
      if (c < 0 || c >= node_count) throw Error(path + ": node '" + node.name + "' has a missing child " + std::to_string(c));
  for (std::size_t j = 0; j < joints.size(); ++j)
    if (!joint_of_node.emplace(joints[j], static_cast<int>(j)).second)
      throw Error(path + ": skin lists node " + std::to_string(joints[j]) + " twice");

  Skeleton skel;
  std::vector<int> parent(joints.size(), -1);
  for (std::size_t j = 0; j < joints.size(); ++j)
    for (int c : model.nodes[static_cast<std::size_t>(joints[j])].children)
      if (auto it = joint_of_node.find(c); it != joint_of_node.end()) parent[static_cast<std::size_t>(it->second)] = static_cast<int>(j);
  auto vec3_of = [&](const std::vector<double>& v, const std::string& name) {
    if (v.size() != 3) return Vec3::Zero().eval();
    const Vec3 out(v[0], v[1], v[2]);
    if (!out.allFinite() || out.cwiseAbs().maxCoeff() > 1e6)
      throw Error(path + ": node '" + name + "' has a translation that is not finite or beyond 1000 km");
    return out;
  };
  std::vector<int> depth(joints.size(), 0);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const auto& node = model.nodes[static_cast<std::size_t>(joints[j])];
    if (parent[j] >= static_cast<int>(j) || (j > 0 && parent[j] < 0))
      throw Error(path + ": skin joints are not in depth-first order with a single root (joint '" + node.name + "')");
    if (j > 0 && (depth[j] = depth[static_cast<std::size_t>(parent[j])] + 1) > kMaxGlbDepth)
      throw Error(path + ": joint '" + node.name + "' is nested more than " + std::to_string(kMaxGlbDepth) + " deep");
    skel.add_joint(node.name, parent[j], vec3_of(node.translation, node.name));
    // A non-joint leaf child is the End Site written by write_glb.
    for (int c : node.children)
      if (!joint_of_node.count(c) && model.nodes[static_cast<std::size_t>(c)].mesh < 0) {
        const auto& end = model.nodes[static_cast<std::size_t>(c)];
        skel.end_sites[j] = vec3_of(end.translation, end.name);
        skel.has_end_site[j] = 1;
      }
  }
  resolve_roles(skel);
  return skel;
}

struct Track {
  std::vector<float> times, values;
};

// Translation and rotation keys per joint of the first animation; returns the
// last key time. Joints without a channel keep their node TRS.
double read_tracks(const tinygltf::Model& model, const Skeleton& skel, const std::map<int, int>& joint_of_node,
                   const std::string& path, std::vector<Track>& tr, std::vector<Track>& rot) {
  tr.assign(static_cast<std::size_t>(skel.joint_count()), {});
  rot.assign(static_cast<std::size_t>(skel.joint_count()), {});
  double duration = 0;
  if (model.animations.empty()) return duration;
  const auto& anim = model.animations[0];
  for (const auto& ch : anim.channels) {
    auto it = joint_of_node.find(ch.target_node);
    if (it == joint_of_node.end() || ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size()) continue;
    const auto& sampler = anim.samplers[static_cast<std::size_t>(ch.sampler)];
    const bool is_tr = ch.target_path == "translation";
    if (!is_tr && ch.target_path != "rotation") continue;
    const std::string& joint = skel.names[static_cast<std::size_t>(it->second)];
    Track& t = (is_tr ? tr : rot)[static_cast<std::size_t>(it->second)];
    t.times = read_floats(model, sampler.input, TINYGLTF_TYPE_SCALAR, path, "animation input");
    t.values = read_floats(model, sampler.output, is_tr ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, path, "animation output");
    if (t.values.size() != t.times.size() * (is_tr ? 3u : 4u))
      throw Error(path + ": animation channel of '" + joint +
                  "' has a different number of times and values (only LINEAR/STEP samplers are read)");
    check_key_times(t.times, path, joint);
    for (float v : t.values)
      if (!std::isfinite(v) || std::abs(v) > 1e6f)
        throw Error(path + ": animation channel of '" + joint + "' has a value that is not finite or beyond 1e6");
    if (!t.times.empty()) duration = std::max(duration, static_cast<double>(t.times.back()));
  }
  return duration;
}

// Pose of every joint at `time` from its keys (LINEAR).
void sample_tracks(const tinygltf::Model& model, const std::vector<Track>& tr, const std::vector<Track>& rot,
                   double time, PoseRef pose) {
  const auto& joints = model.skins[0].joints;
  for (std::size_t ju = 0; ju < tr.size(); ++ju) {
    if (!tr[ju].times.empty()) {
      auto [k, a] = locate(tr[ju].times, time);
      const std::size_t k1 = std::min(k + 1, tr[ju].times.size() - 1);
      const float* v0 = &tr[ju].values[3 * k];
      const float* v1 = &tr[ju].values[3 * k1];
      for (int c = 0; c < 3; ++c) pose.translations[ju][c] = (1 - a) * v0[c] + a * v1[c];
    }
    if (!rot[ju].times.empty()) {
      auto [k, a] = locate(rot[ju].times, time);
      const std::size_t k1 = std::min(k + 1, rot[ju].times.size() - 1);
      const float* v0 = &rot[ju].values[4 * k];
      const float* v1 = &rot[ju].values[4 * k1];
      Quat q0(v0[3], v0[0], v0[1], v0[2]), q1(v1[3], v1[0], v1[1], v1[2]);
      // A zero quaternion has no direction: identity rather than NaN.
      if (!(q0.norm() > 1e-12)) q0 = Quat::Identity();
      if (!(q1.norm() > 1e-12)) q1 = Quat::Identity();
      pose.rotations[ju] = q0.normalized().slerp(a, q1.normalized());
    } else {
      const auto& r = model.nodes[static_cast<std::size_t>(joints[ju])].rotation;
      if (r.size() == 4) {
        const Quat q(r[3], r[0], r[1], r[2]);
        pose.rotations[ju] = q.coeffs().allFinite() && q.norm() > 1e-12 ? q.normalized() : Quat::Identity();
      }
    }
  }
}

}  // namespace

Motion parse_glb(std::string_view bytes, const std::string& path, double fps) {
  if (!(fps > 0) || !(fps <= kMaxGlbFps)) throw Error("read_glb: fps must be in (0, " + std::to_string(kMaxGlbFps) + "]");
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
  std::map<int, int> joint_of_node;
  const Skeleton skel = read_skin_skeleton(model, path, joint_of_node);
  std::vector<Track> tr, rot;
  const double duration = read_tracks(model, skel, joint_of_node, path, tr, rot);
  // The sample count comes from the file: bound it before allocating.
  const double samples = std::floor(duration * fps + 1e-3) + 1;
  if (samples * skel.joint_count() > kMaxGlbJointPoses)
    throw Error(path + ": the animation lasts " + std::to_string(duration) + " s: at " + std::to_string(fps) +
                " fps x " + std::to_string(skel.joint_count()) + " joints that is more than legwork reads (" +
                std::to_string(static_cast<long long>(kMaxGlbJointPoses)) + " joint poses)");
  const int frames = static_cast<int>(samples);
  Motion m(skel, fps, frames);
  for (int f = 0; f < frames; ++f) sample_tracks(model, tr, rot, f / fps, m.frame(f));
  return m;
}

Motion read_glb(const std::string& path, double fps) { return parse_glb(read_binary_file(path), path, fps); }

}  // namespace legwork::io
