// The database (contents, file format): built once from the sample trials.
// Search is in search_test.cpp, the builder's own functions in builder_test.cpp.
#include <legwork/accent/offline/builder.hpp>

#include "accent_testing.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

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

// A real format-4 file (the boxing sample database as format 4 wrote it, no
// head travel) is refused by name with the rebuild message.
TEST(DatabaseFormat, AFormat4FileIsRefusedWithTheRebuildMessage) {
  const std::string path = std::string(LEGWORK_SOURCE_DIR) + "/tests/accent/data/format4_boxing.lwdb";
  try {
    (void)load_database(path);
    FAIL() << "a format-4 file loaded";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "accent database '" + path +
                                         "': format version 4, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  }
}

// The accent_db fuzz target's seed (fuzz/corpus/README.md) must be a database
// of the current format: a stale seed is refused at once, and every mutation
// of it stops at the same check, so the fuzzer never reaches the engine
// (session 24's first format-7 run spent 0.5 M executions that way). It is
// the builder's bytes for its command, so it is also rebuilt bit for bit.
TEST(DatabaseFormat, TheFuzzSeedDatabaseIsOfTheCurrentFormat) {
  const std::string path = std::string(LEGWORK_SOURCE_DIR) + "/fuzz/corpus/accent_db/sample.lwdb";
  const Database seed = load_database(path);
  EXPECT_EQ(seed.class_count(), 1);
  EXPECT_EQ(seed.classes()[0], "boxing");
  BuildConfig cfg;
  cfg.hop = 32;
  const Database again = build_database(load_trials(std::string(LEGWORK_SOURCE_DIR) + "/data/cmu", {"boxing"}, {}), cfg);
  ASSERT_EQ(again.bytes().size(), seed.bytes().size()) << "rebuild " << path << " with the command in fuzz/corpus/README.md";
  EXPECT_EQ(std::memcmp(again.bytes().data(), seed.bytes().data(), seed.bytes().size()), 0)
      << "rebuild " << path << " with the command in fuzz/corpus/README.md";
}

// Format 5 stores the performer's head travel per window: it survives the
// file round trip bit for bit, and it is what the trials did: running
// windows travel faster than walking ones, which travel faster than boxing
// ones (the boxer stays on the spot), and upright performers' heads sit at
// 85-100 % of the body height.
TEST_F(SampleDb, HeadTravelIsStoredPerWindowAndFollowsTheTrials) {
  const fs::path path = temp_file("travel.lwdb");
  save_database(path.string(), *db_);
  const Database loaded = load_database(path.string());
  ASSERT_EQ(loaded.window_count(), db_->window_count());
  for (int d = 0; d < kTravelDim; ++d) {
    EXPECT_EQ(loaded.travel_scale()[static_cast<std::size_t>(d)], db_->travel_scale()[static_cast<std::size_t>(d)]);
    EXPECT_GT(db_->travel_scale()[static_cast<std::size_t>(d)], 0.0f);
  }
  for (int w = 0; w < db_->window_count(); ++w) ASSERT_EQ(loaded.travel(w), db_->travel(w)) << "window " << w;
  fs::remove(path);
  std::map<std::string, std::array<double, 3>> mean;  // class -> short speed, long speed, height; window count
  std::map<std::string, int> count;
  for (int w = 0; w < db_->window_count(); ++w) {
    const auto& src = db_->source(w);
    if (src.speed != 0) continue;
    const std::string& cls = db_->classes()[src.cls];
    const Travel& t = db_->travel(w);
    mean[cls][0] += t[0], mean[cls][1] += t[1], mean[cls][2] += t[3];
    ++count[cls];
  }
  for (auto& [cls, m] : mean)
    for (double& v : m) v /= count[cls];
  std::printf("[ figures  ] head speed 0.2 s / 0.6 s (m/s), height / body height: running %.2f / %.2f, %.2f; walking "
              "%.2f / %.2f, %.2f; boxing %.2f / %.2f, %.2f\n",
              mean["running"][0], mean["running"][1], mean["running"][2], mean["walking"][0], mean["walking"][1],
              mean["walking"][2], mean["boxing"][0], mean["boxing"][1], mean["boxing"][2]);
  EXPECT_GT(mean["running"][1], mean["walking"][1]);
  EXPECT_GT(mean["walking"][1], mean["boxing"][1]);
  EXPECT_GT(mean["walking"][1], 0.8);  // CMU walks: about 1.2-1.4 m/s
  EXPECT_LT(mean["walking"][1], 2.0);
  for (const char* cls : {"walking", "running", "boxing"}) {
    EXPECT_GT(mean[cls][2], 0.85) << cls;
    EXPECT_LT(mean[cls][2], 1.0) << cls;
  }
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
  // A bit flipped in either half of the checksum (format 9: the halves hashed
  // apart, on two threads for a file of this size, 1 MB or more).
  ASSERT_GE(good.size(), std::size_t{1} << 20);
  for (std::size_t at : {good.size() / 2 - 1, good.size() / 2, good.size() / 3, 2 * good.size() / 3}) {
    auto one = good;
    one[at] ^= std::byte{0x01};
    expect_error(one, "checksum");
  }
  auto version = good;
  version[8] = std::byte{10};  // the version field follows the 8-byte magic
  expect_error(version, "format version 10, but this legwork reads version 9");
  auto old = good;
  old[8] = std::byte{1};  // a version 1 file (no foot contacts): rebuild
  expect_error(old, "format version 1, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  auto v2 = good;
  v2[8] = std::byte{2};  // a version 2 file (no stored search index): rebuild
  expect_error(v2, "format version 2, but this legwork reads version 9; rebuild it");
  auto v3 = good;
  v3[8] = std::byte{3};  // a version 3 file (FNV-1a checksum): rebuild
  expect_error(v3, "format version 3, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  auto v4 = good;
  v4[8] = std::byte{4};  // a version 4 file (no head travel): rebuild
  expect_error(v4, "format version 4, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  auto v5 = good;
  v5[8] = std::byte{5};  // a version 5 file (100 ms windows, no stride): rebuild
  expect_error(v5, "format version 5, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  auto v6 = good;
  v6[8] = std::byte{6};  // a version 6 file (feature rows in window order, no row order): rebuild
  expect_error(v6, "format version 6, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  auto v7 = good;
  v7[8] = std::byte{7};  // a version 7 file (feature scale and projection in the JSON): rebuild
  expect_error(v7, "format version 7, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  auto v8 = good;
  v8[8] = std::byte{8};  // a version 8 file (the checksum in one pass): rebuild
  expect_error(v8, "format version 8, but this legwork reads version 9; rebuild it with 'legwork accent build'");
  auto magic = good;
  magic[0] = std::byte{'X'};
  expect_error(magic, "not a legwork accent database");
  expect_error({}, "empty");
  fs::remove(path);
  EXPECT_THROW((void)load_database(temp_file("missing.lwdb").string()), Error);
}

}  // namespace
}  // namespace legwork::accent
