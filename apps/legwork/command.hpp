#pragma once
// Subcommand registry: each cmd_*.cpp adds its subcommands to the app with
// LEGWORK_COMMAND(fn, order), so modules never edit main.cpp. Commands parse
// options, call library functions and print; the work is in the libraries.
#include <CLI/CLI.hpp>

#include <legwork/io/motion_file.hpp>
#include <legwork/io/progress.hpp>
#include <legwork/io/text.hpp>

namespace legwork::cli {

using Registrar = void (*)(CLI::App&);
int add_command(Registrar r, int order);

using io::announce;
using io::require_extension;
using io::split_commas;

// Marks an option as an output file: its folder is made (or refused) by
// io::prepare_output, the same way in every command.
CLI::Option* output_file(CLI::Option* option);

// A number in (0, max]: CLI11's PositiveNumber / NonNegativeNumber print the largest double (300 digits) as
// the maximum in their error; this names a plain range ("Value -1 not in range 0 (exclusive) to 50").
CLI::Validator positive_up_to(double max);
// A number > 0 / >= 0 with no maximum ("Value -1 must be > 0"), for the same reason.
CLI::Validator positive_number();
CLI::Validator non_negative_number();
// 0, or a factor from 1 to 1e6 (accent::Settings::other_class_cost).
CLI::Validator zero_or_factor();

// Progress of long work on stderr: a live bar on a terminal, whole lines in logs.
inline io::ProgressPrinter progress_bar(const std::string& what) { return io::progress_printer(what); }

// Options every command that reads a motion shares: the positional IN (if
// `positional`), --scale, --drop-first, --lenient.
struct MotionInput {
  std::string path;
  io::MotionReadOptions options;
  void add_options(CLI::App* cmd, bool positional = true, const std::string& name = "input");
  io::BvhFile load() const { return io::read_motion(path, options); }
};

}  // namespace legwork::cli

#define LEGWORK_CONCAT_(a, b) a##b
#define LEGWORK_CONCAT(a, b) LEGWORK_CONCAT_(a, b)
#define LEGWORK_COMMAND(fn, order) \
  static const int LEGWORK_CONCAT(legwork_command_, __LINE__) = ::legwork::cli::add_command(fn, order)
