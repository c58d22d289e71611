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

  // A buffer view of raw bytes with no accessor (legwork's exact copy),
  // aligned to 8 bytes for doubles.
  int add_view(const void* data, std::size_t bytes) {
    auto& buf = model_.buffers[0].data;
    while (buf.size() % 8 != 0) buf.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = bytes;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
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

// The exact frame rate and, optionally, the motion in doubles (glTF stores
// floats): animation.extras.legwork = {frame_rate, frames, joints,
// exact_view}, the view holding per frame and joint tx ty tz qx qy qz qw.
void add_exact_copy(tinygltf::Model& model, BufferBuilder& buffers, const Motion& m, bool exact) {
  tinygltf::Value::Object info;
  info["frame_rate"] = tinygltf::Value(m.fps);
  info["frames"] = tinygltf::Value(m.frame_count());
  info["joints"] = tinygltf::Value(m.joint_count());
  if (exact) {
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(m.frame_count()) * static_cast<std::size_t>(m.joint_count()) * 7);
    const auto tr = m.all_translations();
    const auto rot = m.all_rotations();
    for (std::size_t i = 0; i < tr.size(); ++i)
      values.insert(values.end(), {tr[i].x(), tr[i].y(), tr[i].z(), rot[i].x(), rot[i].y(), rot[i].z(), rot[i].w()});
    info["exact_view"] = tinygltf::Value(buffers.add_view(values.data(), values.size() * sizeof(double)));
  }
  tinygltf::Value::Object extras;
  extras["legwork"] = tinygltf::Value(std::move(info));
  model.animations.back().extras = tinygltf::Value(std::move(extras));
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
  add_exact_copy(model, buffers, m, opt.exact_copy);
  model.buffers[0].name = "data";
  return model;
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

}  // namespace legwork::io
