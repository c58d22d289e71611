#pragma once
// Subcommand registry: each cmd_*.cpp adds its subcommands to the app with
// LEGWORK_COMMAND(fn, order), so modules never edit main.cpp.
#include <CLI/CLI.hpp>

#include <legwork/core/types.hpp>

#include <string>
#include <utility>

namespace legwork::cli {

using Registrar = void (*)(CLI::App&);
int add_command(Registrar r, int order);

// Parses "A:B" (inclusive, either side optional) into [first, last] clamped to [0, frames-1].
std::pair<int, int> parse_frame_range(const std::string& spec, int frames);

// Prints "wrote PATH" consistently.
void announce(const std::string& what, const std::string& path);

}  // namespace legwork::cli

#define LEGWORK_CONCAT_(a, b) a##b
#define LEGWORK_CONCAT(a, b) LEGWORK_CONCAT_(a, b)
#define LEGWORK_COMMAND(fn, order) \
  static const int LEGWORK_CONCAT(legwork_command_, __LINE__) = ::legwork::cli::add_command(fn, order)
