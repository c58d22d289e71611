#pragma once
// HTML pages over a folder of results (the demo's outputs), read as a story:
//  - sections are the sub-folders, in the order of the root README.txt's
//    "folder/: Heading - intro" lines (others after them, alphabetically);
//  - in a section, items follow the folder README.txt's "file: caption" lines;
//    under each item its caption and the command that made it, taken from the
//    root commands.txt (one command line per run, written by the demo's
//    command logger: the last command naming the file, or a prefix of it
//    such as an --arc-out stem, made it);
//  - pictures (PNG, else SVG) and videos (with a poster frame "<stem>.poster.png"
//    when present) in a grid, one format per chart: a PNG's SVG twin is linked
//    from its caption, not shown twice; other files as a compact list;
//  - a folder inside a section gets its own page (its index.html), linked
//    from the section with a count of what it holds.
#include <string>
#include <vector>

namespace legwork::render {

struct GalleryPage {
  std::string path;  // relative to the root: "index.html", "wip/eval/index.html"
  std::string html;
};

// Every page of the gallery of `root`: the main page first.
std::vector<GalleryPage> gallery_pages(const std::string& root, const std::string& title);
// The main page only.
std::string gallery_html(const std::string& root, const std::string& title);

// Writes "<stem>.poster.png" beside every .mp4 under `root` that has none (a
// still at 0.5 s through ffmpeg). Returns how many were written; without
// ffmpeg, or for a video ffmpeg cannot read, writes none for it and says why
// in `problems` (the page then shows the video's first frame as its poster).
int write_video_posters(const std::string& root, std::vector<std::string>* problems = nullptr);

}  // namespace legwork::render
