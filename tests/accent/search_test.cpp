// k-nearest-neighbour search over a database's features (src/accent/search.cpp),
// on a database built from the repo's sample trials, checked against a plain
// scan of every window.
#include <legwork/accent/offline/builder.hpp>
#include <legwork/accent/search.hpp>

#include "accent_testing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <random>

namespace legwork::accent {
namespace {

class SearchDb : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    BuildConfig cfg;
    cfg.mirror = true;  // mirrored and re-timed copies: many near-duplicate windows
    db_ = new Database(testing::indexed_database({"walking/07_01", "running/09_01", "boxing/13_18", "basketball/06_04"}, cfg));
  }
  static void TearDownTestSuite() { delete db_; }
  static Database* db_;
};
Database* SearchDb::db_ = nullptr;

// Distances of every allowed window to q, ascending (the oracle, in double).
std::vector<double> scan_distances(const Database& db, int hand, const Feature& q, int only_class = -1) {
  std::vector<double> d;
  for (int w = 0; w < db.window_count(); ++w) {
    if (only_class >= 0 && db.source(w).cls != only_class) continue;
    double s = 0;
    for (int i = 0; i < kDim; ++i) s += std::pow(static_cast<double>(db.feature(hand, w)[static_cast<std::size_t>(i)]) - q[static_cast<std::size_t>(i)], 2);
    d.push_back(std::sqrt(s));
  }
  std::sort(d.begin(), d.end());
  return d;
}

Feature noisy_feature(const Database& db, int hand, std::mt19937& rng) {
  std::uniform_int_distribution<int> pick(0, db.window_count() - 1);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(0.5 * db.typical_distance() / std::sqrt(kDim)));
  Feature f = db.feature(hand, pick(rng));
  for (auto& x : f) x += noise(rng);
  return f;
}

TEST_F(SearchDb, ExactSearchEqualsBruteForceAndFastRecallIsReported) {
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

TEST_F(SearchDb, ClassMaskRestrictsMatches) {
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

TEST_F(SearchDb, EveryModeReturnsTheScansNearestDistancesInOrder) {
  std::mt19937 rng(11);
  for (int q = 0; q < 40; ++q) {
    const int hand = q % 2;
    const Feature f = noisy_feature(*db_, hand, rng);
    const auto oracle = scan_distances(*db_, hand, f);
    for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact}) {
      std::array<Match, 6> m;
      ASSERT_EQ(search_knn(*db_, hand, f, 6, mode, 0, {}, m), 6);
      for (std::size_t i = 0; i < m.size(); ++i) {
        EXPECT_NEAR(m[i].distance, oracle[i], 1e-4 * (1 + oracle[i])) << "query " << q << " rank " << i;
        EXPECT_LE(m[i == 0 ? 0 : i - 1].distance, m[i].distance);
      }
    }
  }
}

TEST_F(SearchDb, AWindowsOwnFeatureFindsItselfAtDistanceZero) {
  for (int w : {0, db_->window_count() / 3, db_->window_count() - 1}) {
    for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact, SearchMode::Fast}) {
      std::array<Match, 1> m;
      ASSERT_EQ(search_knn(*db_, 1, db_->feature(1, w), 1, mode, 0.5f, {}, m), 1);
      EXPECT_EQ(m[0].distance, 0.0f) << "window " << w;
      EXPECT_EQ(db_->feature(1, m[0].window), db_->feature(1, w));  // itself or an identical copy
    }
  }
}

TEST_F(SearchDb, SeedsDoNotChangeExactResultsAndBadSeedsAreIgnored) {
  std::mt19937 rng(5);
  const Feature f = noisy_feature(*db_, 0, rng);
  const int seeds[] = {-1, 3, 3, db_->window_count(), db_->window_count() - 1, 1 << 30};
  for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact}) {
    std::array<Match, 5> plain, seeded;
    ASSERT_EQ(search_knn(*db_, 0, f, 5, mode, 0, {}, plain), 5);
    ASSERT_EQ(search_knn(*db_, 0, f, 5, mode, 0, {}, seeded, seeds), 5);
    for (std::size_t i = 0; i < plain.size(); ++i) EXPECT_NEAR(seeded[i].distance, plain[i].distance, 1e-6f);
    // No window is reported twice, even when a seed is repeated and found again.
    for (std::size_t i = 0; i < seeded.size(); ++i)
      for (std::size_t j = i + 1; j < seeded.size(); ++j) EXPECT_NE(seeded[i].window, seeded[j].window);
  }
}

TEST_F(SearchDb, KIsCappedByTheOutputAndMasksCanExcludeEverything) {
  const Feature& f = db_->feature(0, 10);
  std::array<Match, 3> m;
  EXPECT_EQ(search_knn(*db_, 0, f, 50, SearchMode::Exact, 0, {}, m), 3);
  EXPECT_EQ(search_knn(*db_, 0, f, 0, SearchMode::Exact, 0, {}, m), 0);
  const std::vector<unsigned char> none(static_cast<std::size_t>(db_->class_count()), 0);
  for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact, SearchMode::Fast})
    EXPECT_EQ(search_knn(*db_, 0, f, 3, mode, 0, none, m), 0);
  // A mask shorter than the class list leaves the classes it does not cover out.
  const std::vector<unsigned char> first_only{1};
  const auto oracle = scan_distances(*db_, 0, f, 0);
  for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact}) {
    ASSERT_EQ(search_knn(*db_, 0, f, 3, mode, 0, first_only, m), 3);
    for (std::size_t i = 0; i < m.size(); ++i) {
      EXPECT_EQ(db_->source(m[i].window).cls, 0);
      EXPECT_NEAR(m[i].distance, oracle[i], 1e-4 * (1 + oracle[i]));
    }
  }
}

TEST(AccentSearch, WithoutAnIndexEveryModeFallsBackToTheScan) {
  BuildConfig cfg;
  // The builder stores the index in the database; a file loaded without it has none.
  const auto path = std::filesystem::temp_directory_path() / ("legwork-search-noindex-" + std::to_string(::getpid()) + ".lwdb");
  save_database(path.string(), build_database(testing::sample_trials({"walking/07_01", "boxing/13_18"}), cfg));
  LoadOptions no_index;
  no_index.build_index = false;
  no_index.use_mmap = false;
  const Database db = load_database(path.string(), no_index);
  std::filesystem::remove(path);
  ASSERT_FALSE(db.has_index());
  const Feature& f = db.feature(1, db.window_count() / 2);
  const auto oracle = scan_distances(db, 1, f);
  for (SearchMode mode : {SearchMode::Exact, SearchMode::Fast}) {
    std::array<Match, 4> m;
    ASSERT_EQ(search_knn(db, 1, f, 4, mode, 3.0f, {}, m), 4);
    for (std::size_t i = 0; i < m.size(); ++i) EXPECT_NEAR(m[i].distance, oracle[i], 1e-4 * (1 + oracle[i]));
  }
}

}  // namespace
}  // namespace legwork::accent
