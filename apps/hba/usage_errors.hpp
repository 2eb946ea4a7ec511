#pragma once
// Usage errors the way users know them from git and cargo: a mistyped
// command or flag gets "did you mean", every usage error exits 2, help and
// --version exit 0. Exit codes: 0 success, 1 failure (bad input, a run that
// could not finish), 2 usage (unknown command or flag, bad value).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace hba::cli {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// Checks the first word of the command line against the subcommands before
// parsing ("optimze" -> did you mean 'optimize'?). Returns the message to
// print if the word is no command, else nothing.
std::optional<std::string> unknownCommand(const CLI::App& app, int argc, const char* const* argv);

// Prints a parse error (with a "did you mean" for unknown flags) on stderr
// and returns the exit code: 0 for --help and --version, else 2.
int reportParseError(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv);

}  // namespace hba::cli
