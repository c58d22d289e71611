// Trial catalogues: from the sample's MANIFEST.tsv, from a folder tree of
// SUBJECT_TRIAL.bvh files (which must agree with the manifest), class
// filtering, and errors that name the file, line and field at fault.
#include <legwork/io/catalogue.hpp>

#include <legwork/core/types.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>
#include <unistd.h>

#include "testdata.hpp"
#include "error_message.hpp"

using namespace legwork;
using io::Catalogue;
using io::read_catalogue;
namespace fs = std::filesystem;

using legwork::testdata::message_of;

namespace {

std::string sample_root() { return testdata::sample("cmu").string(); }

// A fresh, empty folder under the temp directory.
fs::path fresh_dir(const std::string& name) {
  const auto d = fs::temp_directory_path() / ("legwork_catalogue_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// The data lines of the sample manifest (header skipped), counted independently of the reader.
int manifest_rows() {
  std::ifstream in(testdata::sample("cmu/MANIFEST.tsv"));
  std::string line;
  int rows = -1;
  while (std::getline(in, line)) rows += !line.empty();
  return rows;
}

using Row = std::tuple<std::string, std::string, int, int>;
std::vector<Row> rows_of(const Catalogue& c) {
  std::vector<Row> out;
  for (const auto& t : c.trials) out.emplace_back(t.file, t.cls, t.subject, t.trial);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(Catalogue, FromTheManifest) {
  const Catalogue c = read_catalogue(sample_root());
  EXPECT_EQ(c.root, sample_root());
  EXPECT_EQ(static_cast<int>(c.trials.size()), manifest_rows());
  const auto classes = c.classes();
  EXPECT_TRUE(std::is_sorted(classes.begin(), classes.end()));
  EXPECT_EQ(std::set<std::string>(classes.begin(), classes.end()).size(), classes.size());
  EXPECT_NE(std::find(classes.begin(), classes.end(), "walking"), classes.end());
  for (const auto& t : c.trials) {
    EXPECT_TRUE(fs::exists(t.path)) << t.path;
    // The file name is SS_TT.bvh and the manifest's subject/trial columns agree with it.
    EXPECT_EQ(fs::path(t.file).stem().string(), t.id()) << t.file;
    EXPECT_EQ(fs::path(t.file).parent_path().filename().string(), t.cls) << t.file;
  }
  const Catalogue w = read_catalogue(sample_root(), "", {"walking", "running"});
  EXPECT_FALSE(w.trials.empty());
  int expected = 0;
  for (const auto& t : c.trials) expected += t.cls == "walking" || t.cls == "running";
  EXPECT_EQ(static_cast<int>(w.trials.size()), expected);
  for (const auto& t : w.trials) EXPECT_TRUE(t.cls == "walking" || t.cls == "running");
}

TEST(Catalogue, IdIsZeroPaddedSubjectAndTrial) {
  io::TrialEntry e;
  e.subject = 7;
  e.trial = 1;
  EXPECT_EQ(e.id(), "07_01");
  e.subject = 124;
  e.trial = 3;
  EXPECT_EQ(e.id(), "124_03");
}

TEST(Catalogue, FolderScanAgreesWithTheManifest) {
  // The sample's trial folders without its MANIFEST.tsv: subjects and trials
  // come from the file names. The folders are symbolic links (as a data
  // folder assembled from shared data is): `file` stays relative to the data
  // folder, not to where the links point.
  const auto dir = fresh_dir("folders");
  for (const char* top : {"bvh", "bvh_daz"}) fs::create_directory_symlink(fs::absolute(testdata::sample("cmu") / top), dir / top);
  const Catalogue scanned = read_catalogue(dir.string());
  EXPECT_EQ(rows_of(scanned), rows_of(read_catalogue(sample_root())));
  EXPECT_TRUE(std::is_sorted(scanned.trials.begin(), scanned.trials.end(),
                             [](const io::TrialEntry& a, const io::TrialEntry& b) { return a.file < b.file; }));
  // An explicit manifest wins over the folder scan.
  std::ofstream(dir / "mine.tsv") << "class\tfile\ttrial\tsubject\textra\r\n"
                                  << "walking\tbvh/walking/07_01.bvh\t1\t7\tignored\r\n";
  const Catalogue one = read_catalogue(dir.string(), (dir / "mine.tsv").string());
  ASSERT_EQ(one.trials.size(), 1u);
  EXPECT_EQ(rows_of(one), (std::vector<Row>{{"bvh/walking/07_01.bvh", "walking", 7, 1}}));
  EXPECT_EQ(one.trials[0].path, (dir / "bvh/walking/07_01.bvh").string());
  fs::remove_all(dir);
}

TEST(Catalogue, NonCmuFileNames) {
  const auto dir = fresh_dir("names");
  fs::create_directories(dir / "bvh" / "dance");
  std::ofstream(dir / "bvh" / "dance" / "salsa.bvh") << "";
  std::ofstream(dir / "bvh" / "dance" / "notes.txt") << "";  // not a trial
  const std::string path = (dir / "bvh" / "dance" / "salsa.bvh").string();
  EXPECT_EQ(message_of([&] { read_catalogue(dir.string()); }),
            path + ": file name is not SUBJECT_TRIAL.bvh; give a --manifest with subject and trial columns");
  const Catalogue c = read_catalogue(dir.string(), "", {}, false);
  EXPECT_EQ(rows_of(c), (std::vector<Row>{{"bvh/dance/salsa.bvh", "dance", 0, 0}}));
  fs::remove_all(dir);
}

TEST(Catalogue, ErrorsNameTheProblem) {
  const std::string root = sample_root();
  const std::string unknown = message_of([&] { read_catalogue(root, "", {"dancing"}); });
  // Lists the classes present.
  std::string present;
  for (const auto& c : read_catalogue(root).classes()) present += (present.empty() ? "" : ", ") + c;
  EXPECT_EQ(unknown, root + ": no class 'dancing' (classes present: " + present + ")");

  const auto dir = fresh_dir("errors");
  EXPECT_EQ(message_of([&] { read_catalogue(dir.string()); }),
            dir.string() + ": no BVH trials found (expected MANIFEST.tsv or bvh*/<class>/*.bvh)");
  EXPECT_EQ(message_of([&] { read_catalogue((dir / "missing").string()); }), (dir / "missing").string() + ": not a directory");
  const std::string manifest = (dir / "MANIFEST.tsv").string();
  const auto error_with = [&](const std::string& text) {
    std::ofstream(manifest) << text;
    return message_of([&] { read_catalogue(dir.string()); });
  };
  EXPECT_EQ(error_with(""), manifest + ": empty manifest");
  EXPECT_EQ(error_with("file\tclass\tsubject\na.bvh\twalking\t7\n"),
            manifest + ":1: no 'trial' column (need file, class, subject, trial; tab-separated)");
  EXPECT_EQ(error_with("file\tclass\tsubject\ttrial\na.bvh\twalking\tseven\t1\n"),
            manifest + ":2: field 'subject' is not an integer: 'seven'");
  EXPECT_EQ(error_with("file\tclass\tsubject\ttrial\n\na.bvh\twalking\t7\t1x\n"),
            manifest + ":3: field 'trial' is not an integer: '1x'");
  EXPECT_EQ(error_with("file\tclass\tsubject\ttrial\na.bvh\twalking\t7\n"),
            manifest + ":2: 3 cells, fewer than the header's columns");
  EXPECT_EQ(error_with("file\tclass\tsubject\ttrial\na.bvh\twalking\t7\t1\n"),
            manifest + ":2: file 'a.bvh' not found under " + dir.string());
  fs::remove_all(dir);
}
