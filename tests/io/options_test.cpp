// Option values checked before any work: number lists and output folders,
// with messages that name the option and what it expects.
#include <legwork/io/options.hpp>

#include <legwork/core/types.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "error_message.hpp"

using namespace legwork;

using legwork::testdata::message_of;

namespace {

std::filesystem::path options_dir() {
  const auto d = std::filesystem::temp_directory_path() / ("legwork_options_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace

TEST(Options, NumberListsNameTheOptionAndTheExpectedForm) {
  EXPECT_EQ(io::parse_number_list(" 1, 1 ,0.5", 3, "--weights", "p,v,a"), (std::vector<double>{1, 1, 0.5}));
  // std::stod used to surface as "error: stod".
  EXPECT_EQ(message_of([] { io::parse_number_list("a,b,c", 3, "--weights", "p,v,a such as 1,1,0.5"); }),
            "--weights 'a,b,c': 'a' is not a number; expected p,v,a such as 1,1,0.5");
  EXPECT_EQ(message_of([] { io::parse_number_list("1,2", 3, "--weights", "p,v,a"); }),
            "--weights '1,2': expected 3 numbers p,v,a, found 2");
  EXPECT_EQ(message_of([] { io::parse_number_list("1,,2", 3, "--weights", "p,v,a"); }),
            "--weights '1,,2': '' is not a number; expected p,v,a");
  EXPECT_EQ(message_of([] { io::parse_number_list("1,2,1e999", 3, "--weights", "p,v,a"); }),
            "--weights '1,2,1e999': '1e999' is not a number; expected p,v,a");
  EXPECT_EQ(message_of([] { io::parse_number_list("1,2,3x", 3, "--weights", "p,v,a"); }),
            "--weights '1,2,3x': '3x' is not a number; expected p,v,a");
}

TEST(Options, OutputFoldersAreCheckedBeforeAnyWork) {
  const std::string file = (options_dir() / "not_a_folder.txt").string();
  std::ofstream(file) << "x";
  EXPECT_EQ(message_of([&] { io::require_writable_folder(file, "--out"); }), "--out '" + file + "': is a file, not a folder");
  EXPECT_EQ(message_of([&] { io::require_writable_folder(file + "/report", "--out"); }),
            "--out '" + file + "/report': cannot write in '" + file + "' (it is a file, not a folder)");
  // A folder that does not exist yet, below a writable one, is fine (and is not created here).
  const auto fresh = options_dir() / "fresh" / "deeper";
  std::filesystem::remove_all(options_dir() / "fresh");
  EXPECT_EQ(message_of([&] { io::require_writable_folder(fresh.string(), "--out"); }), "(no error)");
  EXPECT_FALSE(std::filesystem::exists(fresh));
  EXPECT_EQ(message_of([&] { io::require_writable_folder(options_dir().string(), "--out"); }), "(no error)");
  // Not writable: /proc refuses new folders even to root.
  const std::string msg = message_of([] { io::require_writable_folder("/proc/legwork-report", "--out"); });
  EXPECT_EQ(msg.rfind("--out '/proc/legwork-report': cannot write in '/proc' (", 0), 0u) << msg;
  std::filesystem::remove_all(options_dir());
}

TEST(Options, NumberListsKeepSignsExponentsAndOrder) {
  // strtod's forms, each item exactly as written, in order.
  EXPECT_EQ(io::parse_number_list("-2.5,1e-3, +4 ", 3, "--w", "a,b,c"), (std::vector<double>{-2.5, 0.001, 4}));
  EXPECT_EQ(io::parse_number_list("7", 1, "--n", "n"), std::vector<double>{7});
  EXPECT_EQ(message_of([] { io::parse_number_list("", 1, "--n", "n"); }), "--n '': '' is not a number; expected n");
  EXPECT_EQ(message_of([] { io::parse_number_list("1,2,", 2, "--w", "a,b"); }), "--w '1,2,': '' is not a number; expected a,b");
  EXPECT_EQ(message_of([] { io::parse_number_list("nan,1", 2, "--w", "a,b"); }), "--w 'nan,1': 'nan' is not a number; expected a,b");
}

TEST(Options, TheWriteProbeLeavesNothingBehind) {
  const auto dir = options_dir() / "probe";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  io::require_writable_folder((dir / "new").string(), "--out");
  io::require_writable_folder(dir.string(), "--out");
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(options_dir());
}
