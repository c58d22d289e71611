#include <legwork/io/text.hpp>
#include <legwork/io/file_writer.hpp>

#include <legwork/core/files.hpp>

#include <legwork/core/types.hpp>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace legwork::io {

namespace {

std::string too_large(const std::string& path, std::uintmax_t bytes) {
  return path + ": " + std::to_string(bytes) + " bytes is larger than legwork reads (" +
         std::to_string(kMaxFileBytes >> 20) + " MiB)";
}

// Pipes and devices (/dev/stdin) have no size: read in chunks up to the limit.
std::string read_stream(std::ifstream& in, const std::string& path) {
  std::string text;
  char chunk[65536];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes) throw Error(too_large(path, text.size()));
  }
  if (in.bad()) throw Error(path + ": read failed (" + std::strerror(errno) + ")");
  return text;
}

}  // namespace

std::string read_binary_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!ec && fs::is_directory(st)) throw Error(path + ": is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file (" + std::strerror(errno) + ")");
  if (!fs::is_regular_file(st)) return read_stream(in, path);
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw Error(path + ": cannot determine the file size (" + ec.message() + ")");
  if (size > kMaxFileBytes) throw Error(too_large(path, size));
  // One read into a buffer of the file's size (a stringstream copies twice).
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(size)))
    throw Error(path + ": read failed (the file changed while it was read?)");
  return text;
}

std::string read_text_file(const std::string& path) {
  std::string text = read_binary_file(path);
  const std::size_t bom = text.size() - text_body(text, path).size();
  text.erase(0, bom);
  return text;
}

TextFileWriter::TextFileWriter(const std::string& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a directory, not a file");
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw Error(path + ": cannot write file (" + std::strerror(errno) + ")");
}

TextFileWriter::~TextFileWriter() {
  if (file_) std::fclose(file_);
}

void TextFileWriter::write(std::string_view piece) {
  if (!file_) throw Error(path_ + ": write after close");
  if (!piece.empty() && std::fwrite(piece.data(), 1, piece.size(), file_) != piece.size())
    throw Error(path_ + ": write failed (" + std::strerror(errno) + ")");
}

void TextFileWriter::close() {
  if (!file_) return;
  const bool ok = std::fflush(file_) == 0;
  const int err = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!ok || !closed) throw Error(path_ + ": write failed (" + std::strerror(ok ? errno : err) + ")");
}

void write_text_file(const std::string& path, const std::string& text) {
  TextFileWriter out(path);
  out.write(text);
  out.close();
}

std::string extension_of(const std::string& path) { return legwork::extension_of(path); }

std::string_view text_body(std::string_view text, std::string_view source) {
  auto starts = [&](std::string_view bom) { return text.substr(0, bom.size()) == bom; };
  using namespace std::string_view_literals;
  if (starts("\xEF\xBB\xBF"sv)) return text.substr(3);
  // Binary files of the formats legwork writes, given where text is read.
  if (starts("LWACCENT"sv))
    throw Error(std::string(source) + ": a legwork accent database (binary .lwdb), not a text file; 'legwork info " +
                std::string(source) + "' describes it, 'legwork accent run --db' uses it");
  if (starts("glTF"sv))
    throw Error(std::string(source) + ": a binary glTF (.glb), not a text file; name it .glb where a motion is read");
  const bool utf32 = starts("\xFF\xFE\0\0"sv) || starts("\0\0\xFE\xFF"sv);
  // ASCII interleaved with NULs ("H\0I\0..." or "\0H\0I...") is BOM-less UTF-16.
  const bool interleaved = text.size() >= 4 && ((text[0] != 0 && text[1] == 0 && text[2] != 0 && text[3] == 0) ||
                                                (text[0] == 0 && text[1] != 0 && text[2] == 0 && text[3] != 0));
  if (utf32) throw Error(std::string(source) + ": UTF-32 text; save it as UTF-8");
  if (starts("\xFF\xFE"sv) || starts("\xFE\xFF"sv) || interleaved)
    throw Error(std::string(source) + ": UTF-16 text; save it as UTF-8");
  return text;
}

bool is_valid_utf8(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    int len = 0;
    unsigned cp = 0;
    if (c >= 0xC2 && c <= 0xDF) len = 2, cp = c & 0x1Fu;
    else if (c >= 0xE0 && c <= 0xEF) len = 3, cp = c & 0x0Fu;
    else if (c >= 0xF0 && c <= 0xF4) len = 4, cp = c & 0x07u;
    else return false;
    if (i + static_cast<std::size_t>(len) > s.size()) return false;
    for (int k = 1; k < len; ++k) {
      const auto b = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      if ((b & 0xC0u) != 0x80u) return false;
      cp = (cp << 6) | (b & 0x3Fu);
    }
    if ((len == 3 && (cp < 0x800 || (cp >= 0xD800 && cp <= 0xDFFF))) || (len == 4 && (cp < 0x10000 || cp > 0x10FFFF)))
      return false;
    i += static_cast<std::size_t>(len);
  }
  return true;
}

std::string printable_text(std::string_view s, std::size_t max) {
  std::string out(s.substr(0, max));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  if (s.size() > max) out += "...";
  return out;
}

}  // namespace legwork::io

namespace legwork::io {

void announce(const std::string& what, const std::string& path) { std::printf("wrote %s: %s\n", what.c_str(), path.c_str()); }

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = std::min(s.find(',', start), s.size());
    if (end > start) out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

void require_extension(const std::string& option, const std::string& path, const std::vector<std::string>& exts) {
  const std::string ext = extension_of(path);
  if (std::find(exts.begin(), exts.end(), ext) != exts.end()) return;
  std::string list;
  for (std::size_t i = 0; i < exts.size(); ++i) list += (i == 0 ? "" : i + 1 == exts.size() ? " or " : ", ") + exts[i];
  throw Error(option + " '" + path + "' must end in " + list);
}

std::pair<int, int> parse_frame_range(const std::string& spec, int frames, const std::string& option) {
  const auto parse = [&](std::string_view s, int dflt) {
    if (s.empty()) return dflt;
    int v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size())
      throw Error(option + " '" + spec + "': expected A:B with whole numbers");
    return v < 0 ? v + frames : v;  // -1 = last frame
  };
  const std::string_view sv(spec);
  const auto colon = spec.find(':');
  int a = 0, b = frames - 1;
  if (colon == std::string::npos) {
    a = b = parse(sv, 0);
  } else {
    a = parse(sv.substr(0, colon), 0);
    b = parse(sv.substr(colon + 1), frames - 1);
  }
  if (a < 0 || b >= frames || a > b)
    throw Error(option + " '" + spec + "' is outside the clip's frames 0:" + std::to_string(frames - 1));
  return {a, b};
}

std::string prepare_output(const std::string& path, const std::string& option) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (parent.empty() || fs::is_directory(parent, ec)) return path;
  if (fs::exists(parent, ec))
    throw Error(option + " '" + path + "': '" + parent.string() + "' is a file, not a folder");
  const fs::path rel = fs::absolute(parent, ec).lexically_normal().lexically_relative(fs::current_path(ec));
  const bool inside = !rel.empty() && *rel.begin() != "..";
  if (!inside)
    throw Error(option + " '" + path + "': folder '" + parent.string() +
                "' does not exist and is outside the working folder; create it first");
  fs::create_directories(parent, ec);
  if (ec) throw Error(option + " '" + path + "': cannot create folder '" + parent.string() + "' (" + ec.message() + ")");
  return path;
}

}  // namespace legwork::io
