#pragma once
// Command-line option values checked by the library, before any work, with
// messages that name the option and what it expects.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace legwork::io {

// Checks, before any work, that `path` can be a folder written into: it is a
// folder (or does not exist yet) and a folder can be created in the nearest
// existing folder at or above it (probed, then removed). Throws "<option> '<path>': is a file, not a folder" or
// "<option> '<path>': cannot write in '<folder>' (<reason>)".
void require_writable_folder(const std::string& path, std::string_view option);

// Exactly `count` comma-separated finite numbers ("1,1,0.5"; spaces allowed).
// Throws "<option> '<text>': '<item>' is not a number; expected <form>" (or
// "expected <count> numbers <form>").
std::vector<double> parse_number_list(std::string_view text, std::size_t count, std::string_view option,
                                      std::string_view form);

}  // namespace legwork::io
