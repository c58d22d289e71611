// Building and reading the learned depth mapping (legwork/wip/offline/learn.hpp):
// training samples from a real walk's run, the table from samples, the text
// file round trip and its error messages.
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/run.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cmath>
#include <string>

namespace legwork::wip {
namespace {

std::string shipped_path() { return (testdata::source_dir() / "data/wip/learned_mapping.txt").string(); }

std::string error_of(const std::string& text) {
  try {
    (void)parse_learned_mapping(text, "table.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(LearningSamples, BothFeetOfTheWalkingFramesAfterSettlingWithTheirLeadAndDepthPerLeg) {
  const Motion walk = testdata::load_sample("cmu/bvh/walking/05_01.bvh");
  const Model model = make_model(walk.skeleton);
  RunOptions ro;
  ro.calibrate = false;
  ro.keep_poses = false;
  const auto frames = run_wip(model, tracker_frames_from_motion(walk, 30), ro).frames;
  std::vector<double> left(frames.size(), 0.3), right(frames.size(), -0.2);
  right[frames.size() / 2] = NAN;  // a frame without truth for one foot
  const auto samples = learning_samples(frames, left, right, model.leg_length(), 0.5);
  std::size_t expected = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames[i].walking && frames[i].lead >= 0 && frames[i].time >= 0.5) expected += i == frames.size() / 2 ? 1 : 2;
  ASSERT_GT(expected, 100u);
  EXPECT_EQ(samples.size(), expected);
  int lead = 0;
  for (const auto& s : samples) {
    EXPECT_TRUE(std::abs(s.z - 0.3 / model.leg_length()) < 1e-12 || std::abs(s.z + 0.2 / model.leg_length()) < 1e-12);
    EXPECT_GT(s.apex, 0.02);
    lead += s.lead;
  }
  EXPECT_GT(lead, 0);  // both feet lead at times
  EXPECT_LT(lead, static_cast<int>(samples.size()));
}

TEST(BuildLearnedMapping, SamplesOnANodeGiveItTheirMeanAndEmptyNodesTakeTheNearest) {
  std::vector<LearnSample> samples;
  for (int k = 0; k < 300; ++k) {
    samples.push_back({0.0, 0.0, 1, 0.15, k % 2 ? 0.4 : 0.2});  // node (0, 0) of lead 1: mean 0.3
    samples.push_back({2.0, 2.0, 0, 0.15, -0.5});               // node (last, last) of lead 0
  }
  const auto m = build_learned_mapping(samples);
  constexpr int n = LearnedMapping::kNodes;
  EXPECT_NEAR(m.at(1, 0, 0), 0.3, 1e-12);
  EXPECT_NEAR(m.at(0, n - 1, n - 1), -0.5, 1e-12);
  EXPECT_NEAR(m.at(1, n - 1, n - 1), 0.3, 1e-12);  // the only filled node of its slice
  EXPECT_NEAR(m.apex_mean, 0.15, 1e-12);
  EXPECT_EQ(m.samples, 600);
}

TEST(BuildLearnedMapping, TooFewSamplesAreRefusedWithTheCount) {
  std::vector<LearnSample> samples(10, LearnSample{0.5, 0.5, 1, 0.1, 0.2});
  try {
    (void)build_learned_mapping(samples);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("10 training frames while walking (need at least 200)"), std::string::npos)
        << e.what();
  }
}

TEST(LearnedMappingFile, TheShippedTableRoundTrips) {
  const auto m = read_learned_mapping(shipped_path());
  const auto again = parse_learned_mapping(format_learned_mapping(m, "round trip"), "again.txt");
  for (std::size_t k = 0; k < m.depth.size(); ++k) EXPECT_NEAR(again.depth[k], m.depth[k], 1e-5 * (1 + std::abs(m.depth[k])));
  EXPECT_NEAR(again.gain_slope, m.gain_slope, 1e-5 * (1 + std::abs(m.gain_slope)));
  EXPECT_NEAR(again.apex_mean, m.apex_mean, 1e-6);
  EXPECT_EQ(again.samples, m.samples);
}

TEST(LearnedMappingFile, BadFilesNameTheLineAndTheField) {
  const std::string good = format_learned_mapping(read_learned_mapping(shipped_path()), "test");
  EXPECT_NE(error_of("hello\n").find("table.txt:1: not a learned walking-in-place mapping"), std::string::npos);
  std::string bad = good;
  bad.replace(bad.find("gain_slope "), 11, "gain_slop ");
  EXPECT_NE(error_of(bad).find("expected 'gain_slope <number>'"), std::string::npos) << error_of(bad);
  bad = good;
  const auto row = bad.find("lead 1\n") + 7;
  bad.replace(row, bad.find(' ', row) - row, "x");
  const std::string e = error_of(bad);
  EXPECT_NE(e.find("lead 1 table row 0: column 0 is not a finite number"), std::string::npos) << e;
  EXPECT_NE(e.find("table.txt:"), std::string::npos) << e;
  EXPECT_NE(error_of(good.substr(0, good.rfind('\n', good.size() / 2) + 1)).find("file ends inside the lead"), std::string::npos);
}

}  // namespace
}  // namespace legwork::wip
