// The KD-tree search index stored in the database file (format version 3,
// src/accent/database_index.cpp): loaded with the file, searching like
// rebuilt trees, and never trusted: damaged or bit-flipped sections are
// refused by name or fall back, and never crash the search.
#include <legwork/accent/database.hpp>
#include <legwork/accent/search.hpp>

#include "accent_testing.hpp"
#include "database_file_util.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace legwork::accent {
// The search index is stored in the file (format version 3): a loaded
// database has its KD-trees without building them, and they give the same
// exact neighbours as brute force and as trees rebuilt from the features.
TEST(DatabaseIndex, StoredIndexLoadsWithTheFileAndSearchesLikeRebuiltTrees) {
  const fs::path path = temp_dir() / "index.lwdb";
  save_database(path.string(), testing::indexed_database({"walking/07_01", "running/09_01", "boxing/13_18"}));
  LoadOptions lo;
  lo.verify_checksum = false;
  const Database loaded = load_database(path.string(), lo);
  ASSERT_TRUE(loaded.has_index());
  lo.build_index = false;
  Database rebuilt = load_database(path.string(), lo);
  ASSERT_FALSE(rebuilt.has_index());
  rebuilt.build_index(8);  // another leaf size: other trees, same neighbours
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> pick(0, loaded.window_count() - 1);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(loaded.typical_distance() / std::sqrt(kDim)));
  const std::vector<unsigned char> running_only = [&] {
    std::vector<unsigned char> m(static_cast<std::size_t>(loaded.class_count()), 0);
    m[static_cast<std::size_t>(loaded.find_class("running"))] = 1;
    return m;
  }();
  for (int q = 0; q < 100; ++q) {
    const int hand = q % 2;
    Feature f = loaded.feature(hand, pick(rng));
    for (auto& x : f) x += noise(rng);
    const std::span<const unsigned char> mask = q % 3 == 0 ? std::span<const unsigned char>(running_only) : std::span<const unsigned char>();
    std::array<Match, 8> brute, stored, other;
    const int nb = search_knn(loaded, hand, f, 8, SearchMode::BruteForce, 0, mask, brute);
    const int ns = search_knn(loaded, hand, f, 8, SearchMode::Exact, 0, mask, stored);
    const int no = search_knn(rebuilt, hand, f, 8, SearchMode::Exact, 0, mask, other);
    ASSERT_EQ(nb, 8);
    ASSERT_EQ(ns, nb);
    ASSERT_EQ(no, nb);
    for (std::size_t i = 0; i < 8; ++i) {
      EXPECT_NEAR(stored[i].distance, brute[i].distance, 1e-5f);
      EXPECT_NEAR(other[i].distance, brute[i].distance, 1e-5f);
    }
  }
  fs::remove(path);
}

namespace {

// Byte offset (in the block) of stored tree `t`'s serialization, and its size.
std::pair<std::size_t, std::size_t> stored_tree(const std::vector<std::byte>& block, std::size_t t) {
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  std::uint64_t e[3];
  std::memcpy(e, block.data() + h.index_offset + 32 + 24 * t, sizeof e);
  return {h.index_offset + e[0], e[1]};
}

std::string load_error_unverified(const fs::path& p) {
  LoadOptions lo;
  lo.verify_checksum = false;
  try {
    (void)load_database(p.string(), lo);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

// Declared sizes and indices in the index section are never trusted: with the
// checksum recomputed (or not verified) a damaged index is refused by name.
// The same database saves to the same bytes (reproducible builds, caches,
// checksums of artifacts): the stored trees held heap addresses (each node's
// child pointers) and uninitialised union bytes, so two saves differed in
// ~9,600 bytes of the sample database.
TEST(DatabaseIndex, TheSameDatabaseSavesToTheSameBytes) {
  const std::vector<std::string> trials = {"walking/07_01", "running/09_01", "boxing/13_18"};
  const Database first = testing::indexed_database(trials);
  const Database second = testing::indexed_database(trials);  // built while the first is alive: other addresses
  const fs::path a = temp_dir() / "same_a.lwdb", b = temp_dir() / "same_b.lwdb", c = temp_dir() / "same_c.lwdb";
  save_database(a.string(), first);
  save_database(b.string(), second);
  const std::vector<std::byte> bytes = read_all(a);
  EXPECT_TRUE(bytes == read_all(b)) << "two builds of the same trials saved different bytes";
  save_database(c.string(), load_database(a.string()));  // loaded, then saved again
  EXPECT_TRUE(bytes == read_all(c)) << "a loaded database saved again differs from its file";
  // ...and the canonical file still loads with its index and searches.
  const Database loaded = load_database(c.string());
  ASSERT_TRUE(loaded.has_index());
  std::array<Match, 4> m;
  EXPECT_EQ(search_knn(loaded, 0, loaded.feature(0, 10), 4, SearchMode::Exact, 0, {}, m), 4);
  EXPECT_EQ(m[0].distance, 0.0f);
  for (const auto& p : {a, b, c}) fs::remove(p);
}

TEST(DatabaseIndex, DamagedStoredIndexIsRejectedByName) {
  const fs::path good = temp_dir() / "index_good.lwdb", bad = temp_dir() / "index_bad.lwdb";
  save_database(good.string(), testing::indexed_database({"walking/07_01", "running/09_01"}));
  const std::vector<std::byte> block = read_all(good);
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  ASSERT_GT(h.index_bytes, 0u);
  auto expect = [&](std::vector<std::byte> b, const std::string& what) {
    write_with_checksum(bad, std::move(b));
    for (const std::string& msg : {load_error(bad), load_error_unverified(bad)}) {
      EXPECT_NE(msg.find(what), std::string::npos) << msg;
      EXPECT_NE(msg.find(bad.string()), std::string::npos) << msg;
    }
  };
  auto with_header = [&](auto edit) {
    auto b = block;
    FileHeader x = h;
    edit(x);
    std::memcpy(b.data(), &x, sizeof x);
    return b;
  };
  expect(with_header([](FileHeader& x) { x.index_bytes = 16; }), "search index section is 16 bytes (truncated)");
  expect(with_header([](FileHeader& x) { x.index_bytes = x.file_bytes; }), "section 'search index' lies outside the file");
  expect(with_header([](FileHeader& x) { x.index_bytes = 40; }), "tree table runs past the section");
  const auto [tree0, tree0_bytes] = stored_tree(block, 0);
  auto permutation = block;  // tree 0's first point index, after count, dims, box, leaf size, vector size
  const std::uint32_t far = 0x7fffffff;
  std::memcpy(permutation.data() + tree0 + 8 + 4 + 8 * kTreeDim + 8 + 8, &far, 4);
  expect(permutation, "search index tree 0: permutation entry 0 is out of range or repeated");
  auto points = block;  // tree 1 declares one point more than the database has windows
  std::uint64_t n = 0;
  std::memcpy(&n, points.data() + h.index_offset + 32 + 24 + 16, 8);
  ++n;
  std::memcpy(points.data() + h.index_offset + 32 + 24 + 16, &n, 8);
  expect(points, "search index tree 1 declares");
  auto tail = block;  // the last node of tree 0 loses a child: the node list no longer ends where declared
  std::memset(tail.data() + tree0 + tree0_bytes - 8, 0xab, 8);
  const std::string msg = (write_with_checksum(bad, tail), load_error(bad));
  EXPECT_NE(msg.find("search index tree 0"), std::string::npos) << msg;
  fs::remove(good);
  fs::remove(bad);
}

// Random bit flips in the index section (checksum not verified): the load
// either refuses the file with a message or gives trees that only return
// windows of the database; it never crashes.
TEST(DatabaseIndex, BitFlippedStoredIndexNeverCrashesTheSearch) {
  const fs::path good = temp_dir() / "flip_good.lwdb", bad = temp_dir() / "flip_bad.lwdb";
  save_database(good.string(), testing::indexed_database({"walking/07_01", "running/09_01"}));
  const std::vector<std::byte> block = read_all(good);
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::size_t> at(h.index_offset, h.index_offset + h.index_bytes - 1);
  std::uniform_int_distribution<int> bit(0, 7);
  LoadOptions lo;
  lo.verify_checksum = false;
  int refused = 0, loaded = 0;
  for (int i = 0; i < 300; ++i) {
    auto b = block;
    b[at(rng)] ^= std::byte{static_cast<unsigned char>(1u << bit(rng))};
    write_with_checksum(bad, b);
    try {
      const Database db = load_database(bad.string(), lo);
      ++loaded;
      std::array<Match, 8> m;
      for (int hand = 0; hand < 2; ++hand) {
        const int k = search_knn(db, hand, db.feature(hand, 7), 8, SearchMode::Exact, 0, {}, m);
        for (int j = 0; j < k; ++j) ASSERT_LT(static_cast<unsigned>(m[static_cast<std::size_t>(j)].window), static_cast<unsigned>(db.window_count()));
      }
    } catch (const Error& e) {
      ++refused;
      EXPECT_NE(std::string(e.what()).find("search index"), std::string::npos) << e.what();
    }
  }
  std::printf("[ figures  ] 300 bit flips in the stored index: %d refused, %d loaded (flips in split values or padding)\n",
              refused, loaded);
  EXPECT_GT(refused, 0);
  fs::remove(good);
  fs::remove(bad);
}

}  // namespace legwork::accent
