#pragma once
// Small file helpers shared by the readers.
#include <string>

namespace legwork::io {
// Whole file as a string; throws legwork::Error naming the path on failure.
std::string read_text_file(const std::string& path);
void write_text_file(const std::string& path, const std::string& text);
// Lower-case file extension including the dot (".bvh"), or "".
std::string extension_of(const std::string& path);
}  // namespace legwork::io
