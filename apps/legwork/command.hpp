#pragma once
// Subcommand registry: each cmd_*.cpp adds its subcommands to the app with
// LEGWORK_COMMAND(fn, order), so modules never edit main.cpp.
#include <CLI/CLI.hpp>

#include <legwork/core/motion.hpp>
#include <legwork/core/types.hpp>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace legwork::cli {

using Registrar = void (*)(CLI::App&);
int add_command(Registrar r, int order);

// Parses "A:B" (inclusive, either side optional) into [first, last] clamped to [0, frames-1].
std::pair<int, int> parse_frame_range(const std::string& spec, int frames);

// Prints "wrote PATH" consistently.
void announce(const std::string& what, const std::string& path);

// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
std::vector<std::string> split_commas(const std::string& s);

// Throws "OPTION 'PATH' must end in A or B" unless PATH ends in one of `exts` (".png", ...).
void require_extension(const std::string& option, const std::string& path, const std::vector<std::string>& exts);

// Creates the folder `path` will be written into.
void ensure_parent(const std::string& path);

// Writes a motion as .bvh or .glb (by extension; `name` = the glTF animation name) and announces it.
void write_motion(const std::string& path, const Motion& m, const std::string& what, const std::string& name);

// A one-line progress bar on stderr: "what [####......] done/total item".
std::function<void(int, int, const std::string&)> progress_bar(const std::string& what);

}  // namespace legwork::cli

#define LEGWORK_CONCAT_(a, b) a##b
#define LEGWORK_CONCAT(a, b) LEGWORK_CONCAT_(a, b)
#define LEGWORK_COMMAND(fn, order) \
  static const int LEGWORK_CONCAT(legwork_command_, __LINE__) = ::legwork::cli::add_command(fn, order)
