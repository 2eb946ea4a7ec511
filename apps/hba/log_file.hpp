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

// A log file's lines: "[2026-11-28 10:00:00.000] [info] ...", with times.
inline constexpr const char* kLogFilePattern = "[%Y-%m-%d %H:%M:%S.%e] [%l] %v";

// Checks `path` against the inputs and outputs of `command` (recordRunInputs
// first), opens it for appending and writes the run's first line. Throws
// hba::Error naming the file (also when that line cannot be written).
spdlog::sink_ptr openLogFile(const std::string& path, const CLI::App& command);

// Why a message could not be written to the log file (a full disk), if one
// could not: the run then fails at the end instead of exiting 0.
std::optional<std::string> logFileFailure();

}  // namespace hba::cli
