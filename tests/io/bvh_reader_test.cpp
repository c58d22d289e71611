// BVH reader on well-formed input: lexical variants, channel orders, units
// and roles, zero-frame repair, and the whole shared CMU set.
#include <legwork/core/fk.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>

#include "bvh_fixture.hpp"
#include "testdata.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <array>
#include <fstream>
#include <map>
#include <sstream>

using namespace legwork;
using legwork::testdata::expect_same_motion;
using legwork::testdata::metres;

namespace {

const std::string& kBase = legwork::testdata::kTinyBvh;

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

// Positions of every joint and end-site tip in every frame.
std::vector<Vec3> points(const Motion& m) {
  std::vector<Vec3> out;
  std::vector<Transform> g(static_cast<std::size_t>(m.joint_count()));
  for (int f = 0; f < m.frame_count(); ++f) {
    forward_kinematics(m.skeleton, m.frame(f), g);
    for (int j = 0; j < m.joint_count(); ++j) {
      out.push_back(g[static_cast<std::size_t>(j)].translation);
      out.push_back(end_site_position(m.skeleton, g, j));
    }
  }
  return out;
}

std::map<std::string, std::string> manifest_row(const std::vector<std::string>& header, const std::string& line) {
  std::map<std::string, std::string> row;
  std::stringstream ss(line);
  std::string cell;
  for (std::size_t i = 0; i < header.size() && std::getline(ss, cell, '\t'); ++i) row[header[i]] = cell;
  return row;
}

std::vector<std::map<std::string, std::string>> read_manifest() {
  std::ifstream in(testdata::shared_cmu() / "MANIFEST.tsv");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, '\t');) header.push_back(c);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(manifest_row(header, line));
  return rows;
}

}  // namespace

TEST(BvhReader, LexicalVariantsParseTheSame) {
  const Motion base = io::parse_bvh(kBase, "base.bvh", metres()).motion;
  const std::map<std::string, std::string> variants = {
      {"crlf", replace_all(kBase, "\n", "\r\n")},
      {"tabs", replace_all(kBase, " ", "\t")},
      {"trailing_whitespace", replace_all(kBase, "\n", " \t \n")},
      {"no_final_newline", kBase.substr(0, kBase.size() - 1)},
      {"blank_lines_in_motion", replace_all(kBase, "30\n", "30\n\n")},
      {"scientific_notation", replace_all(replace_all(kBase, "0.25 1 0.1 5 -7 3 10 20 30", "2.5e-1 1E0 +1e-1 5.0e0 -7 3 1e1 20 30"),
                                          "OFFSET 0 0.5 0", "OFFSET 0e0 5E-1 -0.0")},
      {"frames_label_spacing", replace_all(replace_all(kBase, "Frames: 2", "Frames :\t2"), "Frame Time: 0.1", "Frame Time:\t0.1")},
  };
  const auto want = points(base);
  for (const auto& [name, text] : variants) {
    SCOPED_TRACE(name);
    const Motion m = io::parse_bvh(text, name + ".bvh", metres()).motion;
    const auto got = points(m);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT((got[i] - want[i]).norm(), 1e-12);
  }
}

TEST(BvhReader, SixChannelsOnANonRootJointTranslateIt) {
  const std::string text = replace_all(
      replace_all(kBase, "    CHANNELS 3 Zrotation Yrotation Xrotation", "    CHANNELS 6 Zposition Xposition Yposition Xrotation Yrotation Zrotation"),
      "10 20 30\n", "0.3 0.1 0.7 10 20 30\n");
  const auto f = io::parse_bvh(text, "six.bvh", metres());
  ASSERT_EQ(f.channels[1].channels.size(), 6u);
  // Position channels replace the OFFSET (x=0.1, y=0.7, z=0.3 in file order Z X Y).
  EXPECT_TRUE(f.motion.frame(1).translations[1].isApprox(Vec3(0.1, 0.7, 0.3)));
  const io::Channel order[3] = {io::Channel::Xrotation, io::Channel::Yrotation, io::Channel::Zrotation};
  const double deg[3] = {10, 20, 30};
  EXPECT_TRUE(f.motion.frame(1).rotations[1].isApprox(io::euler_to_quat(order, deg, 3)));
  // The writer keeps the translation: the default layout gives a translated joint position channels.
  const auto again = io::parse_bvh(io::format_bvh(f.motion), "again.bvh", metres());
  expect_same_motion(f.motion, again.motion, 1e-6);
}

TEST(BvhReader, EveryRotationOrderComposesLeftToRight) {
  const std::array<const char*, 3> axes = {"X", "Y", "Z"};
  std::array<int, 3> perm = {0, 1, 2};
  int orders = 0;
  do {
    std::string ch;
    for (int a : perm) ch += std::string(" ") + axes[static_cast<std::size_t>(a)] + "rotation";
    const std::string text = replace_all(kBase, "    CHANNELS 3 Zrotation Yrotation Xrotation", "    CHANNELS 3" + ch);
    const auto f = io::parse_bvh(text, "order.bvh", metres());
    // Independent oracle: Eigen's AngleAxis product in file order.
    const double deg[3] = {10, 20, 30};
    Quat want = Quat::Identity();
    for (int k = 0; k < 3; ++k)
      want = want * Quat(Eigen::AngleAxisd(deg2rad(deg[k]), Vec3::Unit(perm[static_cast<std::size_t>(k)])));
    SCOPED_TRACE(ch);
    EXPECT_TRUE(f.motion.frame(1).rotations[1].isApprox(want, 1e-12));
    ++orders;
  } while (std::next_permutation(perm.begin(), perm.end()));
  EXPECT_EQ(orders, 6);
}

TEST(BvhReader, PositionChannelsInAnyOrder) {
  const std::string text = replace_all(kBase, "CHANNELS 6 Xposition Yposition Zposition", "CHANNELS 6 Zposition Xposition Yposition");
  const auto f = io::parse_bvh(text, "pos.bvh", metres());
  EXPECT_TRUE(f.motion.frame(1).translations[0].isApprox(Vec3(1, 0.1, 0.25)));
}

TEST(BvhReader, CmuUnitsAndRolesAreDetected) {
  const auto f = io::read_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string());
  EXPECT_NEAR(f.report.scale, kCmuUnitMetres, 1e-12);
  EXPECT_NE(f.report.scale_reason.find("CMU"), std::string::npos) << f.report.scale_reason;
  EXPECT_TRUE(f.report.missing_roles.empty());
  const auto daz = io::read_bvh(testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh").string());
  EXPECT_NEAR(daz.report.scale, 0.01, 1e-12);
  EXPECT_EQ(daz.channels[1].channels[1], io::Channel::Xrotation);  // DAZ's Z X Y order
}

TEST(BvhReader, DropFirstFrameAndZeroFrameRepair) {
  const auto path = testdata::sample("cmu/bvh/walking/07_12.bvh").string();
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  const auto f = io::read_bvh(path, opt);
  EXPECT_TRUE(f.report.dropped_first_frame);
  EXPECT_EQ(f.motion.frame_count(), f.report.declared_frames - 1);
  // 07_12's frame 1 is all zeros in the source: it is replaced by frame 2, not left at the origin.
  EXPECT_EQ(f.report.repaired_zero_frames, 1);
  EXPECT_GT(f.motion.frame(0).translations[0].norm(), 0.5);
  EXPECT_LT((f.motion.frame(0).translations[0] - f.motion.frame(1).translations[0]).norm(), 1e-12);
  opt.repair_zero_frames = false;
  EXPECT_EQ(io::read_bvh(path, opt).motion.frame(0).translations[0].norm(), 0.0);
}

// ---- the full shared data set ------------------------------------------------

TEST(BvhSharedData, EveryFileParsesAndMatchesTheManifest) {
  LEGWORK_REQUIRE_SHARED_CMU();
  const auto rows = read_manifest();
  ASSERT_GE(rows.size(), 100u);
  int checked = 0;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.at("file"));
    const auto f = io::read_bvh((testdata::shared_cmu() / row.at("file")).string());
    EXPECT_EQ(f.motion.joint_count(), std::stoi(row.at("joints")));
    EXPECT_EQ(f.motion.frame_count(), std::stoi(row.at("frames")));
    EXPECT_EQ(f.report.declared_frames, std::stoi(row.at("frames")));
    for (Role r : f.report.missing_roles) EXPECT_FALSE(role_is_required(r)) << role_name(r);  // DAZ has no toe joints
    ++checked;
  }
  // And no .bvh in the folder is missing from the manifest.
  int on_disk = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(testdata::shared_cmu()))
    on_disk += e.path().extension() == ".bvh";
  EXPECT_EQ(on_disk, checked);
}

TEST(BvhSharedData, StandingHeightIsHuman) {
  // measure_body is a lower bound on stature for the cgspeed layout: the
  // thorax bone is missing (Neck sits at Spine1's start, ~0.09-0.12 m) and the
  // Head end site stops below the crown. Subject 105 is the smallest subject
  // (leg 0.74 m, hip height 0.85 m, so about 1.6 m tall) and measures 1.30 m:
  // it gets a lower floor, and every body must have human proportions.
  LEGWORK_REQUIRE_SHARED_CMU();
  int checked = 0;
  for (const auto& row : read_manifest()) {
    if (row.at("class") == "swimming") continue;  // swimmers are not standing trials
    SCOPED_TRACE(row.at("file"));
    const auto f = io::read_bvh((testdata::shared_cmu() / row.at("file")).string());
    const auto b = measure_body(f.motion.skeleton);
    EXPECT_GE(b.standing_height, row.at("subject") == "105" ? 1.25 : 1.4);
    EXPECT_LE(b.standing_height, 2.0);
    EXPECT_GT(b.hip_height / b.standing_height, 0.55);  // legs are about half of a body
    EXPECT_LT(b.hip_height / b.standing_height, 0.7);
    ++checked;
  }
  EXPECT_GE(checked, 120);
}

TEST(BvhSharedData, WalkingStartsWithAFootOnTheFloor) {
  // Floor = the lowest joint or end-site tip over the whole trial (CMU has no
  // floor plane). On the first real frame (the T-pose dropped) the lowest
  // foot point (ankle, toe, toe tip) must be within 0.15 m of it.
  LEGWORK_REQUIRE_SHARED_CMU();
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  int walks = 0;
  for (const auto& row : read_manifest()) {
    if (row.at("class") != "walking") continue;
    SCOPED_TRACE(row.at("file"));
    const auto m = io::read_bvh((testdata::shared_cmu() / row.at("file")).string(), opt).motion;
    const auto p = points(m);  // per frame: joint, tip, joint, tip...
    const double floor = std::min_element(p.begin(), p.end(), [](const Vec3& a, const Vec3& b) { return a.y() < b.y(); })->y();
    const auto& r = m.skeleton.roles;
    double foot = 1e9;
    for (Role role : {Role::LeftAnkle, Role::LeftToe, Role::RightAnkle, Role::RightToe}) {
      const auto j = static_cast<std::size_t>(r[role]);
      foot = std::min({foot, p[2 * j].y(), p[2 * j + 1].y()});
    }
    EXPECT_LT(foot - floor, 0.15);
    ++walks;
  }
  EXPECT_GE(walks, 50);
}

TEST(BvhSharedData, ZeroFramesOf0910And0712AreRepaired) {
  LEGWORK_REQUIRE_SHARED_CMU();
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  const auto a = io::read_bvh((testdata::shared_cmu() / "bvh/running/09_10.bvh").string(), opt);
  EXPECT_EQ(a.report.repaired_zero_frames, 4);
  const auto b = io::read_bvh((testdata::shared_cmu() / "bvh/walking/07_12.bvh").string(), opt);
  EXPECT_EQ(b.report.repaired_zero_frames, 1);
  for (const auto* f : {&a, &b})
    for (int i = 0; i < 5; ++i) EXPECT_GT(f->motion.frame(i).translations[0].y(), 0.5) << "frame " << i;
}

TEST(BvhSharedData, BoxingToesFrameCountMismatch) {
  const auto path = testdata::shared_cmu().parent_path() / "extra" / "bvh" / "boxing" / "Boxing_Toes.bvh";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  try {
    io::read_bvh(path.string());
    FAIL() << "strict mode must reject the extra motion line";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ":128: 'Frames: 3069' but the file has 3070 motion lines");
  }
  io::BvhReadOptions lenient;
  lenient.strict_frame_count = false;
  const auto f = io::read_bvh(path.string(), lenient);
  EXPECT_EQ(f.motion.frame_count(), 3069);
  EXPECT_EQ(f.motion.joint_count(), 21);
  EXPECT_NEAR(f.motion.fps, 100.0, 1e-9);
  EXPECT_NEAR(f.report.scale, 0.01, 1e-12);
  ASSERT_EQ(f.report.warnings.size(), 1u);
  const double h = measure_body(f.motion.skeleton).standing_height;
  EXPECT_GT(h, 1.4);
  EXPECT_LT(h, 2.0);
}

