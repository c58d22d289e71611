// File-name extension helper (src/core/files.cpp).
#include <legwork/core/files.hpp>

#include "testdata.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>

using namespace legwork;

TEST(ExtensionOf, LowerCaseWithTheDot) {
  EXPECT_EQ(extension_of("walk.bvh"), ".bvh");
  EXPECT_EQ(extension_of("/data/cmu/WALK.BVH"), ".bvh");
  EXPECT_EQ(extension_of("out/avatar.GlB"), ".glb");
  EXPECT_EQ(extension_of("archive.tar.gz"), ".gz");  // only the last one
  EXPECT_EQ(extension_of("trailing."), ".");
}

TEST(ExtensionOf, NoExtensionIsEmptyEvenWhenADirectoryHasADot) {
  EXPECT_EQ(extension_of("Makefile"), "");
  EXPECT_EQ(extension_of(""), "");
  EXPECT_EQ(extension_of("runs.v2/output"), "");
  EXPECT_EQ(extension_of("C:\\runs.v2\\output"), "");
  EXPECT_EQ(extension_of("C:\\runs\\take.CSV"), ".csv");
  EXPECT_EQ(extension_of("../data/x"), "");
}

TEST(ExtensionOf, AgreesWithTheFilesystemOnTheShippedData) {
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(testdata::sample("cmu"))) {
    if (!e.is_regular_file()) continue;
    ++files;
    std::string ext = e.path().extension().string();
    for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(extension_of(e.path().string()), ext) << e.path();
  }
  EXPECT_GT(files, 10);
}
