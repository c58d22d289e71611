#include <legwork/io/text.hpp>

#include <legwork/core/files.hpp>

#include <legwork/core/types.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace legwork::io {

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error(path + ": cannot open file (" + std::strerror(errno) + ")");
  // One read into a buffer of the file's size (a stringstream copies twice).
  const std::streamoff size = in.tellg();
  if (size < 0) throw Error(path + ": cannot determine the file size");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(text.data(), size)) throw Error(path + ": read failed");
  return text;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path + ": cannot write file (" + std::strerror(errno) + ")");
  out << text;
  if (!out) throw Error(path + ": write failed");
}

std::string extension_of(const std::string& path) { return legwork::extension_of(path); }

}  // namespace legwork::io
