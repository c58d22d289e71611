// Building and reading the learned depth mapping (legwork/wip/offline/learn.hpp):
// training samples from a real walk's run, the table from samples, the text
// file round trip and its error messages.
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/run.hpp>

#include "sample_walk_run.hpp"
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
  const auto& run = samples::sample_walk_run();
  const auto& frames = run.frames;
  const double leg = run.leg_length;
  std::vector<double> left(frames.size(), 0.3), right(frames.size(), -0.2);
  right[frames.size() / 2] = NAN;  // a frame without truth for one foot
  const auto samples = learning_samples(frames, left, right, leg, 0.5);
  std::size_t expected = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames[i].walking && frames[i].lead >= 0 && frames[i].time >= 0.5) expected += i == frames.size() / 2 ? 1 : 2;
  ASSERT_GT(expected, 100u);
  EXPECT_EQ(samples.size(), expected);
  int lead = 0;
  for (const auto& s : samples) {
    EXPECT_TRUE(std::abs(s.z - 0.3 / leg) < 1e-12 || std::abs(s.z + 0.2 / leg) < 1e-12);
    EXPECT_GT(s.apex, 0.02);
    lead += s.lead;
  }
  EXPECT_GT(lead, 0);  // both feet lead at times
  EXPECT_LT(lead, static_cast<int>(samples.size()));
}

TEST(BuildLearnedMapping, SamplesOnANodeGiveItTheirMeanShapeAndEmptyNodesTakeTheNearest) {
  std::vector<LearnSample> samples;
  for (int k = 0; k < 300; ++k) {
    // node (since 0, 0, 0) of lead 1: z / amplitude 0.4 / 0.5 and 0.2 / 0.5, mean 0.6
    samples.push_back({0.0, 0.0, 1, 0.0, 0.1, 1.0, k % 2 ? 0.4 : 0.2, 0.5});
    samples.push_back({2.0, 2.0, 0, 100.0, 0.2, 0.5, -0.25, 0.25});  // the last node of lead 0: -1
  }
  const auto m = build_learned_mapping(samples);
  constexpr int n = LearnedMapping::kNodes, ks = LearnedMapping::kSinceNodes;
  EXPECT_NEAR(m.at(1, 0, 0, 0), 0.6, 1e-12);
  EXPECT_NEAR(m.at(0, ks - 1, n - 1, n - 1), -1, 1e-12);
  EXPECT_NEAR(m.at(1, ks - 1, n - 1, n - 1), 0.6, 1e-12);  // the only filled node of its slice
  EXPECT_NEAR(m.at(0, 0, 0, 0), -1, 1e-12);
  EXPECT_NEAR(m.apex_mean, 0.15, 1e-12);
  EXPECT_NEAR(m.cadence_mean, 0.75, 1e-12);
  // amplitude 0.5 at (apex 0.1, cadence 1), 0.25 at (0.2, 0.5): collinear, so the fit goes through both
  EXPECT_NEAR(m.amplitude(0.1, 1.0), 0.5, 1e-9);
  EXPECT_NEAR(m.amplitude(0.2, 0.5), 0.25, 1e-9);
  EXPECT_EQ(m.samples, 600);
}

// The turning gain: least squares of the true depth on the table's prediction p
// and p * turn rate. One node per lead foot, one amplitude: p is the node's mean depth,
// so the fit is exact.
TEST(BuildLearnedMapping, TheTurningGainIsFittedAndAnUnreadableOneIsDropped) {
  auto fit = [](double z_still, double z_turning) {
    std::vector<LearnSample> samples;
    for (int k = 0; k < 300; ++k) {
      const bool turning = k % 2;
      samples.push_back({0.0, 0.0, 1, 0.0, 0.1, 1.0, turning ? z_turning : z_still, 0.5, turning ? 1.0 : 0.0});
      // The trailing foot, behind the pelvis by as much (both lead slices need frames).
      samples.push_back({0.0, 0.0, 0, 0.0, 0.1, 1.0, turning ? -z_turning : -z_still, 0.5, turning ? 1.0 : 0.0});
    }
    return build_learned_mapping(samples);
  };
  // Steps 1.2 long standing still, 0.9 turning at 1 rad/s: gains 1.2 / 1.05 and 0.9 / 1.05.
  const LearnedMapping m = fit(0.12, 0.09);
  EXPECT_NEAR(m.turn_intercept, 1.2 / 1.05, 1e-9);
  EXPECT_NEAR(m.turn_slope, -0.3 / 1.05, 1e-9);
  EXPECT_NEAR(m.turn_gain(1.0), 0.9 / 1.05, 1e-9);
  // A fit whose intercept the reader would refuse (2.5 > kMaxTurnGain) is dropped: no turn term,
  // and the table still round-trips.
  const LearnedMapping wild = fit(0.10, -0.02);
  EXPECT_EQ(wild.turn_intercept, 1.0);
  EXPECT_EQ(wild.turn_slope, 0.0);
  EXPECT_NO_THROW(parse_learned_mapping(format_learned_mapping(wild, "test"), "wild.txt"));
}

TEST(BuildLearnedMapping, TooFewSamplesAreRefusedWithTheCount) {
  std::vector<LearnSample> samples(10, LearnSample{0.5, 0.5, 1, 0.2, 0.1, 1.0, 0.2, 0.4});
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
  for (std::size_t k = 0; k < m.shape.size(); ++k) EXPECT_NEAR(again.shape[k], m.shape[k], 1e-5 * (1 + std::abs(m.shape[k])));
  EXPECT_NEAR(again.amplitude_intercept, m.amplitude_intercept, 1e-6);
  EXPECT_NEAR(again.amplitude_slope, m.amplitude_slope, 1e-5 * (1 + std::abs(m.amplitude_slope)));
  EXPECT_NEAR(again.cadence_slope, m.cadence_slope, 1e-5 * (1 + std::abs(m.cadence_slope)));
  EXPECT_NEAR(again.apex_mean, m.apex_mean, 1e-6);
  EXPECT_EQ(again.samples, m.samples);
}

TEST(LearnedMappingFile, BadFilesNameTheLineAndTheField) {
  const std::string good = format_learned_mapping(read_learned_mapping(shipped_path()), "test");
  EXPECT_NE(error_of("hello\n").find("table.txt:1: not a learned walking-in-place mapping"), std::string::npos);
  std::string bad = good;
  bad.replace(bad.find("cadence_slope "), 14, "cadence_slop ");
  EXPECT_NE(error_of(bad).find("expected 'cadence_slope <number>'"), std::string::npos) << error_of(bad);
  bad = good;
  const auto row = bad.find("\n", bad.find("lead 1\n") + 7) + 1;  // first row after "since 0"
  bad.replace(row, bad.find(' ', row) - row, "x");
  const std::string e = error_of(bad);
  EXPECT_NE(e.find("lead 1 since node 0 row 0: column 0 is not a finite number"), std::string::npos) << e;
  EXPECT_NE(e.find("table.txt:"), std::string::npos) << e;
  EXPECT_NE(error_of(good.substr(0, good.rfind('\n', good.size() / 2) + 1)).find("file ends inside the table"), std::string::npos);
  bad = good;
  const auto ti = bad.find("turn_intercept ") + 15;
  bad.replace(ti, bad.find('\n', ti) - ti, "2.5");
  EXPECT_NE(error_of(bad).find("'turn_intercept' must be within [0, 2]"), std::string::npos) << error_of(bad);
  // A count beyond an int (wip_table_fuzz: a float-to-int overflow before the check) or not whole.
  for (const char* count : {"2.3e87", "-1", "12.5"}) {
    bad = good;
    const auto at = bad.find("samples ") + 8;
    bad.replace(at, bad.find('\n', at) - at, count);
    const std::string m = error_of(bad);
    EXPECT_NE(m.find("'samples' must be a whole number from 0 to 1000000000"), std::string::npos) << count << ": " << m;
    EXPECT_NE(m.find("table.txt:"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace legwork::wip
