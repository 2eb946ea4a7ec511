#pragma once
// The one output rule: what a run writes never replaces or deletes what it
// reads, nor what hba did not write.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/output_lock.hpp"
#include "core/path_inside.hpp"
#include "hba/io/dataset.hpp"

namespace hba::cli {

// Records every existing file or folder named by an option or argument of
// `command` other than its outputs (-o/--output, --json, --plot): the run's
// inputs, which no output may replace. Called once the command line is parsed.
void recordRunInputs(const CLI::App& command);
const std::vector<std::filesystem::path>& runInputs();
// The values of `command`'s output options, as given.
std::vector<std::filesystem::path> namedOutputs(const CLI::App& command);

// Throws hba::Error if `output` (a file or folder to be written) is the
// dataset's folder, its scans folder, or anything inside them.
void refuseOutputInsideInput(const std::filesystem::path& output, const io::Dataset& dataset);

// Throws hba::Error if `output` is an input of this run or holds one (a
// folder is replaced whole): `--poses run1/pose.json -o run1 --force`.
void refuseReplacingInputs(const std::filesystem::path& output);

// The rule for single files (map, render, eval --json/--plot): never an
// input of the run, an existing file only with --force (then replaced
// atomically), and one run at a time. Hold the lock until it is written.
std::unique_ptr<OutputLock> claimOutputFile(const std::filesystem::path& output, bool force);

}  // namespace hba::cli
