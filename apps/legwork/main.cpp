// legwork: believable bodies for VR and game characters.
#include "command.hpp"

#include <legwork/io/errors.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iostream>
#include <limits>
#include <utility>
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

CLI::Option* output_file(CLI::Option* option) {
  const std::string name = option->get_name();
  return option->each([name](const std::string& path) { io::prepare_output(path, name); });
}

namespace {
// A number above `low` (or at least `low`) and at most `max` (infinity: no maximum), with a
// message naming the range in plain digits.
CLI::Validator number_from(double low, bool low_allowed, double max) {
  const std::string lo = CLI::detail::to_string(low);
  const std::string high = std::isinf(max) ? std::string{} : CLI::detail::to_string(max);
  const std::string range = high.empty() ? (low_allowed ? ">= " : "> ") + lo
                                         : lo + (low_allowed ? "" : " (exclusive)") + " to " + high;
  return CLI::Validator(
      [=](std::string& in) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(in, v) || std::isnan(v)) return "Value " + in + " is not a number";
        const bool above = low_allowed ? v >= low : v > low;
        if (above && v <= max) return {};
        return high.empty() ? "Value " + in + " must be " + range : "Value " + in + " not in range " + range;
      },
      high.empty() ? range : (low_allowed ? "[" : "(") + lo + " - " + high + "]");
}
}  // namespace

CLI::Validator positive_up_to(double max) { return number_from(0, false, max); }
CLI::Validator positive_number() { return number_from(0, false, std::numeric_limits<double>::infinity()); }
CLI::Validator non_negative_number() { return number_from(0, true, std::numeric_limits<double>::infinity()); }
CLI::Validator zero_or_factor() {
  return CLI::Validator(
      [](std::string& in) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(in, v) || std::isnan(v)) return "Value " + in + " is not a number";
        if (v == 0 || (v >= 1 && v <= 1e6)) return {};
        return "Value " + in + " must be 0 (off) or a factor from 1 to 1000000";
      },
      "0 or [1 - 1000000]");
}

void MotionInput::add_options(CLI::App* cmd, bool positional, const std::string& name) {
  if (positional) cmd->add_option(name, path, "motion file to read: .bvh, or a .glb (legwork's or another tool's skinned glTF whose rig resolves to roles)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--scale", options.scale, "file units -> metres (0 = detect from the rest-pose height; CMU = 0.056444)")
      ->check(non_negative_number());
  cmd->add_flag("--drop-first", options.drop_first, "drop frame 0 (the synthetic T-pose of CMU files)");
  cmd->add_flag("--lenient", options.lenient, "accept more motion lines than 'Frames:' declares (extra lines ignored)");
}

namespace {
// Every --help shows each option's default, except where the description
// already says it in words ("default: the walk's") or the value only means
// "not given" (-1).
void show_defaults(CLI::App* app) {
  for (auto* opt : app->get_options()) {
    const std::string& d = opt->get_description();
    if (d.find("default") != std::string::npos || opt->get_default_str() == "-1") opt->default_str("");
  }
  for (auto* sub : app->get_subcommands({})) show_defaults(sub);
}
}  // namespace

}  // namespace legwork::cli

int main(int argc, char** argv) {
  CLI::App app{
      "legwork - believable bodies for VR and game characters.\n"
      "Walking-in-place legs, a walk-cycle generator and full-body accentuation from\n"
      "headset + controllers, over BVH motion capture. Units: metres, seconds; y up,\n"
      "characters face +z. Run 'legwork COMMAND --help' for each command's options.",
      "legwork"};
  app.require_subcommand(0, 1);
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", "legwork 0.1.0");
  auto& reg = legwork::cli::registry();
  std::stable_sort(reg.begin(), reg.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& [order, fn] : reg) fn(app);
  legwork::cli::show_defaults(&app);
  // A command with subcommands given none prints its help (as bare `legwork` does).
  for (auto* cmd : app.get_subcommands([](CLI::App* c) { return c->get_require_subcommand_min() > 0; }))
    cmd->require_subcommand(0, 1)->callback([cmd] {
      if (cmd->get_subcommands().empty()) std::cout << cmd->help();
    });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (...) {
    std::cerr << "legwork: error: " << legwork::io::describe_exception(std::current_exception()) << "\n";
    return 1;
  }
  if (app.get_subcommands().empty()) std::cout << app.help();
  return 0;
}
