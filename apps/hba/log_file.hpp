#pragma once
// --log-file: every message, with times, appended to a file. The file must
// be writable and must be nothing else the run reads or writes: appending a
// log line to a trajectory, or logging into a folder the run replaces whole,
// would lose data.
#include <spdlog/common.h>

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace hba::cli {

// Checks `path` against the inputs and outputs of `command` (recordRunInputs
// first) and opens it for appending. Throws hba::Error naming the file.
spdlog::sink_ptr openLogFile(const std::string& path, const CLI::App& command);

// Why a message could not be written to the log file (a full disk), if one
// could not: the run then fails at the end instead of exiting 0.
std::optional<std::string> logFileFailure();

}  // namespace hba::cli
