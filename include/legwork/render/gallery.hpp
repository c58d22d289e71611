#pragma once
// An HTML page over a folder of results: every picture, video and result file
// under `root` (one section per sub-folder, captions from each folder's
// README.txt "file: caption" lines).
#include <string>

namespace legwork::render {

std::string gallery_html(const std::string& root, const std::string& title);

}  // namespace legwork::render
