// legwork: believable bodies for VR and game characters.
#include "command.hpp"

#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>
#include <iostream>
#include <vector>

namespace legwork::cli {

namespace {
std::vector<std::pair<int, Registrar>>& registry() {
  static std::vector<std::pair<int, Registrar>> r;
  return r;
}
}  // namespace

int add_command(Registrar r, int order) {
  registry().emplace_back(order, r);
  return 0;
}

std::pair<int, int> parse_frame_range(const std::string& spec, int frames) {
  auto colon = spec.find(':');
  auto parse = [&](std::string_view s, int dflt) {
    if (s.empty()) return dflt;
    int v = 0;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size())
      throw Error("--frames '" + spec + "': expected A:B with whole numbers");
    if (v < 0) v += frames;  // -1 = last frame
    return v;
  };
  std::string_view sv(spec);
  int a = 0, b = frames - 1;
  if (colon == std::string::npos) {
    a = b = parse(sv, 0);
  } else {
    a = parse(sv.substr(0, colon), 0);
    b = parse(sv.substr(colon + 1), frames - 1);
  }
  if (a < 0 || b >= frames || a > b)
    throw Error("--frames '" + spec + "' is outside the clip's frames 0:" + std::to_string(frames - 1));
  return {a, b};
}

void announce(const std::string& what, const std::string& path) { std::cout << "wrote " << what << ": " << path << "\n"; }

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
  const std::string ext = io::extension_of(path);
  if (std::find(exts.begin(), exts.end(), ext) != exts.end()) return;
  std::string list;
  for (std::size_t i = 0; i < exts.size(); ++i)
    list += (i == 0 ? "" : i + 1 == exts.size() ? " or " : ", ") + exts[i];
  throw Error(option + " '" + path + "' must end in " + list);
}

void ensure_parent(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

void write_motion(const std::string& path, const Motion& m, const std::string& what, const std::string& name) {
  require_extension("output", path, {".bvh", ".glb"});
  ensure_parent(path);
  if (io::extension_of(path) == ".bvh") io::write_bvh(path, m);
  else io::write_glb(path, m, {name, true});
  announce(what, path);
}

std::function<void(int, int, const std::string&)> progress_bar(const std::string& what) {
  return [what](int done, int total, const std::string& item) {
    const int width = 30;
    const int filled = total > 0 ? done * width / total : width;
    std::fprintf(stderr, "\r%s [%s%s] %d/%d %-40.40s", what.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done, total, item.c_str());
    if (done >= total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  };
}

}  // namespace legwork::cli

namespace {

// What the user reads for an exception: never a library's raw text
// ("std::bad_alloc", "stod", "vector::_M_fill_insert", "filesystem error").
std::string user_message(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const legwork::Error& e) {
    return e.what();
  } catch (const std::bad_alloc&) {
    return "out of memory: the input or an option asks for more than this machine can hold";
  } catch (const std::length_error&) {
    return "a size from the input or an option is larger than legwork can hold";
  } catch (const std::filesystem::filesystem_error& e) {
    std::string msg = e.path1().empty() ? std::string("file system") : e.path1().string();
    if (!e.path2().empty()) msg += " -> " + e.path2().string();
    return msg + ": " + e.code().message();
  } catch (const std::system_error& e) {
    return "system error: " + e.code().message();
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.type_error.316] invalid UTF-8 byte ..." -> the part after the tag.
    std::string what = e.what();
    if (const auto close = what.find("] "); what.rfind("[json.exception.", 0) == 0 && close != std::string::npos)
      what.erase(0, close + 2);
    return "JSON data: " + what;
  } catch (const std::invalid_argument&) {
    return "a value that should be a number is not one (check the numeric options)";
  } catch (const std::out_of_range&) {
    return "a number or index is out of range (check the numeric options and frame ranges)";
  } catch (const std::exception& e) {
    const char* debug = std::getenv("LEGWORK_DEBUG");
    return std::string("internal error (please report it with the command line)") +
           (debug && *debug ? std::string(": ") + e.what() : std::string("; LEGWORK_DEBUG=1 shows details"));
  } catch (...) {
    return "internal error: unknown exception (please report it with the command line)";
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "legwork - believable bodies for VR and game characters.\n"
      "Walking-in-place legs, a walk-cycle generator and full-body accentuation from\n"
      "headset + controllers, over BVH motion capture. Units: metres, seconds; y up,\n"
      "characters face +z. Run 'legwork COMMAND --help' for each command's options.",
      "legwork"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "legwork 0.1.0");
  auto& reg = legwork::cli::registry();
  std::stable_sort(reg.begin(), reg.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& [order, fn] : reg) fn(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (...) {
    std::cerr << "legwork: error: " << user_message(std::current_exception()) << "\n";
    return 1;
  }
  return 0;
}
