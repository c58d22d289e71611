#pragma once
// Small file helpers shared by the readers.
#include <cstddef>
#include <string>
#include <string_view>

namespace legwork::io {

// Largest file the readers load (2 GiB): larger is refused by name, not a bad_alloc.
inline constexpr std::size_t kMaxFileBytes = std::size_t{1} << 31;

// Whole file as a string; throws legwork::Error naming the path on failure:
// "<path>: is a directory", "<path>: cannot open file (<reason>)", larger
// than kMaxFileBytes, and UTF-16/UTF-32 text ("<path>: UTF-16 text; save it
// as UTF-8"). A UTF-8 byte-order mark is removed.
std::string read_text_file(const std::string& path);
// Whole file as bytes (same checks, no text rules).
std::string read_binary_file(const std::string& path);
void write_text_file(const std::string& path, const std::string& text);
// Lower-case file extension including the dot (".bvh"), or "".
std::string extension_of(const std::string& path);

// `text` without a UTF-8 byte-order mark; throws "<source>: UTF-16 text; save
// it as UTF-8" (or UTF-32) when the text starts with such a byte-order mark
// or with ASCII interleaved with NUL bytes.
std::string_view text_body(std::string_view text, std::string_view source);
// True if `s` is well-formed UTF-8 (no overlong forms, surrogates or values past U+10FFFF).
bool is_valid_utf8(std::string_view s);
// `s` cut to `max` bytes with control and non-ASCII bytes shown as '?', for
// messages that quote file content.
std::string printable_text(std::string_view s, std::size_t max = 200);

}  // namespace legwork::io
