// legwork: believable bodies for VR and game characters.
#include "command.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
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

}  // namespace legwork::cli

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
  } catch (const legwork::Error& e) {
    std::cerr << "legwork: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "legwork: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
