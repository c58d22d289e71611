// File helpers: every failure names the path and says what is wrong, in
// words a user can act on (never "std::bad_alloc" for a directory).
#include <legwork/io/text.hpp>

#include "testdata.hpp"

#include <legwork/core/types.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace legwork;

namespace {

std::filesystem::path text_dir() {
  const auto d = std::filesystem::temp_directory_path() / "legwork_text_test";
  std::filesystem::create_directories(d);
  return d;
}

std::string write_bytes(const std::string& name, const std::string& bytes) {
  const auto p = (text_dir() / name).string();
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

std::string error_of(const std::string& path) {
  try {
    io::read_text_file(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Text, DirectoryIsNamedNotABadAlloc) {
  // An ifstream opens a directory on Linux and reports a size of 2^63.
  const std::string dir = text_dir().string();
  EXPECT_EQ(error_of(dir), dir + ": is a directory, not a file");
}

TEST(Text, MissingFileSaysWhy) {
  const std::string p = (text_dir() / "no-such-file.bvh").string();
  EXPECT_EQ(error_of(p), p + ": cannot open file (No such file or directory)");
}

TEST(Text, Utf16AndUtf32AreNamed) {
  const std::string le = write_bytes("le.csv", std::string("\xFF\xFEt\0i\0m\0e\0", 10));
  EXPECT_EQ(error_of(le), le + ": UTF-16 text; save it as UTF-8");
  const std::string be = write_bytes("be.csv", std::string("\xFE\xFF\0t\0i", 6));
  EXPECT_EQ(error_of(be), be + ": UTF-16 text; save it as UTF-8");
  const std::string u32 = write_bytes("u32.csv", std::string("\xFF\xFE\0\0t\0\0\0", 8));
  EXPECT_EQ(error_of(u32), u32 + ": UTF-32 text; save it as UTF-8");
}

TEST(Text, LegworksBinaryFilesAreNamedWhereTextIsRead) {
  // Real files: a database the engine loads and a GLB legwork wrote (the fuzz seeds).
  const std::string db = (testdata::source_dir() / "tests/accent/data/format4_boxing.lwdb").string();
  EXPECT_EQ(error_of(db), db + ": a legwork accent database (binary .lwdb), not a text file; 'legwork info " + db +
                              "' describes it, 'legwork accent run --db' uses it");
  const std::string glb = (testdata::source_dir() / "fuzz/corpus/glb/07_01.glb").string();
  EXPECT_EQ(error_of(glb), glb + ": a binary glTF (.glb), not a text file; name it .glb where a motion is read");
}

TEST(Text, Utf8ByteOrderMarkIsDropped) {
  const std::string p = write_bytes("bom.csv", "\xEF\xBB\xBFtime\n0\n");
  EXPECT_EQ(io::read_text_file(p), "time\n0\n");
  // Binary reads keep every byte.
  EXPECT_EQ(io::read_binary_file(p).size(), 10u);
}

TEST(Text, PipesAndDevicesAreReadByStreaming) {
  // No size to trust: /dev/null reads as empty rather than failing.
  EXPECT_EQ(io::read_text_file("/dev/null"), "");
}

TEST(Text, WritingOverADirectoryIsNamed) {
  const std::string dir = text_dir().string();
  try {
    io::write_text_file(dir, "x");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not a file");
  }
}

TEST(Text, Utf8Validation) {
  EXPECT_TRUE(io::is_valid_utf8("Hips"));
  EXPECT_TRUE(io::is_valid_utf8("Wirbels\xC3\xA4ule"));        // 2 bytes
  EXPECT_TRUE(io::is_valid_utf8("\xE8\x85\xB0"));              // 3 bytes (CJK)
  EXPECT_TRUE(io::is_valid_utf8("\xF0\x9F\xA6\xB5"));          // 4 bytes (emoji leg)
  EXPECT_FALSE(io::is_valid_utf8("Sp\xE9ne"));                 // Latin-1
  EXPECT_FALSE(io::is_valid_utf8("\xC0\xAF"));                 // overlong '/'
  EXPECT_FALSE(io::is_valid_utf8("\xED\xA0\x80"));             // UTF-16 surrogate
  EXPECT_FALSE(io::is_valid_utf8("\xF4\x90\x80\x80"));         // past U+10FFFF
  EXPECT_FALSE(io::is_valid_utf8("\xE8\x85"));                 // truncated
}

TEST(Text, PrintableTextHidesControlBytes) {
  EXPECT_EQ(io::printable_text(std::string("a\0b\xff", 4)), "a?b?");
  EXPECT_EQ(io::printable_text("abcdef", 3), "abc...");
}

TEST(TextHelpers, SplitCommasDropsEmptyItems) {
  EXPECT_EQ(io::split_commas("a,b,,c,"), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_TRUE(io::split_commas("").empty());
}

TEST(TextHelpers, FrameRangesCountFromEitherEnd) {
  EXPECT_EQ(io::parse_frame_range("1:", 10), std::make_pair(1, 9));
  EXPECT_EQ(io::parse_frame_range(":-2", 10), std::make_pair(0, 8));
  EXPECT_EQ(io::parse_frame_range("4", 10), std::make_pair(4, 4));
  try {
    io::parse_frame_range("3:x", 10, "--strip");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--strip '3:x': expected A:B with whole numbers");
  }
  try {
    io::parse_frame_range("8:12", 10);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--frames '8:12' is outside the clip's frames 0:9");
  }
}

TEST(TextHelpers, RequireExtensionListsTheChoices) {
  EXPECT_NO_THROW(io::require_extension("--out", "a/b.PNG", {".png", ".svg"}));
  try {
    io::require_extension("--out", "b.gif", {".png", ".svg", ".mp4"});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--out 'b.gif' must end in .png, .svg or .mp4");
  }
}

TEST(TextHelpers, OutputFoldersAreMadeOnlyUnderTheWorkingFolder) {
  namespace fs = std::filesystem;
  const fs::path work = text_dir() / "work";
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path before = fs::current_path();
  fs::current_path(work);
  EXPECT_EQ(io::prepare_output("new/deeper/out.png", "--out"), "new/deeper/out.png");
  EXPECT_TRUE(fs::is_directory(work / "new" / "deeper"));
  std::string outside;
  try {
    io::prepare_output("../elsewhere-legwork-test/out.png", "--plot");
  } catch (const Error& e) {
    outside = e.what();
  }
  std::string absolute;
  try {
    io::prepare_output("/nonexistent-legwork-test/out.png", "--out");
  } catch (const Error& e) {
    absolute = e.what();
  }
  write_bytes("work/afile", "x");
  std::string file_parent;
  try {
    io::prepare_output("afile/out.png", "--out");
  } catch (const Error& e) {
    file_parent = e.what();
  }
  fs::current_path(before);
  EXPECT_EQ(outside, "--plot '../elsewhere-legwork-test/out.png': folder '../elsewhere-legwork-test' does not exist and is "
                     "outside the working folder; create it first");
  EXPECT_FALSE(fs::exists(text_dir() / "elsewhere-legwork-test"));
  EXPECT_EQ(absolute, "--out '/nonexistent-legwork-test/out.png': folder '/nonexistent-legwork-test' does not exist and is "
                      "outside the working folder; create it first");
  EXPECT_FALSE(fs::exists("/nonexistent-legwork-test"));
  EXPECT_EQ(file_parent, "--out 'afile/out.png': 'afile' is a file, not a folder");
}
