#pragma once
// Where tests find data: the repo's sample trials (always present) and the
// full shared CMU set (present on the project's machines; tests that need it
// skip with a clear message when it is absent).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace legwork::testdata {

inline std::filesystem::path source_dir() { return LEGWORK_SOURCE_DIR; }
// data/cmu inside the repo.
inline std::filesystem::path sample(const std::string& rel) { return source_dir() / "data" / rel; }
// ../shared/data/cmu, or $LEGWORK_SHARED_DATA/cmu if set.
inline std::filesystem::path shared_cmu() {
  if (const char* env = std::getenv("LEGWORK_SHARED_DATA")) return std::filesystem::path(env) / "cmu";
  return source_dir().parent_path() / "shared" / "data" / "cmu";
}
inline bool have_shared_cmu() { return std::filesystem::exists(shared_cmu() / "MANIFEST.tsv"); }

}  // namespace legwork::testdata

#define LEGWORK_REQUIRE_SHARED_CMU()                                                        \
  do {                                                                                      \
    if (!legwork::testdata::have_shared_cmu())                                              \
      GTEST_SKIP() << "shared CMU data not found at " << legwork::testdata::shared_cmu()    \
                   << " (set LEGWORK_SHARED_DATA); this test needs the full data set";      \
  } while (0)
