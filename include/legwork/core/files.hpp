#pragma once
// File-name helpers shared by every module that picks a format by extension.
#include <string>

namespace legwork {
// Lower-case extension including the dot (".bvh"), or "" if none.
std::string extension_of(const std::string& path);
}  // namespace legwork
