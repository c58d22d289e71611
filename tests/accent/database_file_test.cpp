// Database files (reliability): saving replaces the file atomically, so a
// process that has the old one mapped keeps working; checksum-valid files
// with absurd contents are rejected by name.
#include <legwork/accent/database.hpp>
#include <legwork/io/text.hpp>

#include "../../src/accent/database_impl.hpp"
#include "accent_testing.hpp"  // the builder (its header moves with the module layout)
#include "database_file_util.hpp"

#include <legwork/accent/search.hpp>

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <limits>
#include <string>
#include <vector>

namespace legwork::accent {
namespace {


// Replaces the JSON number after `"key":` in the metadata by `value`, padded
// with spaces to the same length (so no offset moves).
void set_meta_number(std::vector<std::byte>& block, const std::string& key, const std::string& value) {
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  char* meta = reinterpret_cast<char*>(block.data() + h.meta_offset);
  std::string_view text(meta, h.meta_bytes);
  const auto at = text.find("\"" + key + "\":");
  ASSERT_NE(at, std::string_view::npos) << key;
  std::size_t b = at + key.size() + 3, e = b;
  while (e < text.size() && (std::isdigit(static_cast<unsigned char>(text[e])) || std::strchr(".-+eE", text[e]))) ++e;
  ASSERT_LE(value.size(), e - b) << key;
  std::string repl = value + std::string(e - b - value.size(), ' ');
  std::memcpy(meta + b, repl.data(), repl.size());
}

// Replaces the first `from` in the metadata by `to` (same length: no offset moves).
void replace_in_meta(std::vector<std::byte>& block, const std::string& from, const std::string& to) {
  ASSERT_EQ(from.size(), to.size());
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  char* meta = reinterpret_cast<char*>(block.data() + h.meta_offset);
  const auto at = std::string_view(meta, h.meta_bytes).find(from);
  ASSERT_NE(at, std::string_view::npos) << from;
  std::memcpy(meta + at, to.data(), to.size());
}

}  // namespace

TEST(DatabaseFile, MetadataErrorsNameTheFieldNotTheJsonLibrary) {
  const fs::path good = temp_dir() / "meta_good.lwdb", bad = temp_dir() / "meta_bad.lwdb";
  save_database(good.string(), testing::indexed_database({"walking/07_01"}));
  const std::vector<std::byte> block = read_all(good);
  const auto error_for = [&](const std::string& from, const std::string& to) {
    auto b = block;
    replace_in_meta(b, from, to);
    write_with_checksum(bad, b);
    return load_error(bad);
  };
  const std::string prefix = "accent database '" + bad.string() + "': ";
  EXPECT_EQ(error_for("\"hop\":", "\"hoq\":"), prefix + "metadata field 'build.hop' is missing; rebuild the database");
  EXPECT_EQ(error_for("\"mirrored\":false", "\"mirrored\":\"abc\""),
            prefix + "metadata field 'build.mirrored': expected true or false, found string; rebuild the database");
  EXPECT_EQ(error_for("\"height_m\":", "\"height_m\"["), prefix + "metadata is not valid JSON; rebuild the database");
  // A raw byte in the JSON: the library's message quoted it ("last read: '\xff...'").
  const std::string msg = error_for("{\"build\"", "\xff\"build\"");
  EXPECT_EQ(msg, prefix + "metadata is not valid JSON; rebuild the database");
}

TEST(DatabaseFile, SavingOverAMappedFileLeavesTheReaderIntact) {
  const fs::path path = temp_dir() / "mapped.lwdb";
  save_database(path.string(), testing::indexed_database({"walking/07_01", "running/09_01"}));
  const Database mapped = load_database(path.string());
  ASSERT_TRUE(mapped.is_mapped());
  const std::vector<std::byte> before(mapped.bytes().begin(), mapped.bytes().end());
  // A smaller database replaces it: truncating in place made the first
  // process's next page touch a SIGBUS.
  save_database(path.string(), testing::indexed_database({"walking/07_01"}));
  EXPECT_LT(fs::file_size(path), before.size());
  EXPECT_TRUE(std::equal(before.begin(), before.end(), mapped.bytes().begin()));
  EXPECT_EQ(load_database(path.string()).trials().size(), 1u);
  // Nothing left behind but the database itself.
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(temp_dir()))
    if (e.path().filename().string().rfind("mapped.lwdb", 0) == 0) ++files;
  EXPECT_EQ(files, 1);
  EXPECT_EQ(fs::status(path).permissions() & fs::perms::others_read, fs::perms::others_read);
}

TEST(DatabaseFile, SavingIntoAMissingFolderIsAClearError) {
  const fs::path path = temp_dir() / "no-such-folder" / "x.lwdb";
  try {
    save_database(path.string(), testing::indexed_database({"walking/07_01"}));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write accent database '" + path.string() + "': No such file"),
              std::string::npos)
        << e.what();
  }
}

TEST(DatabaseFile, ChecksumValidButAbsurdContentsAreRejectedByName) {
  const fs::path good = temp_dir() / "good.lwdb", bad = temp_dir() / "bad.lwdb";
  save_database(good.string(), testing::indexed_database({"walking/07_01"}));
  const std::vector<std::byte> block = read_all(good);
  ASSERT_EQ(load_error(good), "(no error)");
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);

  auto pose = block;  // a rotation of 1e38 (reported 'matched' with 42 cm error before)
  const float huge[4] = {1e38f, 0, 0, 1e38f};
  std::memcpy(pose.data() + h.pose_offset, huge, sizeof huge);
  write_with_checksum(bad, pose);
  EXPECT_NE(load_error(bad).find("pose 0 joint 'Hips' is not a finite unit quaternion"), std::string::npos)
      << load_error(bad);

  auto zero = block;  // a zero rotation fell back to neutral, also 'matched'
  std::memset(zero.data() + h.pose_offset + 16 * 5, 0, 16);
  write_with_checksum(bad, zero);
  EXPECT_NE(load_error(bad).find("pose 0 joint '"), std::string::npos) << load_error(bad);

  // The checksum pass scans every data section in cache-sized chunks; what it
  // flags is named by section and element.
  auto align = block;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(align.data() + h.align_offset + sizeof(AlignXZ) * 2 + 4, &nan, 4);
  write_with_checksum(bad, align);
  EXPECT_NE(load_error(bad).find("alignment point of window 2 is not finite"), std::string::npos) << load_error(bad);
  auto feature = block;
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(feature.data() + h.feature_offset[1] + sizeof(Feature) * 3, &inf, 4);
  write_with_checksum(bad, feature);
  std::uint32_t window_of_row3;  // rows are stored in the trees' leaf order (format 7): named by window
  std::memcpy(&window_of_row3, block.data() + h.order_offset + 4 * (std::size_t{h.window_count} + 3), 4);
  EXPECT_NE(load_error(bad).find("feature of window " + std::to_string(window_of_row3) + " is not finite"),
            std::string::npos)
      << load_error(bad);
  auto contact = block;
  contact[h.contact_offset + 5] = std::byte{2};
  write_with_checksum(bad, contact);
  EXPECT_NE(load_error(bad).find("foot contact of pose 2 is neither 0 nor 1"), std::string::npos) << load_error(bad);
  auto last = block;  // the last pose's last joint: the scan reaches the section's end
  std::memset(last.data() + h.pose_offset + std::size_t{h.pose_count} * h.joint_count * 16 - 16, 0, 16);
  write_with_checksum(bad, last);
  EXPECT_NE(load_error(bad).find("pose " + std::to_string(h.pose_count - 1) + " joint '"), std::string::npos) << load_error(bad);

  for (const auto& [key, value, expect] : {std::tuple{"height_m", "0", "height_m is 0.000000"},
                                           std::tuple{"typical_distance", "-1", "typical_distance is -1.000000"}}) {
    auto meta = block;
    set_meta_number(meta, key, value);
    write_with_checksum(bad, meta);
    const std::string msg = load_error(bad);
    EXPECT_NE(msg.find(expect), std::string::npos) << msg;
    EXPECT_NE(msg.find("rebuild the database"), std::string::npos) << msg;
  }
}

// A window's speed index picks the factor its candidate is played forward at
// (speeds[index] / hop): an index past the list read freed memory in
// accent::update (found by accent_db_fuzz in session 24, once its seed was of
// the current format), so the index, the list and the hop are checked at load.
TEST(DatabaseFile, AWindowsSpeedIndexTheHopAndTheSpeedListAreChecked) {
  const fs::path good = temp_dir() / "speed.lwdb", bad = temp_dir() / "speed-bad.lwdb";
  save_database(good.string(), testing::indexed_database({"walking/07_01"}));
  const auto block = read_all(good);
  ASSERT_EQ(load_error(good), "(no error)");
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  // The load error after `mutate` changes a copy of the good block (checksum rewritten).
  auto error_after = [&](auto mutate) {
    auto x = block;
    mutate(x);
    write_with_checksum(bad, x);
    return load_error(bad);
  };
  auto expect_error = [](const std::string& msg, const std::string& what) {
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  };
  expect_error(error_after([&](auto& x) {  // 3 factors: 0..2
                 x[h.source_offset + 5 * sizeof(WindowSource) + offsetof(WindowSource, speed)] = std::byte{3};
               }),
               "window 5 refers to a missing pose, trial, class or speed");
  expect_error(error_after([](auto& x) { set_meta_number(x, "hop", "0"); }),
               "build hop is 0, expected a whole number from 1 to 10000; rebuild the database");
  expect_error(error_after([](auto& x) { replace_in_meta(x, "\"speeds\":[1.0,0.5,1.5]", "\"speeds\":[1.0,0.5,9e9]"); }),
               "a build speed factor is 9000000000.000000, expected a finite value in (0, 100.000000]");
  expect_error(error_after([](auto& x) { replace_in_meta(x, "\"speeds\":[1.0,0.5,1.5]", "\"speeds\":[           ]"); }),
               "build speeds list has 0 factors, expected 1 to 256");
}

// Format 6 stores the feature windows' stride: a file whose windows were taken
// at another stride would match the live windows silently wrong, so it is
// refused by name (checksum valid).
TEST(DatabaseFile, AFileOfAnotherWindowStrideIsRefusedByName) {
  const fs::path good = temp_dir() / "stride.lwdb", bad = temp_dir() / "stride-bad.lwdb";
  save_database(good.string(), testing::indexed_database({"walking/07_01"}));
  auto block = read_all(good);
  ASSERT_EQ(load_error(good), "(no error)");
  set_meta_number(block, "stride", std::to_string(kStride + 1));
  write_with_checksum(bad, block);
  EXPECT_NE(load_error(bad).find("window stride differs from this build's " + std::to_string(kStride)), std::string::npos)
      << load_error(bad);
}

// Format 8 stores the feature scale and projection as a binary section of
// doubles: they read back bit for bit (a 17-digit JSON round trip was exact
// too, but cost three quarters of the fuzz target's time), the metadata no
// longer holds them, and a section outside the file or a non-finite value in
// it is refused by name (checksum valid).
TEST(DatabaseFile, TheFeatureSpaceIsABinarySectionCheckedByName) {
  const fs::path good = temp_dir() / "space.lwdb", bad = temp_dir() / "space-bad.lwdb";
  const Database built = testing::indexed_database({"walking/07_01"});
  save_database(good.string(), built);
  const auto block = read_all(good);
  const Database loaded = load_database(good.string());
  EXPECT_EQ(std::memcmp(loaded.feature_space().scale.data(), built.feature_space().scale.data(),
                        sizeof built.feature_space().scale), 0);
  EXPECT_EQ(std::memcmp(loaded.feature_space().projection.data(), built.feature_space().projection.data(),
                        sizeof built.feature_space().projection), 0);
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  const std::string_view meta(reinterpret_cast<const char*>(block.data() + h.meta_offset), h.meta_bytes);
  EXPECT_EQ(meta.find("\"projection\""), std::string_view::npos);
  EXPECT_EQ(meta.find("\"scale\""), std::string_view::npos);
  EXPECT_LT(h.meta_bytes, 4000u) << "the metadata of a one-trial database is its skeleton and trial list";

  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto projection = block;
  std::memcpy(projection.data() + h.space_offset + 8 * (kRawDim + 5), &nan, 8);
  write_with_checksum(bad, projection);
  EXPECT_NE(load_error(bad).find("feature projection is not finite"), std::string::npos) << load_error(bad);
  auto scale = block;
  std::memcpy(scale.data() + h.space_offset + 8 * 3, &nan, 8);
  write_with_checksum(bad, scale);
  EXPECT_NE(load_error(bad).find("feature scale is not finite"), std::string::npos) << load_error(bad);
  auto outside = block;
  h.space_offset = h.file_bytes - 64;
  std::memcpy(outside.data(), &h, sizeof h);
  write_with_checksum(bad, outside);
  EXPECT_NE(load_error(bad).find("section 'feature space' lies outside the file (truncated?)"), std::string::npos)
      << load_error(bad);
}

// Format 7 stores each hand's feature rows in its trees' leaf order and the
// window of each row beside them. The rows are a real reordering (not the
// identity), the stored trees' permutation is the identity, every feature
// reads back by window as the builder made it, and a row order that is not a
// permutation inside each class's windows is refused by name.
TEST(DatabaseFile, FeatureRowsAreStoredInLeafOrderAndTheirOrderIsChecked) {
  const fs::path good = temp_dir() / "order.lwdb", bad = temp_dir() / "order-bad.lwdb";
  const Database built = testing::indexed_database({"walking/07_01", "boxing/13_18"});
  save_database(good.string(), built);
  const auto block = read_all(good);
  ASSERT_EQ(load_error(good), "(no error)");
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  const std::size_t n = h.window_count;
  ASSERT_EQ(built.class_count(), 2);
  std::vector<std::uint32_t> order(2 * n);  // window of each row, per hand (the row of each window follows)
  std::memcpy(order.data(), block.data() + h.order_offset, 8 * n);
  std::size_t moved = 0;
  for (std::size_t r = 0; r < 2 * n; ++r) moved += order[r] != r % n;
  EXPECT_GT(moved, n / 2) << "rows in leaf order differ from window order";

  const Database loaded = load_database(good.string());
  const auto& d = loaded.impl();
  for (std::size_t c = 0; c < 2; ++c)
    for (int hand = 0; hand < 2; ++hand) {
      const auto& perm = d.index[c].tree[static_cast<std::size_t>(hand)]->vAcc;
      for (std::size_t i = 0; i < perm.size(); ++i) ASSERT_EQ(perm[i], i) << "class " << c << " hand " << hand;
    }
  // By window, each feature is the one the row order names.
  for (int hand = 0; hand < 2; ++hand)
    for (std::size_t r = 0; r < n; ++r) {
      const Feature& by_window = loaded.feature(hand, static_cast<int>(order[static_cast<std::size_t>(hand) * n + r]));
      ASSERT_EQ(std::memcmp(by_window.data(), block.data() + h.feature_offset[hand] + r * sizeof(Feature), sizeof(Feature)), 0);
    }

  const int a = built.class_range(1).first;  // boxing's first window
  ASSERT_GT(a, 0);
  auto with = [&](std::size_t at, std::uint32_t value) {  // at: index into the four u32 arrays
    auto x = block;
    std::memcpy(x.data() + h.order_offset + 4 * at, &value, 4);
    write_with_checksum(bad, x);
    return load_error(bad);
  };
  const auto ua = static_cast<std::uint32_t>(a);
  const std::size_t row_of_a = 2 * n + ua;  // left hand's row of window a
  std::uint32_t row;
  std::memcpy(&row, block.data() + h.order_offset + 4 * row_of_a, 4);
  // Window a's row moved into walking's rows, past the end, and onto another window's row.
  EXPECT_EQ(with(row_of_a, 0), "accent database '" + bad.string() + "': left-hand row order: window " + std::to_string(a) +
                                   "'s row 0 is outside its class's rows; rebuild the database");
  EXPECT_NE(with(row_of_a, 0xffffffffu).find("window " + std::to_string(a) + "'s row 4294967295 is outside its class's rows"),
            std::string::npos);
  EXPECT_NE(with(row_of_a, row + 1 < n ? row + 1 : row - 1).find("left-hand row order: window "), std::string::npos);
  // A row that names another window than the one whose row it is (right hand).
  std::uint32_t right_row;
  std::memcpy(&right_row, block.data() + h.order_offset + 4 * (3 * n + ua), 4);
  EXPECT_NE(with(n + right_row, ua + 1).find("right-hand row order: window " + std::to_string(a) + "'s row " +
                                              std::to_string(right_row) + " holds window " + std::to_string(a + 1)),
            std::string::npos)
      << with(n + right_row, ua + 1);

  // Class ranges that overlap would leave windows whose rows nobody checked.
  auto overlap = block;
  const std::string from = "[[0," + std::to_string(a) + "],[" + std::to_string(a) + ",";
  const std::string to = "[[0," + std::to_string(a + 1) + "],[" + std::to_string(a) + ",";
  ASSERT_EQ(from.size(), to.size());
  replace_in_meta(overlap, from, to);
  write_with_checksum(bad, overlap);
  EXPECT_NE(load_error(bad).find("class window ranges do not follow each other (a class starts at window " +
                                 std::to_string(a) + ", expected " + std::to_string(a + 1) + ")"),
            std::string::npos)
      << load_error(bad);
}

}  // namespace legwork::accent
