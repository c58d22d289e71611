#pragma once
// Locating legwork's own data from a command: the repository's sample data
// (data/cmu) and the shared CMU set beside it (../shared/data/cmu).
#include <filesystem>
#include <string>

namespace legwork::io {

// The repository root: the first of the working directory and the running
// executable's folder, or one of their ancestors (up to 5 levels), that
// holds `marker` (a path relative to the root). Empty if none does.
std::filesystem::path find_repo_root(const std::string& marker = "data/cmu/bvh/walking/07_01.bvh");

// The repository's sample walk data/cmu/bvh/walking/07_01.bvh. Throws
// legwork::Error naming `option` (the option that would give another file)
// when the repository is not found.
std::string sample_walk_file(const std::string& option);

// The shared CMU walking trials (../shared/data/cmu/bvh/walking, beside the
// working directory or the repository); when absent, the repository's sample
// walks with `*note` saying so. Throws legwork::Error if neither is found.
std::filesystem::path walking_data(std::string* note);

}  // namespace legwork::io
