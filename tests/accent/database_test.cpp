// Database build, file format and search.
#include <legwork/accent/offline/builder.hpp>
#include <legwork/accent/search.hpp>

#include "accent_testing.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>
#include <random>

namespace legwork::accent {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kSample{"walking/05_01", "walking/07_01", "walking/10_04", "running/09_01",
                                       "running/35_17", "boxing/13_18", "basketball/06_04", "climbing_ladder/14_33"};

fs::path temp_file(const std::string& name) { return fs::temp_directory_path() / ("legwork_accent_" + name); }

std::vector<std::byte> read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::vector<char> c((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::byte> b(c.size());
  std::memcpy(b.data(), c.data(), c.size());
  return b;
}
void write_all(const fs::path& p, const std::vector<std::byte>& b) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

class SampleDb : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    report_ = new BuildReport();
    BuildConfig cfg;
    cfg.mirror = true;
    db_ = new Database(testing::indexed_database(kSample, cfg, report_));
  }
  static void TearDownTestSuite() {
    delete db_;
    delete report_;
  }
  static Database* db_;
  static BuildReport* report_;
};
Database* SampleDb::db_ = nullptr;
BuildReport* SampleDb::report_ = nullptr;

// Foot contacts: a walking capture plants each foot a good part of the time,
// one foot at a time now and then (the other swings), and a mirrored copy
// swaps the feet of its original.
TEST_F(SampleDb, FootContactsAlternateInWalkingAndSwapWhenMirrored) {
  const int walking = db_->find_class("walking");
  ASSERT_GE(walking, 0);
  const auto [first, last] = db_->class_range(walking);
  std::map<std::tuple<std::uint32_t, std::uint32_t, std::uint8_t>, std::array<bool, 2>> original;
  int n = 0, left = 0, right = 0, only_left = 0, only_right = 0;
  for (int w = first; w < last; ++w) {
    const WindowSource& src = db_->source(w);
    const auto c = db_->contact(static_cast<int>(src.pose));
    if (src.mirrored) continue;
    original[{src.trial, src.frame, src.speed}] = c;
    ++n;
    left += c[0];
    right += c[1];
    only_left += c[0] && !c[1];
    only_right += c[1] && !c[0];
  }
  ASSERT_GT(n, 100);
  for (int planted : {left, right}) {
    EXPECT_GT(planted, n / 3) << "of " << n;
    EXPECT_LT(planted, n * 9 / 10) << "of " << n;
  }
  EXPECT_GT(only_left, n / 10);
  EXPECT_GT(only_right, n / 10);
  int mirrored = 0;
  for (int w = first; w < last; ++w) {
    const WindowSource& src = db_->source(w);
    if (!src.mirrored) continue;
    const auto it = original.find({src.trial, src.frame, src.speed});
    ASSERT_NE(it, original.end());
    const auto c = db_->contact(static_cast<int>(src.pose));
    EXPECT_EQ(c[0], it->second[1]) << "window " << w;
    EXPECT_EQ(c[1], it->second[0]) << "window " << w;
    ++mirrored;
  }
  EXPECT_EQ(mirrored, n);
}

TEST_F(SampleDb, ClassesAreContiguousAndEveryWindowHasItsSource) {
  ASSERT_EQ(db_->classes().size(), 5u);  // basketball, boxing, climbing_ladder, running, walking
  int expect_first = 0;
  for (int c = 0; c < db_->class_count(); ++c) {
    const auto [a, b] = db_->class_range(c);
    EXPECT_EQ(a, expect_first);
    expect_first = b;
    for (int w = a; w < b; ++w) ASSERT_EQ(db_->source(w).cls, c);
  }
  EXPECT_EQ(expect_first, db_->window_count());
  // The DAZ ladder trial is mapped through roles, not rejected.
  bool ladder = false;
  for (const auto& t : report_->trials)
    if (t.cls == "climbing_ladder") ladder = t.kept && t.reason.find("roles") != std::string::npos;
  EXPECT_TRUE(ladder);
  // Mirrored copies and speed variants are present.
  int mirrored = 0, fast = 0;
  for (int w = 0; w < db_->window_count(); ++w) {
    mirrored += db_->source(w).mirrored;
    fast += db_->source(w).speed != 0;
  }
  EXPECT_GT(mirrored, db_->window_count() / 3);
  EXPECT_GT(fast, db_->window_count() / 2);
}

TEST_F(SampleDb, ExactSearchEqualsBruteForceAndFastRecallIsReported) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(0, db_->window_count() - 1);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(0.5 * db_->typical_distance() / std::sqrt(kDim)));
  int hits = 0, total = 0;
  for (int q = 0; q < 200; ++q) {
    const int hand = q % 2;
    Feature f = db_->feature(hand, pick(rng));
    for (auto& x : f) x += noise(rng);
    std::array<Match, 8> brute, exact, fast;
    const int nb = search_knn(*db_, hand, f, 8, SearchMode::BruteForce, 0, {}, brute);
    const int ne = search_knn(*db_, hand, f, 8, SearchMode::Exact, 0, {}, exact);
    const int nf = search_knn(*db_, hand, f, 8, SearchMode::Fast, 2.0f, {}, fast);
    ASSERT_EQ(nb, 8);
    ASSERT_EQ(ne, nb);
    for (int i = 0; i < nb; ++i) {
      EXPECT_NEAR(exact[static_cast<std::size_t>(i)].distance, brute[static_cast<std::size_t>(i)].distance, 1e-4f);
      // Windows differ only between equidistant duplicates (mirror/speed copies).
      if (exact[static_cast<std::size_t>(i)].window != brute[static_cast<std::size_t>(i)].window) {
        EXPECT_NEAR(exact[static_cast<std::size_t>(i)].distance, brute[static_cast<std::size_t>(i)].distance, 1e-6f);
      }
    }
    for (int i = 0; i < nf; ++i)
      for (int j = 0; j < nb; ++j) hits += fast[static_cast<std::size_t>(i)].window == brute[static_cast<std::size_t>(j)].window;
    total += nb;
  }
  const double recall = static_cast<double>(hits) / total;
  std::printf("[ figures  ] fast-mode recall@8 (eps 2) on %d windows: %.3f\n", db_->window_count(), recall);
  EXPECT_GT(recall, 0.3);
}

TEST_F(SampleDb, ClassMaskRestrictsMatches) {
  const int boxing = db_->find_class("boxing");
  ASSERT_GE(boxing, 0);
  std::vector<unsigned char> mask(static_cast<std::size_t>(db_->class_count()), 0);
  mask[static_cast<std::size_t>(boxing)] = 1;
  const Feature& f = db_->feature(0, db_->class_range(db_->find_class("walking")).first + 5);
  for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact, SearchMode::Fast}) {
    std::array<Match, 5> m;
    const int n = search_knn(*db_, 0, f, 5, mode, 1.0f, mask, m);
    ASSERT_EQ(n, 5);
    for (int i = 0; i < n; ++i) EXPECT_EQ(db_->source(m[static_cast<std::size_t>(i)].window).cls, boxing);
  }
}

TEST_F(SampleDb, FileRoundTripByMmapIsIdentical) {
  const auto path = temp_file("roundtrip.lwdb");
  save_database(path.string(), *db_);
  const Database loaded = load_database(path.string());
  EXPECT_TRUE(loaded.is_mapped());
  ASSERT_EQ(loaded.window_count(), db_->window_count());
  ASSERT_EQ(loaded.bytes().size(), db_->bytes().size());
  EXPECT_EQ(std::memcmp(loaded.bytes().data(), db_->bytes().data(), db_->bytes().size()), 0);
  EXPECT_EQ(loaded.skeleton().names, db_->skeleton().names);
  EXPECT_EQ(loaded.classes(), db_->classes());
  EXPECT_DOUBLE_EQ(loaded.typical_distance(), db_->typical_distance());
  EXPECT_EQ(loaded.feature_space().projection, db_->feature_space().projection);
  fs::remove(path);
}

TEST_F(SampleDb, BadFilesAreRejectedWithClearMessages) {
  const auto path = temp_file("bad.lwdb");
  save_database(path.string(), *db_);
  const auto good = read_all(path);
  auto expect_error = [&](const std::vector<std::byte>& bytes, const std::string& what) {
    write_all(path, bytes);
    try {
      (void)load_database(path.string());
      ADD_FAILURE() << "expected an error containing '" << what << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  };
  expect_error(std::vector<std::byte>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(good.size() / 2)), "truncated");
  expect_error(std::vector<std::byte>(good.begin(), good.begin() + 40), "truncated");
  auto flipped = good;
  flipped[good.size() - 100] ^= std::byte{0x10};
  expect_error(flipped, "checksum");
  auto version = good;
  version[8] = std::byte{7};  // the version field follows the 8-byte magic
  expect_error(version, "version 7");
  auto old = good;
  old[8] = std::byte{1};  // a version 1 file (no foot contacts): rebuild
  expect_error(old, "format version 1, but this legwork reads version 3; rebuild it with 'legwork accent build'");
  auto v2 = good;
  v2[8] = std::byte{2};  // a version 2 file (no stored search index): rebuild
  expect_error(v2, "format version 2, but this legwork reads version 3; rebuild it");
  auto magic = good;
  magic[0] = std::byte{'X'};
  expect_error(magic, "not a legwork accent database");
  expect_error({}, "empty");
  fs::remove(path);
  EXPECT_THROW((void)load_database(temp_file("missing.lwdb").string()), Error);
}

TEST(AccentBuild, AllFilteredOrEmptyInputIsAClearError) {
  BuildConfig cfg;
  cfg.correlation_threshold = 1.01;  // nothing can pass
  BuildReport report;
  try {
    (void)build_database(testing::sample_trials({"walking/07_01"}), cfg, &report);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no windows"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)build_database(std::vector<TrialInput>{}, BuildConfig{}), Error);
}

// A typo in an exclusion used to keep the held-out trial in the database silently.
TEST(AccentBuild, ExcludingATrialThatIsNotThereIsAnError) {
  const std::string data = testdata::sample("cmu").string();
  const auto message = [&](const std::vector<std::string>& classes, const std::string& exclude) {
    try {
      (void)load_trials(data, classes, {exclude});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message({"boxing"}, "nothere.bvh"),
            "exclude 'nothere.bvh' matches no trial of '" + data +
                "' in the chosen classes (name a file as in the manifest, e.g. 'bvh/boxing/13_18.bvh', or by its file name)");
  EXPECT_NE(message({"boxing"}, "bvh/walking/07_01.bvh").find("matches no trial"), std::string::npos);
  EXPECT_EQ(message({"boxing", "walking"}, "bvh/walking/07_02.bvh"), "(no error)");
  EXPECT_EQ(message({"boxing", "walking"}, "07_02.bvh"), "(no error)");
  EXPECT_EQ(load_trials(data, {"boxing"}, {"13_18.bvh"}).size(), 0u);
}

TEST(AccentBuild, SkeletonWithoutHandsIsRejectedPerTrial) {
  auto trials = testing::sample_trials({"walking/07_01", "walking/05_01"});
  // Cut the arms off the second trial's rig: its hands' roles disappear.
  Skeleton s;
  const Skeleton& full = trials[1].motion.skeleton;
  std::vector<int> keep(static_cast<std::size_t>(full.joint_count()), -1);
  const int lhand = full.roles[Role::LeftHand];
  for (int j = 0; j < full.joint_count(); ++j) {
    const int p = full.parents[static_cast<std::size_t>(j)];
    if (full.is_ancestor(lhand, j) || (p >= 0 && keep[static_cast<std::size_t>(p)] < 0)) continue;
    keep[static_cast<std::size_t>(j)] = s.add_joint(full.names[static_cast<std::size_t>(j)], p < 0 ? -1 : keep[static_cast<std::size_t>(p)], full.rest_offsets[static_cast<std::size_t>(j)]);
  }
  resolve_roles(s);
  ASSERT_FALSE(s.roles.has(Role::LeftHand));
  trials[1].motion = Motion(s, trials[1].motion.fps, 50);
  BuildReport report;
  const Database db = build_database(trials, BuildConfig{}, &report);
  ASSERT_EQ(report.trials.size(), 2u);
  EXPECT_TRUE(report.trials[0].kept);
  EXPECT_FALSE(report.trials[1].kept);
  EXPECT_NE(report.trials[1].reason.find("left_hand"), std::string::npos) << report.trials[1].reason;
}

}  // namespace
}  // namespace legwork::accent

namespace legwork::accent {
namespace {

// The leave-one-out path of the evaluation: prepare once, assemble per fold.
TEST(AccentFolds, PreparedTrialsAssembleFoldsWithoutTheHeldOutTrial) {
  const auto trials = testing::sample_trials({"walking/05_01", "walking/07_01", "walking/07_12", "running/09_01"});
  const Skeleton ref = reference_skeleton(trials);
  const BuildConfig cfg;
  std::vector<PreparedTrial> prepared;
  for (const auto& t : trials) prepared.push_back(prepare_trial(t, ref, cfg));
  for (std::size_t held = 0; held < prepared.size(); ++held) {
    std::vector<const PreparedTrial*> train;
    for (std::size_t i = 0; i < prepared.size(); ++i)
      if (i != held) train.push_back(&prepared[i]);
    BuildReport report;
    const Database db = assemble_database(train, ref, cfg, &report);
    EXPECT_EQ(db.skeleton().names, ref.names);
    for (int w = 0; w < db.window_count(); ++w)
      ASSERT_NE(db.trials()[db.source(w).trial].file, prepared[held].info.file) << "fold " << held << " leaks";
    int expected = 0;
    for (const auto* t : train) expected += t->kept;
    EXPECT_EQ(static_cast<int>(db.trials().size()), expected);
  }
}

}  // namespace
}  // namespace legwork::accent
