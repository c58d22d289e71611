// Locating the repository's sample data and the shared set.
#include <legwork/io/data_files.hpp>

#include <gtest/gtest.h>

namespace legwork::io {
namespace {

TEST(DataFiles, FindsThisRepositoryAndItsSampleWalk) {
  // The test executable lives under the build tree inside the repository.
  const auto root = find_repo_root();
  ASSERT_FALSE(root.empty());
  EXPECT_TRUE(std::filesystem::equivalent(root, LEGWORK_SOURCE_DIR));
  EXPECT_TRUE(std::filesystem::exists(sample_walk_file("--clip")));
  EXPECT_TRUE(find_repo_root("no/such/marker.file").empty());
  std::string note;
  const auto data = walking_data(&note);
  EXPECT_TRUE(std::filesystem::is_directory(data));
  if (!note.empty()) {
    EXPECT_NE(note.find("absent"), std::string::npos);
  }
}

}  // namespace
}  // namespace legwork::io
