#include <legwork/io/data_files.hpp>

#include <legwork/core/types.hpp>

#include <unistd.h>
#include <vector>

namespace legwork::io {

namespace fs = std::filesystem;

fs::path find_repo_root(const std::string& marker) {
  std::vector<fs::path> starts{fs::current_path()};
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n > 0) starts.push_back(fs::path(std::string(buf, static_cast<std::size_t>(n))).parent_path());
  for (auto p : starts)
    for (int up = 0; up < 5 && !p.empty(); ++up, p = p.parent_path())
      if (fs::exists(p / marker)) return p;
  return {};
}

std::string sample_walk_file(const std::string& option) {
  const fs::path root = find_repo_root();
  if (root.empty())
    throw Error(option + " not given and the default data/cmu/bvh/walking/07_01.bvh was not found "
                "(run from the repository or pass " + option + " FILE.bvh)");
  return (root / "data" / "cmu" / "bvh" / "walking" / "07_01.bvh").string();
}

fs::path walking_data(std::string* note) {
  const fs::path root = find_repo_root();
  std::vector<fs::path> shared{fs::current_path() / ".." / "shared" / "data" / "cmu" / "bvh" / "walking"};
  if (!root.empty()) shared.push_back(root.parent_path() / "shared" / "data" / "cmu" / "bvh" / "walking");
  for (const auto& p : shared)
    if (fs::is_directory(p)) return fs::weakly_canonical(p);
  if (root.empty()) throw Error("--data not given and no walking trials found (../shared/data/cmu/bvh/walking or data/cmu/bvh/walking)");
  *note = "the full CMU walking set (../shared/data/cmu/bvh/walking) is absent: evaluating only the repo's sample trials";
  return root / "data" / "cmu" / "bvh" / "walking";
}

}  // namespace legwork::io
