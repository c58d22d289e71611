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

tinygltf::Model build_model(const Motion& m, const GltfOptions& opt) {
  const Skeleton& s = m.skeleton;
  const int n = s.joint_count();
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "legwork";
  BufferBuilder buffers(model);

  // Joint nodes in skeleton order, rest pose TRS.
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

  // Skin: the inverse bind matrix of a joint in the rest pose (identity
  // rotations) is a pure translation by minus its model-space position.
  Pose rest(s);
  std::vector<Transform> bind(static_cast<std::size_t>(n));
  forward_kinematics(s, rest, bind);
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

  tinygltf::Scene scene;
  scene.name = "legwork";
  scene.nodes.push_back(0);

  if (opt.include_mesh) {
    BoneMesh mesh;
    for (int j = 1; j < n; ++j) {
      const int p = s.parents[static_cast<std::size_t>(j)];
      mesh.add_bone(bind[static_cast<std::size_t>(p)].translation, bind[static_cast<std::size_t>(j)].translation, p);
    }
    for (int j = 0; j < n; ++j)
      if (s.has_end_site[static_cast<std::size_t>(j)])
        mesh.add_bone(bind[static_cast<std::size_t>(j)].translation, bind[static_cast<std::size_t>(j)].apply(s.end_sites[static_cast<std::size_t>(j)]), j);
    if (mesh.vertex_count() > 0) {
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
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  // Animation: one time input shared by every sampler.
  const int frames = m.frame_count();
  std::vector<float> times(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) times[static_cast<std::size_t>(f)] = static_cast<float>(f / m.fps);
  tinygltf::Animation anim;
  anim.name = opt.animation_name;
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
  model.buffers[0].name = "data";
  return model;
}

// Float elements of an accessor (any stride), checked against the expected shape.
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
  const int comps = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type));
  const int stride = acc.ByteStride(view);
  const std::size_t start = view.byteOffset + acc.byteOffset;
  if (stride <= 0 || (acc.count > 0 && start + (acc.count - 1) * static_cast<std::size_t>(stride) +
                                               static_cast<std::size_t>(comps) * sizeof(float) > buf.size()))
    throw Error(path + ": " + what + " reaches past the end of its buffer");
  std::vector<float> out(acc.count * static_cast<std::size_t>(comps));
  for (std::size_t i = 0; i < acc.count; ++i)
    std::memcpy(&out[i * static_cast<std::size_t>(comps)], buf.data() + start + i * static_cast<std::size_t>(stride),
                static_cast<std::size_t>(comps) * sizeof(float));
  return out;
}

// Index of the key segment [k, k+1] holding t and the blend factor in it.
std::pair<std::size_t, double> locate(const std::vector<float>& times, double t) {
  if (times.size() < 2 || t <= times.front()) return {0, 0.0};
  if (t >= times.back()) return {times.size() - 1, 0.0};
  const auto it = std::upper_bound(times.begin(), times.end(), static_cast<float>(t));
  const std::size_t k = static_cast<std::size_t>(it - times.begin()) - 1;
  const double span = times[k + 1] - times[k];
  return {k, span > 0 ? std::clamp((t - times[k]) / span, 0.0, 1.0) : 0.0};
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

Motion read_glb(const std::string& path, double fps) {
  if (!(fps > 0)) throw Error("read_glb: fps must be positive");
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  std::string err, warn;
  if (!gltf.LoadBinaryFromFile(&model, &err, &warn, path)) throw Error(path + ": cannot read glTF binary: " + err);
  if (model.skins.empty()) throw Error(path + ": no skin (legwork reads skeletons from the first skin)");
  const auto& joints = model.skins[0].joints;
  if (joints.empty()) throw Error(path + ": skin 0 has no joints");
  const auto node_count = static_cast<int>(model.nodes.size());
  for (int node : joints)
    if (node < 0 || node >= node_count) throw Error(path + ": skin joint refers to missing node " + std::to_string(node));
  for (const auto& node : model.nodes)
    for (int c : node.children)
      if (c < 0 || c >= node_count) throw Error(path + ": node '" + node.name + "' has a missing child " + std::to_string(c));
  std::map<int, int> joint_of_node;
  for (std::size_t j = 0; j < joints.size(); ++j) joint_of_node[joints[j]] = static_cast<int>(j);

  Skeleton skel;
  std::vector<int> parent(joints.size(), -1);
  for (std::size_t j = 0; j < joints.size(); ++j)
    for (int c : model.nodes[static_cast<std::size_t>(joints[j])].children)
      if (auto it = joint_of_node.find(c); it != joint_of_node.end()) parent[static_cast<std::size_t>(it->second)] = static_cast<int>(j);
  auto vec3_of = [](const std::vector<double>& v) { return v.size() == 3 ? Vec3(v[0], v[1], v[2]) : Vec3::Zero(); };
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const auto& node = model.nodes[static_cast<std::size_t>(joints[j])];
    if (parent[j] >= static_cast<int>(j) || (j > 0 && parent[j] < 0))
      throw Error(path + ": skin joints are not in depth-first order with a single root (joint '" + node.name + "')");
    skel.add_joint(node.name, parent[j], vec3_of(node.translation));
    // A non-joint leaf child is the End Site written by write_glb.
    for (int c : node.children)
      if (!joint_of_node.count(c) && model.nodes[static_cast<std::size_t>(c)].mesh < 0) {
        skel.end_sites[j] = vec3_of(model.nodes[static_cast<std::size_t>(c)].translation);
        skel.has_end_site[j] = 1;
      }
  }
  resolve_roles(skel);

  // Keys per joint; joints without a channel keep their node TRS.
  const int n = skel.joint_count();
  struct Track {
    std::vector<float> times, values;
  };
  std::vector<Track> tr(static_cast<std::size_t>(n)), rot(static_cast<std::size_t>(n));
  double duration = 0;
  if (!model.animations.empty()) {
    const auto& anim = model.animations[0];
    for (const auto& ch : anim.channels) {
      auto it = joint_of_node.find(ch.target_node);
      if (it == joint_of_node.end() || ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size()) continue;
      const auto& sampler = anim.samplers[static_cast<std::size_t>(ch.sampler)];
      const bool is_tr = ch.target_path == "translation";
      if (!is_tr && ch.target_path != "rotation") continue;
      Track& t = (is_tr ? tr : rot)[static_cast<std::size_t>(it->second)];
      t.times = read_floats(model, sampler.input, TINYGLTF_TYPE_SCALAR, path, "animation input");
      t.values = read_floats(model, sampler.output, is_tr ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, path, "animation output");
      if (t.values.size() != t.times.size() * (is_tr ? 3u : 4u))
        throw Error(path + ": animation channel of '" + skel.names[static_cast<std::size_t>(it->second)] +
                    "' has a different number of times and values (only LINEAR/STEP samplers are read)");
      if (!t.times.empty()) duration = std::max(duration, static_cast<double>(t.times.back()));
    }
  }
  const int frames = static_cast<int>(std::floor(duration * fps + 1e-3)) + 1;
  Motion m(skel, fps, frames);
  for (int f = 0; f < frames; ++f) {
    const double time = f / fps;
    PoseRef pose = m.frame(f);
    for (int j = 0; j < n; ++j) {
      const auto ju = static_cast<std::size_t>(j);
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
        const Quat q0(v0[3], v0[0], v0[1], v0[2]), q1(v1[3], v1[0], v1[1], v1[2]);
        pose.rotations[ju] = q0.normalized().slerp(a, q1.normalized());
      } else {
        const auto& r = model.nodes[static_cast<std::size_t>(joints[ju])].rotation;
        if (r.size() == 4) pose.rotations[ju] = Quat(r[3], r[0], r[1], r[2]).normalized();
      }
    }
  }
  return m;
}

}  // namespace legwork::io
