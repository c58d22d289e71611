// GLB import: legwork's own files come back exactly (BVH -> GLB -> BVH on
// real CMU clips at 120 and 60 Hz), other tools' skins and animations are
// read when the rig resolves to roles (assets built here with tinygltf).
#include <tiny_gltf.h>

#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

using namespace legwork;

namespace {

// Per process: ctest runs each test in its own process, two at a time, and two
// tests writing the same clip's file raced (fresh-clone ctest, session 10).
std::string reader_temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)).string();
}

// The numbers of a BVH text's MOTION section after the Frame Time line.
std::vector<double> motion_numbers(const std::string& text) {
  const auto at = text.find("Frame Time:");
  std::istringstream in(text.substr(text.find('\n', at) + 1));
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

std::string frame_time_line(const std::string& text) {
  const auto at = text.find("Frame Time:");
  return text.substr(at, text.find('\n', at) - at);
}

// BVH file -> GLB -> Motion -> BVH text in the file's own units and channel layout.
struct RoundTrip {
  io::BvhFile original;
  Motion back;
  std::string bvh_text;
};

RoundTrip bvh_glb_bvh(const std::filesystem::path& bvh, bool exact_copy) {
  RoundTrip r;
  r.original = io::read_bvh(bvh.string());
  const std::string glb = reader_temp("legwork_rt_" + bvh.stem().string() + ".glb");
  io::GltfOptions opt;
  opt.exact_copy = exact_copy;
  io::write_glb(glb, r.original.motion, opt);
  r.back = io::read_glb(glb);
  std::filesystem::remove(glb);
  io::BvhWriteOptions w;
  w.scale = 1.0 / r.original.report.scale;
  w.channels = r.original.channels;
  if (exact_copy) r.bvh_text = io::format_bvh(r.back, w);
  return r;
}

// Frames, frame time and every channel value equal to 1e-6.
void expect_exact_round_trip(const std::filesystem::path& bvh) {
  SCOPED_TRACE(bvh.string());
  const RoundTrip r = bvh_glb_bvh(bvh, true);
  const std::string text = io::read_text_file(bvh.string());
  ASSERT_EQ(r.back.frame_count(), r.original.motion.frame_count());
  EXPECT_NEAR(r.back.frame_time(), r.original.motion.frame_time(), 1e-12);
  EXPECT_NEAR(std::stod(frame_time_line(r.bvh_text).substr(11)), std::stod(frame_time_line(text).substr(11)), 1e-6);
  const auto a = motion_numbers(text);
  const auto b = motion_numbers(r.bvh_text);
  ASSERT_EQ(a.size(), b.size());
  // Which numbers of a frame are angles (-180 and 180 degrees are one angle).
  std::vector<bool> angle;
  for (const auto& joint : r.original.channels)
    for (io::Channel c : joint.channels) angle.push_back(c >= io::Channel::Xrotation);
  ASSERT_EQ(a.size() % angle.size(), 0u);
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = std::abs(a[i] - b[i]);
    worst = std::max(worst, angle[i % angle.size()] ? std::min(d, std::abs(d - 360)) : d);
  }
  EXPECT_LE(worst, 1e-6) << "worst channel difference (file units / degrees)";
}

}  // namespace

TEST(GltfReader, BvhGlbBvhIsExactOnSampleClipsAt120And60Hz) {
  expect_exact_round_trip(testdata::sample("cmu/bvh/walking/07_01.bvh"));   // 120 Hz, 317 frames
  expect_exact_round_trip(testdata::sample("cmu/bvh/swimming/79_02.bvh"));  // 60 Hz
  expect_exact_round_trip(testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh"));  // DAZ layout
}

TEST(GltfReader, BvhGlbBvhIsExactOnSharedClips) {
  LEGWORK_REQUIRE_SHARED_CMU();
  // The first two trials at each frame time in the manifest.
  std::ifstream manifest(testdata::shared_cmu() / "MANIFEST.tsv");
  std::string line;
  std::getline(manifest, line);
  std::map<std::string, int> taken;
  while (std::getline(manifest, line)) {
    std::istringstream cols(line);
    std::vector<std::string> f;
    for (std::string c; std::getline(cols, c, '\t');) f.push_back(c);
    if (f.size() < 6 || taken[f[5]] >= 2) continue;
    ++taken[f[5]];
    expect_exact_round_trip(testdata::shared_cmu() / f[0]);
  }
  EXPECT_GE(taken[".0166667"], 1) << "no 60 Hz clip in the manifest";
  EXPECT_GE(taken[".0083333"], 1) << "no 120 Hz clip in the manifest";
}

TEST(GltfReader, FloatChannelsAloneKeepFramesAndRate) {
  // What another tool sees (no exact copy): one frame per key, the rate
  // written, values within float rounding.
  for (const char* clip : {"cmu/bvh/walking/07_01.bvh", "cmu/bvh/swimming/79_02.bvh"}) {
    SCOPED_TRACE(clip);
    const RoundTrip r = bvh_glb_bvh(testdata::sample(clip), false);
    ASSERT_EQ(r.back.frame_count(), r.original.motion.frame_count());
    EXPECT_NEAR(r.back.frame_time(), r.original.motion.frame_time(), 1e-12);
    const auto a = joint_positions(r.original.motion);
    const auto b = joint_positions(r.back);
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
    EXPECT_LT(worst, 1e-5) << "worst joint position difference (m)";
  }
}

// ---- Files from other tools, built here with tinygltf --------------------

namespace {

// How a foreign exporter lays out a skinned animation of a legwork motion.
struct Foreign {
  std::string prefix = "mixamorig:";  // joint names: prefix + CMU name
  double armature_scale = 0.01;      // an "Armature" node above the root (cm rig in a metre scene)
  Quat armature_rotation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitY()));
  bool armature_as_matrix = false;
  bool reverse_skin = true;           // skin joints listed children first
  bool rotation_only = true;          // translation channel on the root only
  std::string interpolation = "LINEAR";
  std::vector<std::string> names;     // replaces the joint names if not empty
};

int add_floats(tinygltf::Model& model, const std::vector<float>& v, int type) {
  auto& buf = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = v.size() * sizeof(float);
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  buf.insert(buf.end(), p, p + view.byteLength);
  model.bufferViews.push_back(view);
  tinygltf::Accessor acc;
  acc.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  acc.type = type;
  acc.count = v.size() / static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<uint32_t>(type)));
  if (type == TINYGLTF_TYPE_SCALAR) acc.minValues = {v.front()}, acc.maxValues = {v.back()};
  model.accessors.push_back(acc);
  return static_cast<int>(model.accessors.size()) - 1;
}

// One channel's output: per key the value, or for CUBICSPLINE zero tangents around it.
std::vector<float> channel_values(const Motion& m, int j, bool tr, bool cubic) {
  std::vector<float> out;
  const int comps = tr ? 3 : 4;
  for (int f = 0; f < m.frame_count(); ++f) {
    const auto pose = m.frame(f);
    const auto& q = pose.rotations[static_cast<std::size_t>(j)];
    const Vec3& t = pose.translations[static_cast<std::size_t>(j)];
    const double v[4] = {tr ? t.x() : q.x(), tr ? t.y() : q.y(), tr ? t.z() : q.z(), q.w()};
    if (cubic) out.insert(out.end(), static_cast<std::size_t>(comps), 0.0f);
    for (int c = 0; c < comps; ++c) out.push_back(static_cast<float>(v[c]));
    if (cubic) out.insert(out.end(), static_cast<std::size_t>(comps), 0.0f);
  }
  return out;
}

void add_channel(tinygltf::Model& model, tinygltf::Animation& anim, int input, int node, const char* path,
                 std::vector<float> values, const std::string& interpolation) {
  tinygltf::AnimationSampler s;
  s.input = input;
  s.output = add_floats(model, values, std::string(path) == "translation" ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4);
  s.interpolation = interpolation;
  anim.samplers.push_back(s);
  tinygltf::AnimationChannel ch;
  ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
  ch.target_node = node;
  ch.target_path = path;
  anim.channels.push_back(ch);
}

// Node 0 "Armature", joints at node 1 + j; the root's keys are expressed
// inside the armature so that the world pose equals `m`'s.
std::string foreign_glb(const Motion& in, const Foreign& opt) {
  Motion m = in;
  const double s = opt.armature_scale;
  const Quat r_inv = opt.armature_rotation.conjugate();
  for (int f = 0; f < m.frame_count(); ++f) {
    auto pose = m.frame(f);
    for (auto& t : pose.translations) t /= s;
    pose.translations[0] = r_inv * pose.translations[0];
    pose.rotations[0] = r_inv * pose.rotations[0];
  }
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Khronos glTF Blender I/O";
  model.buffers.emplace_back();
  tinygltf::Node armature;
  armature.name = "Armature";
  const Quat& q = opt.armature_rotation;
  if (opt.armature_as_matrix) {
    Eigen::Matrix4d a = Eigen::Matrix4d::Identity();
    a.topLeftCorner<3, 3>() = s * q.toRotationMatrix();
    armature.matrix.assign(a.data(), a.data() + 16);
  } else {
    armature.scale = {s, s, s};
    armature.rotation = {q.x(), q.y(), q.z(), q.w()};
  }
  model.nodes.push_back(armature);
  const int n = m.joint_count();
  for (int j = 0; j < n; ++j) {
    tinygltf::Node node;
    node.name = opt.names.empty() ? opt.prefix + m.skeleton.names[static_cast<std::size_t>(j)] : opt.names[static_cast<std::size_t>(j)];
    const Vec3 o = m.frame(0).translations[static_cast<std::size_t>(j)];
    node.translation = {o.x(), o.y(), o.z()};
    const int p = m.skeleton.parents[static_cast<std::size_t>(j)];
    model.nodes[static_cast<std::size_t>(p + 1)].children.push_back(j + 1);
    model.nodes.push_back(node);
  }
  tinygltf::Skin skin;
  for (int j = 0; j < n; ++j) skin.joints.push_back(opt.reverse_skin ? n - j : j + 1);
  model.skins.push_back(skin);
  std::vector<float> times;
  for (int f = 0; f < m.frame_count(); ++f) times.push_back(static_cast<float>(f / m.fps));
  tinygltf::Animation anim;
  const int input = add_floats(model, times, TINYGLTF_TYPE_SCALAR);
  const bool cubic = opt.interpolation == "CUBICSPLINE";
  for (int j = 0; j < n; ++j) {
    if (j == 0 || !opt.rotation_only) add_channel(model, anim, input, j + 1, "translation", channel_values(m, j, true, cubic), opt.interpolation);
    add_channel(model, anim, input, j + 1, "rotation", channel_values(m, j, false, cubic), opt.interpolation);
  }
  model.animations.push_back(anim);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  std::ostringstream bytes;
  tinygltf::TinyGLTF gltf;
  EXPECT_TRUE(gltf.WriteGltfSceneToStream(&model, bytes, false, true));
  return bytes.str();
}

const Motion& walk() {
  static const Motion m = [] {
    const Motion full = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
    Motion out(full.skeleton, full.fps, 0);
    for (int f = 0; f < 40; ++f) out.push_back(full.frame(f));
    return out;
  }();
  return m;
}

// Worst world joint position difference (m) between a motion read from a
// foreign file and `ref`, joints matched by name without the exporter's prefix.
double worst_position_error(const Motion& read, const Motion& ref, const std::string& prefix = "mixamorig:") {
  if (read.frame_count() != ref.frame_count() || read.joint_count() != ref.joint_count()) return 1e9;
  double worst = 0;
  for (int f = 0; f < ref.frame_count(); ++f) {
    const auto pa = joint_positions(read.skeleton, read.frame(f));
    const auto pb = joint_positions(ref.skeleton, ref.frame(f));
    for (int j = 0; j < read.joint_count(); ++j) {
      const int k = ref.skeleton.find(read.skeleton.names[static_cast<std::size_t>(j)].substr(prefix.size()));
      if (k < 0) return 1e9;
      worst = std::max(worst, (pa[static_cast<std::size_t>(j)] - pb[static_cast<std::size_t>(k)]).norm());
    }
  }
  return worst;
}

std::string read_error(const std::string& bytes) {
  try {
    io::parse_glb(bytes, "foreign.glb");
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(GltfReader, BlenderStyleRigReadsBackTheWorldPose) {
  // Mixamo names, a centimetre armature scaled by 0.01 and turned, skin
  // joints listed children first, rotation-only channels below the root.
  const Motion m = io::parse_glb(foreign_glb(walk(), {}), "blender.glb");
  ASSERT_EQ(m.frame_count(), walk().frame_count());
  EXPECT_NEAR(m.fps, walk().fps, 1e-3);
  EXPECT_EQ(m.skeleton.names[0], "mixamorig:Hips");
  EXPECT_EQ(m.skeleton.names[static_cast<std::size_t>(m.skeleton.roles[Role::LeftKnee])], "mixamorig:LeftLeg");
  EXPECT_LT(worst_position_error(m, walk()), 1e-5);
}

TEST(GltfReader, ThreeJsStyleNamesAndMatrixNodesResolve) {
  // three.js drops ':' from node names ("mixamorigHips") and may write matrices.
  Foreign opt;
  opt.prefix = "mixamorig";
  opt.armature_as_matrix = true;
  opt.reverse_skin = false;
  opt.rotation_only = false;
  const Motion m = io::parse_glb(foreign_glb(walk(), opt), "three.glb");
  EXPECT_EQ(m.skeleton.roles[Role::RightAnkle], m.skeleton.find("mixamorigRightFoot"));
  EXPECT_LT(worst_position_error(m, walk(), "mixamorig"), 1e-5);
}

TEST(GltfReader, StepKeysHoldBetweenKeys) {
  Foreign opt;
  opt.interpolation = "STEP";
  const std::string bytes = foreign_glb(walk(), opt);
  const Motion keys = io::parse_glb(bytes, "step.glb");
  EXPECT_LT(worst_position_error(keys, walk()), 1e-5);
  const Motion doubled = io::parse_glb(bytes, "step.glb", 2 * keys.fps);  // a sample between every two keys
  ASSERT_EQ(doubled.frame_count(), 2 * keys.frame_count() - 1);
  for (int f = 0; f + 1 < keys.frame_count(); ++f)
    EXPECT_LT((joint_positions(doubled.skeleton, doubled.frame(2 * f + 1))[5] - joint_positions(keys.skeleton, keys.frame(f))[5]).norm(), 1e-6)
        << "frame " << f;
}

TEST(GltfReader, CubicSplineKeysAreHermite) {
  Foreign opt;
  opt.interpolation = "CUBICSPLINE";
  opt.rotation_only = false;
  const std::string bytes = foreign_glb(walk(), opt);
  const Motion keys = io::parse_glb(bytes, "cubic.glb");
  EXPECT_LT(worst_position_error(keys, walk()), 1e-5);
  // Zero tangents: half way between keys is the mean of the two (Hermite at s = 1/2).
  const Motion doubled = io::parse_glb(bytes, "cubic.glb", 2 * keys.fps);
  for (int f = 0; f + 1 < keys.frame_count(); ++f) {
    const Vec3 mid = 0.5 * (keys.frame(f).translations[0] + keys.frame(f + 1).translations[0]);
    EXPECT_LT((doubled.frame(2 * f + 1).translations[0] - mid).norm(), 1e-6) << "frame " << f;
  }
}

TEST(GltfReader, RigWithoutRolesNamesWhatIsMissing) {
  Foreign opt;
  for (int j = 0; j < walk().joint_count(); ++j) opt.names.push_back("bone_" + std::to_string(j));
  const std::string msg = read_error(foreign_glb(walk(), opt));
  EXPECT_NE(msg.find("foreign.glb: cannot resolve joint roles: neck, head, left_shoulder"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Joints are: bone_0 bone_1 bone_2"), std::string::npos) << msg;
}

TEST(GltfReader, UnevenArmatureScaleIsRefused) {
  Foreign opt;
  opt.armature_as_matrix = true;
  opt.armature_rotation = Quat::Identity();
  std::string bytes = foreign_glb(walk(), opt);
  // Stretch the armature's x column: a non-uniform scale cannot fold into the root.
  const auto at = bytes.find("\"matrix\":[0.01");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at + 10, 4, "0.02");
  EXPECT_NE(read_error(bytes).find("foreign.glb: the nodes above the root joint 'mixamorig:Hips' scale it unevenly"),
            std::string::npos)
      << read_error(bytes);
}
