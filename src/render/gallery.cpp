// HTML pages over a folder of results (see gallery.hpp).
#include <legwork/render/gallery.hpp>
#include <legwork/render/render.hpp>

#include <legwork/core/files.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
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

// Percent-encodes what a relative URL cannot hold as is (spaces, #, ?, %...).
std::string url_of(const std::string& rel) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : rel) {
    if (std::isalnum(c) || std::string_view("/-_.~").find(static_cast<char>(c)) != std::string_view::npos) {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

// "name: caption" lines of DIR/README.txt, in file order.
std::vector<std::pair<std::string, std::string>> read_captions(const fs::path& dir) {
  std::vector<std::pair<std::string, std::string>> out;
  std::ifstream in(dir / "README.txt");
  std::string line;
  while (std::getline(in, line)) {
    // The name is a file or folder name: no spaces (a sentence with a colon is not a caption).
    auto colon = line.find(": ");
    if (colon != std::string::npos && colon > 0 && line.find(' ') > colon) out.emplace_back(line.substr(0, colon), line.substr(colon + 2));
  }
  return out;
}

// Files the gallery writes or reads for itself, never shown as results.
bool is_gallery_file(const fs::path& p) {
  const std::string name = p.filename().string();
  return name == "index.html" || name == "README.txt" || name == "commands.txt" ||
         (name.size() > 11 && name.ends_with(".poster.png"));
}

std::string size_text(std::uintmax_t bytes) {
  std::ostringstream os;
  if (bytes < 1024) os << bytes << " B";
  else if (bytes < 1024 * 1024) os << (bytes + 512) / 1024 << " kB";
  else os << static_cast<double>(bytes / (1024 * 102)) / 10.0 << " MB";
  return os.str();
}

// The command that made a file: among the logged commands, one with an
// argument naming the file (any leading folders allowed: the demo's output
// folder), else one naming a prefix of it that ends before '_', '.' or '/'
// (an output stem or folder). The last such command wins.
class Commands {
 public:
  explicit Commands(const fs::path& root) {
    std::ifstream in(root / "commands.txt");
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("# results: ", 0) == 0) results_ = line.substr(11) + "/";
      if (!line.empty() && line[0] != '#') lines_.push_back(line);
    }
  }

  std::string made(const std::string& rel) const {
    std::string best;
    int best_score = 0;
    for (const auto& line : lines_) {
      std::istringstream words(line);
      int score = 0;
      for (std::string w; words >> w;) score = std::max(score, match(strip_quotes(w), rel));
      if (score > 0 && score >= best_score) best = line, best_score = score;
    }
    return best;
  }

 private:
  static std::string strip_quotes(std::string w) {
    if (w.size() >= 2 && (w.front() == '\'' || w.front() == '"') && w.back() == w.front()) w = w.substr(1, w.size() - 2);
    return w;
  }
  // 2: a path suffix of `word` is `rel`; 1: a path suffix of `word` that
  // keeps a folder is a stem or folder of `rel`.
  // With the results folder known ("# results: demo-out"), only the part of
  // a word after it is compared.
  int match(const std::string& word, const std::string& rel) const {
    std::vector<std::string> tails{word};
    if (!results_.empty()) {
      if (word.rfind(results_, 0) != 0) return 0;
      tails = {word.substr(results_.size())};
    }
    for (auto k = word.find('/'); results_.empty() && k != std::string::npos; k = word.find('/', k + 1)) tails.push_back(word.substr(k + 1));
    int score = 0;
    const bool path = word.find('/') != std::string::npos;  // not a subcommand such as "eval"
    for (const auto& tail : tails) {
      if (tail == rel) return 2;
      if (path && !tail.empty() && rel.size() > tail.size() && rel.compare(0, tail.size(), tail) == 0) {
        const char next = rel[tail.size()];
        // A stem keeps its folder ("walkcycle/normal" + "_arc..."); a folder may be a section ("eval" + "/...").
        if (next == '/' || (std::string_view("_.").find(next) != std::string_view::npos && tail.find('/') != std::string::npos))
          score = 1;
      }
    }
    return score;
  }
  std::vector<std::string> lines_;
  std::string results_;  // "demo-out/", or empty: any leading folders
};

struct Item {
  fs::path file;       // what the grid shows or the list links
  std::string caption;
  fs::path svg_twin;   // an SVG of the same chart, linked from the caption
  bool picture = false, video = false;
};

bool is_picture(const fs::path& p) { return p.extension() == ".png" || p.extension() == ".svg"; }

// The items of one folder, README order first; a PNG's SVG twin joins it.
std::vector<Item> folder_items(const fs::path& dir) {
  static const std::set<std::string> shown = {".png", ".svg", ".mp4", ".glb", ".bvh", ".json", ".csv", ".md", ".txt", ".html", ".tsv"};
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && !is_gallery_file(e.path()) && shown.count(extension_of(e.path().string()))) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  auto captions = read_captions(dir);
  // The parent folder's README may caption files in here: "combined/report.md: ...".
  const std::string prefix = dir.filename().string() + "/";
  for (const auto& [name, text] : read_captions(dir.parent_path()))
    if (name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0) captions.emplace_back(name.substr(prefix.size()), text);
  std::map<std::string, std::size_t> rank;
  for (std::size_t i = 0; i < captions.size(); ++i) rank.emplace(captions[i].first, i);
  auto rank_of = [&](const fs::path& f) {
    auto it = rank.find(f.filename().string());
    return it == rank.end() ? captions.size() : it->second;
  };
  std::stable_sort(files.begin(), files.end(), [&](const fs::path& a, const fs::path& b) { return rank_of(a) < rank_of(b); });
  std::vector<Item> items;
  for (const auto& f : files) {
    fs::path png = f;
    png.replace_extension(".png");
    if (f.extension() == ".svg" && fs::exists(png)) continue;  // shown as its PNG
    Item it;
    it.file = f;
    if (auto c = rank.find(f.filename().string()); c != rank.end()) it.caption = captions[c->second].second;
    it.picture = is_picture(f);
    it.video = f.extension() == ".mp4";
    fs::path svg = f;
    svg.replace_extension(".svg");
    if (f.extension() == ".png" && fs::exists(svg)) it.svg_twin = svg;
    items.push_back(it);
  }
  return items;
}

// Width / height of a PNG from its header (0 if unreadable).
double png_aspect(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char h[24] = {};
  if (!in.read(reinterpret_cast<char*>(h), sizeof h) || h[1] != 'P' || h[2] != 'N' || h[3] != 'G') return 0;
  auto be = [&](int at) { return (h[at] << 24) | (h[at + 1] << 16) | (h[at + 2] << 8) | h[at + 3]; };
  return be(20) > 0 ? static_cast<double>(be(16)) / be(20) : 0;
}

// The command under an item; a command already shown in this folder is named
// by the first file it made instead of repeated. `shown` maps command -> that file.
std::string command_html(const std::string& command, const fs::path& file, const fs::path& base,
                         std::map<std::string, fs::path>& shown) {
  if (command.empty()) return "";
  if (auto it = shown.find(command); it != shown.end())
    return "<code class=\"cmd\">$ the command of <a href=\"" + url_of(fs::relative(it->second, base).generic_string()) + "\">" +
           html_escape(it->second.filename().string()) + "</a></code>";
  shown.emplace(command, file);
  return "<code class=\"cmd\">$ " + html_escape(command) + "</code>";
}

// One grid tile (picture or video); `base` is the page's folder.
std::string tile_html(const fs::path& root, const fs::path& base, const Item& it, const Commands& commands,
                      std::map<std::string, fs::path>& shown) {
  const std::string href = url_of(fs::relative(it.file, base).generic_string());
  const std::string name = it.file.filename().string();
  std::ostringstream os;
  os << (it.picture && it.file.extension() == ".png" && png_aspect(it.file) > 2.2 ? "<figure class=\"wide\">" : "<figure>");
  if (it.video) {
    fs::path poster = it.file;
    poster.replace_extension(".poster.png");
    os << "<video controls muted loop playsinline preload=\"metadata\" src=\"" << href
       << (fs::exists(poster) ? "" : "#t=0.1") << "\"";
    if (fs::exists(poster)) os << " poster=\"" << url_of(fs::relative(poster, base).generic_string()) << "\"";
    os << "></video>";
  } else {
    os << "<a href=\"" << href << "\"><img src=\"" << href << "\" alt=\"" << html_escape(it.caption.empty() ? name : it.caption)
       << "\" loading=\"lazy\"></a>";
  }
  os << "<figcaption><a class=\"name\" href=\"" << href << "\">" << html_escape(name) << "</a>";
  if (!it.svg_twin.empty())
    os << " <a class=\"fmt\" href=\"" << url_of(fs::relative(it.svg_twin, base).generic_string()) << "\">SVG</a>";
  if (!it.caption.empty()) os << "<br>" << html_escape(it.caption);
  os << command_html(commands.made(fs::relative(it.file, root).generic_string()), it.file, base, shown) << "</figcaption></figure>\n";
  return os.str();
}

std::string file_row_html(const fs::path& root, const fs::path& base, const Item& it, const Commands& commands,
                          std::map<std::string, fs::path>& shown) {
  std::error_code ec;
  const auto bytes = fs::file_size(it.file, ec);
  std::ostringstream os;
  os << "<li><a href=\"" << url_of(fs::relative(it.file, base).generic_string()) << "\">" << html_escape(it.file.filename().string())
     << "</a> <span class=\"size\">" << (ec ? "" : size_text(bytes)) << "</span>";
  if (!it.caption.empty()) os << " &mdash; " << html_escape(it.caption);
  os << command_html(commands.made(fs::relative(it.file, root).generic_string()), it.file, base, shown) << "</li>\n";
  return os.str();
}

// What a folder holds, recursively: "57 pictures, 2 files".
std::string folder_summary(const fs::path& dir) {
  int pictures = 0, videos = 0, files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file() || is_gallery_file(e.path())) continue;
    if (e.path().extension() == ".png") ++pictures;
    else if (e.path().extension() == ".mp4") ++videos;
    else if (e.path().extension() != ".svg") ++files;
  }
  std::ostringstream os;
  const char* sep = "";
  for (auto [n, what] : {std::pair{pictures, "picture"}, std::pair{videos, "video"}, std::pair{files, "file"}})
    if (n > 0) os << sep << n << ' ' << what << (n == 1 ? "" : "s"), sep = ", ";
  return os.str();
}

std::vector<fs::path> sub_folders(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory()) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// A folder's items (grid, then file list) and links to its sub-folders' pages.
std::string folder_body(const fs::path& root, const fs::path& dir, const fs::path& base, const Commands& commands,
                        bool link_sub_folders = true) {
  const auto items = folder_items(dir);
  std::ostringstream grid, list;
  std::map<std::string, fs::path> shown;
  for (const auto& it : items)
    if (it.picture || it.video) grid << tile_html(root, base, it, commands, shown);
  for (const auto& it : items)
    if (!it.picture && !it.video) list << file_row_html(root, base, it, commands, shown);
  const auto captions = read_captions(dir);
  for (const auto& sub : link_sub_folders ? sub_folders(dir) : std::vector<fs::path>{}) {
    const std::string summary = folder_summary(sub);
    if (summary.empty()) continue;
    std::string caption;
    for (const auto& [name, text] : captions)
      if (name == sub.filename().string() + "/") caption = text;
    list << "<li class=\"page\"><a href=\"" << url_of(fs::relative(sub / "index.html", base).generic_string()) << "\">"
         << html_escape(sub.filename().string()) << "/</a> <span class=\"size\">" << summary << " &mdash; own page</span>"
         << (caption.empty() ? "" : " &mdash; " + html_escape(caption)) << "</li>\n";
  }
  std::string out;
  if (!grid.str().empty()) out += "<div class=\"grid\">\n" + grid.str() + "</div>\n";
  if (!list.str().empty()) out += "<ul class=\"files\">\n" + list.str() + "</ul>\n";
  return out;
}

std::string page_head(const std::string& title) {
  return "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width\">"
         "<title>" + html_escape(title) + "</title><style>"
         "body{font-family:system-ui,sans-serif;margin:1.5em auto;max-width:1560px;padding:0 1em;color:#222;line-height:1.4}"
         "h2{border-bottom:1px solid #ccc;margin-top:2em}nav a{margin-right:1em}.intro{color:#444;max-width:60em}"
         ".grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(360px,1fr));gap:1.2em}"
         "figure{margin:0}figure.wide{grid-column:span 2}img,video{width:100%;height:auto;border:1px solid #ddd;background:#fff}"
         "figcaption{font-size:.9em}.name{font-weight:600}.fmt{font-size:.85em;margin-left:.4em}"
         "code.cmd{display:block;font-size:.8em;color:#555;background:#f4f4f4;padding:.2em .4em;margin-top:.2em;"
         "white-space:pre-wrap;word-break:break-all}"
         "ul.files{columns:2 520px;padding-left:1.2em;font-size:.9em}ul.files li{break-inside:avoid;margin-bottom:.4em}"
         ".size{color:#777;font-size:.85em}</style></head><body>\n";
}

struct Section {
  fs::path dir;
  std::string heading, intro;
};

// Sections in the order of the root README.txt's "folder/: Heading - intro" lines, then the rest.
std::vector<Section> sections_of(const fs::path& root) {
  std::vector<Section> out;
  std::set<std::string> listed;
  for (const auto& [name, text] : read_captions(root)) {
    if (name.empty() || name.back() != '/' || !fs::is_directory(root / name)) continue;
    const std::string folder = name.substr(0, name.size() - 1);
    const auto dash = text.find(" - ");
    out.push_back({root / folder, dash == std::string::npos ? text : text.substr(0, dash),
                   dash == std::string::npos ? "" : text.substr(dash + 3)});
    listed.insert(folder);
  }
  for (const auto& dir : sub_folders(root))
    if (!listed.count(dir.filename().string())) out.push_back({dir, dir.filename().string(), ""});
  return out;
}

// The root README.txt's lines that are not "name: caption": the page's introduction.
std::string root_intro(const fs::path& root) {
  std::ifstream in(root / "README.txt");
  std::string line, out;
  while (std::getline(in, line)) {
    const auto colon = line.find(": ");
    if (!line.empty() && (colon == std::string::npos || line.find(' ') < colon)) out += html_escape(line) + " ";
  }
  return out;
}

std::string anchor_of(const std::string& name) {
  std::string out;
  for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return out;
}

// A page for a folder inside a section (and, recursively, its own folders);
// `back` is the page that links to it (with its anchor).
void add_sub_pages(const fs::path& root, const fs::path& dir, const std::string& back, const std::string& title,
                   const Commands& commands, std::vector<GalleryPage>& pages) {
  for (const auto& sub : sub_folders(dir)) {
    if (folder_summary(sub).empty()) continue;
    const std::string rel = fs::relative(sub, root).generic_string();
    std::ostringstream os;
    os << page_head(title + ": " + rel) << "<p><a href=\"" << url_of(fs::relative(root / back, sub).generic_string()) << "\">&larr; "
       << html_escape(title) << "</a></p><h1>" << html_escape(rel) << "/</h1>\n"
       << folder_body(root, sub, sub, commands) << "</body></html>\n";
    pages.push_back({rel + "/index.html", os.str()});
    add_sub_pages(root, sub, rel + "/index.html", title, commands, pages);
  }
}

}  // namespace

std::vector<GalleryPage> gallery_pages(const std::string& root_dir, const std::string& title) {
  const fs::path root(root_dir);
  const Commands commands(root);
  const auto sections = sections_of(root);
  std::ostringstream os;
  os << page_head(title) << "<h1>" << html_escape(title) << "</h1>\n";
  if (const std::string intro = root_intro(root); !intro.empty()) os << "<p class=\"intro\">" << intro << "</p>\n";
  os << "<nav>";
  for (const auto& s : sections)
    if (!folder_summary(s.dir).empty()) os << "<a href=\"#" << anchor_of(s.dir.filename().string()) << "\">" << html_escape(s.heading) << "</a>";
  os << "</nav>\n";
  if (const std::string top = folder_body(root, root, root, commands, false); !top.empty()) os << "<h2>Outputs</h2>\n" << top;
  std::vector<GalleryPage> pages(1);
  for (const auto& s : sections) {
    if (folder_summary(s.dir).empty()) continue;
    os << "<h2 id=\"" << anchor_of(s.dir.filename().string()) << "\">" << html_escape(s.heading) << "</h2>\n";
    if (!s.intro.empty()) os << "<p class=\"intro\">" << html_escape(s.intro) << "</p>\n";
    os << folder_body(root, s.dir, root, commands);
    add_sub_pages(root, s.dir, "index.html", title, commands, pages);
  }
  os << "</body></html>\n";
  pages[0] = {"index.html", os.str()};
  return pages;
}

std::string gallery_html(const std::string& root, const std::string& title) { return gallery_pages(root, title)[0].html; }

int write_video_posters(const std::string& root, std::vector<std::string>* problems) {
  int written = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (!e.is_regular_file() || e.path().extension() != ".mp4") continue;
    fs::path poster = e.path();
    poster.replace_extension(".poster.png");
    if (fs::exists(poster) && fs::last_write_time(poster) >= fs::last_write_time(e.path())) continue;
    try {
      write_video_still(e.path().string(), poster.string());
      ++written;
    } catch (const Error& err) {
      if (problems) problems->push_back(err.what());
    }
  }
  return written;
}

}  // namespace legwork::render
