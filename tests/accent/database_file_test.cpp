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
  EXPECT_NE(load_error(bad).find("feature of window 3 is not finite"), std::string::npos) << load_error(bad);
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

}  // namespace legwork::accent
