// Option values checked before any work (see options.hpp).
#include <legwork/io/options.hpp>

#include <legwork/core/types.hpp>
#include <legwork/io/text.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace legwork::io {

void require_writable_folder(const std::string& path, std::string_view option) {
  namespace fs = std::filesystem;
  const std::string what = std::string(option) + " '" + path + "'";
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  if (ec) throw Error(what + ": " + ec.message());
  if (fs::exists(p, ec) && !fs::is_directory(p, ec)) throw Error(what + ": is a file, not a folder");
  // The nearest existing ancestor is where the folders get created.
  while (!fs::exists(p, ec) && p.has_parent_path() && p.parent_path() != p) p = p.parent_path();
  if (!fs::is_directory(p, ec)) throw Error(what + ": cannot write in '" + p.string() + "' (it is a file, not a folder)");
  // Probed by creating (and removing) a folder there: access() says yes to
  // root on /proc or a read-only mount.
  std::string probe = (p / ".legwork-write-test-XXXXXX").string();
  if (!::mkdtemp(probe.data())) throw Error(what + ": cannot write in '" + p.string() + "' (" + std::strerror(errno) + ")");
  ::rmdir(probe.c_str());
}

std::vector<double> parse_number_list(std::string_view text, std::size_t count, std::string_view option,
                                      std::string_view form) {
  const std::string what = std::string(option) + " '" + printable_text(text) + "': ";
  std::vector<double> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    std::string item(text.substr(at, comma - at));
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
      throw Error(what + "'" + printable_text(item) + "' is not a number; expected " + std::string(form));
    out.push_back(v);
    at = comma + 1;
  }
  if (out.size() != count)
    throw Error(what + "expected " + std::to_string(count) + " numbers " + std::string(form) + ", found " + std::to_string(out.size()));
  return out;
}

}  // namespace legwork::io
