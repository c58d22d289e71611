#pragma once
// A catalogue of motion-capture trials in a folder laid out like
// ../shared/data/cmu: MANIFEST.tsv (tab-separated, columns file, class,
// subject, trial; others ignored) or, without one, DIR/bvh*/<class>/SS_TT.bvh.
// Offline code: throws legwork::Error naming the file and line at fault.
#include <string>
#include <vector>

namespace legwork::io {

struct TrialEntry {
  std::string path;  // absolute or relative to the working directory
  std::string file;  // as listed (relative to the data folder)
  std::string cls;
  int subject = 0, trial = 0;
  std::string id() const;  // "SS_TT", e.g. "16_21"
};

struct Catalogue {
  std::string root;  // the data folder
  std::vector<TrialEntry> trials;
  std::vector<std::string> classes() const;  // sorted, unique
};

// Reads DIR's trials: from `manifest` if given, else DIR/MANIFEST.tsv if it
// exists, else every DIR/bvh*/<class>/*.bvh (subject and trial from the
// "SS_TT" file name; with cmu_names false, other names get subject 0 instead
// of an error). Only `classes` are kept (empty = all); an unknown class name
// is an error listing the classes present.
Catalogue read_catalogue(const std::string& dir, const std::string& manifest = "",
                         const std::vector<std::string>& classes = {}, bool cmu_names = true);

}  // namespace legwork::io
