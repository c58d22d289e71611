// An HTML page over a folder of results (see gallery.hpp).
#include <legwork/render/gallery.hpp>

#include <legwork/core/files.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace legwork::render {
namespace {

namespace fs = std::filesystem;

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// "file: caption" lines of DIR/README.txt.
std::map<std::string, std::string> read_captions(const fs::path& dir) {
  std::map<std::string, std::string> out;
  std::ifstream in(dir / "README.txt");
  std::string line;
  while (std::getline(in, line)) {
    auto colon = line.find(": ");
    if (colon != std::string::npos) out[line.substr(0, colon)] = line.substr(colon + 2);
  }
  return out;
}

std::string item_html(const fs::path& root, const fs::path& file, const std::string& caption) {
  const std::string rel = fs::relative(file, root).generic_string();
  const std::string ext = extension_of(file.string());
  std::ostringstream os;
  os << "<figure>";
  if (ext == ".png" || ext == ".svg")
    os << "<a href=\"" << html_escape(rel) << "\"><img src=\"" << html_escape(rel) << "\" loading=\"lazy\"></a>";
  else if (ext == ".mp4")
    os << "<video src=\"" << html_escape(rel) << "\" controls loop muted playsinline></video>";
  os << "<figcaption><a href=\"" << html_escape(rel) << "\">" << html_escape(file.filename().string()) << "</a>";
  if (!caption.empty()) os << " &mdash; " << html_escape(caption);
  os << "</figcaption></figure>\n";
  return os.str();
}

}  // namespace

std::string gallery_html(const std::string& root_dir, const std::string& title) {
  const fs::path root(root_dir);
  static const std::vector<std::string> shown = {".png", ".svg", ".mp4", ".glb", ".bvh", ".json", ".csv", ".md", ".html"};
  std::vector<fs::path> dirs{root};
  for (const auto& e : fs::directory_iterator(root))
    if (e.is_directory()) dirs.push_back(e.path());
  std::sort(dirs.begin() + 1, dirs.end());
  std::ostringstream os;
  os << "<!doctype html><html><head><meta charset=\"utf-8\"><title>" << html_escape(title) << "</title><style>"
     << "body{font-family:sans-serif;margin:2em;color:#222}h2{border-bottom:1px solid #ccc}"
     << ".grid{display:flex;flex-wrap:wrap;gap:1em}figure{margin:0;max-width:480px}"
     << "img,video{max-width:480px;border:1px solid #ddd}figcaption{font-size:.9em}</style></head><body>\n"
     << "<h1>" << html_escape(title) << "</h1>\n";
  for (const auto& dir : dirs) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename() != "index.html" &&
          std::find(shown.begin(), shown.end(), extension_of(e.path().string())) != shown.end())
        files.push_back(e.path());
    if (files.empty()) continue;
    std::sort(files.begin(), files.end());
    const auto captions = read_captions(dir);
    os << "<h2>" << html_escape(dir == root ? std::string("outputs") : dir.filename().string()) << "</h2><div class=\"grid\">\n";
    for (const auto& f : files) {
      auto it = captions.find(f.filename().string());
      os << item_html(root, f, it == captions.end() ? "" : it->second);
    }
    os << "</div>\n";
  }
  os << "</body></html>\n";
  return os.str();
}

}  // namespace legwork::render
