// The linequad program: each subcommand registers its options and says how it runs, in a file of
// its own (cli/<subcommand>.cpp); what they share is here (cli/options.cpp).
//
// Exit status: 0 all well; 1 the data has problems (malformed case lines, a broken claim, an
// incomplete merge, a diff that got worse or compared other cases); 2 the command cannot run (bad
// options, unreadable input, unwritable output); 130 an audit stopped early by a signal.
#pragma once

#include "linequad/audit_solver.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace linequad::cli {

// A subcommand: its CLI11 app, holding its options; a check of them all once parsed ("" or why
// not, named by its option); and what runs when it was given, with the whole command line (for
// reports).
struct Command {
    CLI::App* app = nullptr;
    std::function<int(const std::string& command_line)> run;
    std::function<std::pair<std::string, std::string>()> check; // (option, why not)
};

Command solve_command(CLI::App& app);
Command sense_command(CLI::App& app);
Command cells_command(CLI::App& app);
Command replay_command(CLI::App& app);
Command audit_command(CLI::App& app);
Command cases_command(CLI::App& app);
Command merge_command(CLI::App& app);
Command diff_command(CLI::App& app);
Command html_command(CLI::App& app);
Command history_command(CLI::App& app);
Command spawn_command(CLI::App& app);
Command scenes_command(CLI::App& app);
Command solvers_command(CLI::App& app);
Command version_command(CLI::App& app);
Command worker_command(CLI::App& app);
int print_version();

// ---- options, read as text and checked here: CLI11's own conversions read "-1" as 2^64 - 1,
// "010" as octal, and take "nan" for a positive number.

inline constexpr std::uint64_t max_cases = 1000000000; // per family, shape and range
inline constexpr std::uint64_t max_shards = 1000000;

// A decimal whole number in [lo, hi] into *out (if given); "" or why not.
std::string whole_number(const std::string& text, std::uint64_t lo, std::uint64_t hi,
                         std::uint64_t* out);
CLI::Validator WholeNumber(std::uint64_t lo, std::uint64_t hi);
std::uint64_t to_whole(const std::string& text); // one WholeNumber validated
// A finite number in (0, hi].
CLI::Validator PositiveNumber(double hi);
// A finite fraction >= 0 (a growth threshold).
CLI::Validator Fraction();
double to_real(const std::string& text); // one PositiveNumber or Fraction validated
// "K/N": shard K of N into *k, *n (if given); "" or why not.
std::string shard_error(const std::string& text, int* k, int* n);
// "a,b,c": the names of a list option (one argument, so that a file after it stays a file).
std::vector<std::string> split_list(const std::string& list);
// A validator of a list option: each name must pass check (which says why not).
CLI::Validator each_of_list(std::function<std::string(const std::string&)> check);

// ---- names a user can discover

// "a, b, c" (for help texts and errors).
std::string joined(const std::vector<std::string>& names);
// What a list of names holds: "family", "families".
struct Kind {
    std::string one, many;
};
// "" when name is one of known; else "no family named 'x' (did you mean 'y'?); the families: ..."
// (the nearest name by edit distance, when it is near enough to be a slip).
std::string unknown_name(const Kind& kind, const std::string& name,
                         const std::vector<std::string>& known);
// A list option whose names must each be one of known.
CLI::Validator names_in(const Kind& kind, std::vector<std::string> known);

// --plugin and --solver-timeout; --history and --commit.
void add_plugin_options(CLI::App* app, std::vector<std::string>& plugins, std::string& timeout);
// --max-line-bytes N (64 to 2^30), into `value` (its default already there).
void add_max_line_bytes(CLI::App* app, std::string& value,
                        const char* help = "the longest line read");
void add_history_options(CLI::App* app, std::string& history, std::string& commit);

// ---- outputs

// Why `output` must not be written: it is one of `inputs` (the same file, by device and inode),
// which writing it would destroy. Empty when it is not (or does not exist yet).
std::string output_is_input(const std::string& output, const std::vector<std::string>& inputs);

// ---- markdown on the standard output

// --format for a command that prints its markdown (diff, history): md, text, or auto (the
// default: plain text on a terminal, markdown into a pipe or a file).
void add_format_option(CLI::App* c, std::string& format);
// The markdown as the standard output should get it under that choice.
std::string for_standard_output(const std::string& md, const std::string& format);

// ---- solvers from outside linequad

// The peer libraries built in, then the solvers of the plugins given, loaded once (each plugin in
// a worker process: this program in another mode). The peers that run as plugins (VecGeom) are
// loaded only when one of their solvers is among `wanted` ("*": all of them).
std::vector<audit::ExternalSolver> external_solvers(const std::vector<std::string>& plugins,
                                                    const std::string& timeout,
                                                    const std::vector<std::string>& wanted);
const audit::ExternalSolver* find_external(const std::vector<audit::ExternalSolver>& ext,
                                           const std::string& name);
// "" if a solver has this name (batch too, if batch_too), else why not.
std::string solver_error(const std::string& name, bool batch_too,
                         const std::vector<audit::ExternalSolver>& ext);
// What the plugins' solvers wrote on their standard output and error, on linequad's standard
// error (never mixed into its results), a few lines each.
void report_plugin_output(const std::vector<audit::ExternalSolver>& ext);

// ---- output

int fail(const std::string& msg); // on standard error; returns 2
// A report to out_file, or standard output when none is given.
int write_markdown(const std::string& md, const std::string& out_file, const char* what);

} // namespace linequad::cli
