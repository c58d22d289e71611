#include <legwork/io/catalogue.hpp>

#include <legwork/core/types.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace legwork::io {
namespace fs = std::filesystem;

namespace {

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, '\t')) out.push_back(cell);
  if (!line.empty() && line.back() == '\t') out.emplace_back();
  return out;
}

std::string strip_cr(std::string s) {
  if (!s.empty() && s.back() == '\r') s.pop_back();
  return s;
}

int parse_int(const std::string& cell, const std::string& where, const char* field) {
  try {
    std::size_t used = 0;
    const int v = std::stoi(cell, &used);
    if (used == cell.size()) return v;
  } catch (const std::exception&) {
  }
  throw Error(where + ": field '" + field + "' is not an integer: '" + cell + "'");
}

// "16_21.bvh" -> subject 16, trial 21.
bool parse_cmu_name(const std::string& stem, int& subject, int& trial) {
  const auto us = stem.find('_');
  if (us == std::string::npos) return false;
  try {
    std::size_t a = 0, b = 0;
    subject = std::stoi(stem.substr(0, us), &a);
    trial = std::stoi(stem.substr(us + 1), &b);
    return a == us && b == stem.size() - us - 1;
  } catch (const std::exception&) {
    return false;
  }
}

std::vector<TrialEntry> from_manifest(const fs::path& manifest, const fs::path& root) {
  std::ifstream in(manifest);
  if (!in) throw Error(manifest.string() + ": cannot open the manifest");
  std::string line;
  if (!std::getline(in, line)) throw Error(manifest.string() + ": empty manifest");
  const auto head = split_tabs(strip_cr(line));
  auto col = [&](const char* name) {
    const auto it = std::find(head.begin(), head.end(), name);
    if (it == head.end())
      throw Error(manifest.string() + ":1: no '" + name + "' column (need file, class, subject, trial; tab-separated)");
    return static_cast<std::size_t>(it - head.begin());
  };
  const std::size_t cf = col("file"), cc = col("class"), cs = col("subject"), ct = col("trial");
  std::vector<TrialEntry> out;
  int lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    line = strip_cr(line);
    if (line.empty()) continue;
    const auto cells = split_tabs(line);
    const std::string where = manifest.string() + ":" + std::to_string(lineno);
    if (cells.size() <= std::max({cf, cc, cs, ct}))
      throw Error(where + ": " + std::to_string(cells.size()) + " cells, fewer than the header's columns");
    TrialEntry e;
    e.file = cells[cf];
    e.cls = cells[cc];
    e.subject = parse_int(cells[cs], where, "subject");
    e.trial = parse_int(cells[ct], where, "trial");
    e.path = (root / e.file).string();
    if (!fs::exists(e.path)) throw Error(where + ": file '" + e.file + "' not found under " + root.string());
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<TrialEntry> from_folders(const fs::path& root, bool cmu_names) {
  std::vector<TrialEntry> out;
  for (const auto& top : fs::directory_iterator(root)) {
    if (!top.is_directory() || top.path().filename().string().rfind("bvh", 0) != 0) continue;
    for (const auto& cls : fs::directory_iterator(top.path())) {
      if (!cls.is_directory()) continue;
      for (const auto& f : fs::directory_iterator(cls.path())) {
        if (f.path().extension() != ".bvh") continue;
        TrialEntry e;
        e.cls = cls.path().filename().string();
        // Lexically: fs::relative resolves symbolic links, so a linked class
        // folder gave "../../<link target>/x.bvh" instead of "bvh/<class>/x.bvh".
        e.file = f.path().lexically_relative(root).string();
        e.path = f.path().string();
        if (!parse_cmu_name(f.path().stem().string(), e.subject, e.trial)) {
          if (cmu_names)
            throw Error(e.path + ": file name is not SUBJECT_TRIAL.bvh; give a --manifest with subject and trial columns");
          e.subject = e.trial = 0;  // unknown; callers that need subjects ask for cmu_names
        }
        out.push_back(std::move(e));
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const TrialEntry& a, const TrialEntry& b) { return a.file < b.file; });
  return out;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace

std::string TrialEntry::id() const {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02d_%02d", subject, trial);
  return buf;
}

std::vector<std::string> Catalogue::classes() const {
  std::set<std::string> s;
  for (const auto& t : trials) s.insert(t.cls);
  return {s.begin(), s.end()};
}

Catalogue read_catalogue(const std::string& dir, const std::string& manifest, const std::vector<std::string>& classes,
                         bool cmu_names) {
  const fs::path root(dir);
  if (!fs::is_directory(root)) throw Error(dir + ": not a directory");
  Catalogue c;
  c.root = dir;
  if (!manifest.empty()) c.trials = from_manifest(manifest, root);
  else if (fs::exists(root / "MANIFEST.tsv")) c.trials = from_manifest(root / "MANIFEST.tsv", root);
  else c.trials = from_folders(root, cmu_names);
  if (c.trials.empty()) throw Error(dir + ": no BVH trials found (expected MANIFEST.tsv or bvh*/<class>/*.bvh)");
  if (!classes.empty()) {
    const auto present = c.classes();
    for (const auto& want : classes)
      if (std::find(present.begin(), present.end(), want) == present.end())
        throw Error(dir + ": no class '" + want + "' (classes present: " + join(present) + ")");
    std::erase_if(c.trials, [&](const TrialEntry& t) {
      return std::find(classes.begin(), classes.end(), t.cls) == classes.end();
    });
  }
  return c;
}

}  // namespace legwork::io
