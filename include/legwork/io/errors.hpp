#pragma once
// What a person reads for an exception: legwork::Error's own text, and for
// everything else a sentence instead of a library's raw text ("std::bad_alloc",
// "stod", "vector::_M_fill_insert", "filesystem error", "[json.exception...]").
#include <exception>
#include <string>

namespace legwork::io {

// The library's own text only with LEGWORK_DEBUG=1 (for unexpected exceptions).
std::string describe_exception(const std::exception_ptr& error);

}  // namespace legwork::io
