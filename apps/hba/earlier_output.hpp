#pragma once
// An earlier `hba optimize` output folder read back (`hba view OUT`, and
// `hba optimize --map OUT`): the run's report.json and what it names (parsed
// by pyramid/output_report.hpp, which the fuzzer reaches).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dataset_args.hpp"
#include "hba/core/pose.hpp"
#include "hba/io/dataset.hpp"

namespace hba::cli {

// Whether `folder` holds an output's report.json and pose.json.
bool isOptimizeOutput(const std::filesystem::path& folder);

// The report of an optimize output. Throws hba::Error naming `folder`
// when it is not one, and report.json when it cannot be parsed.
nlohmann::json readOutputReport(const std::filesystem::path& folder);

// A text field of the report's `input` section ("dataset", "poses",
// "pose_frame"). Throws hba::Error naming report.json when it is missing.
std::string outputInput(const nlohmann::json& report, const std::filesystem::path& folder, const char* key);

// A true/false field of the report's `input` section ("scans_in_world"),
// false when absent. Throws hba::Error naming report.json for another value.
bool outputInputFlag(const nlohmann::json& report, const std::filesystem::path& folder, const char* key);

// The dataset the run that wrote `folder` read, opened as that run opened it
// (a recording with the topics, offset and keyframes of input.recording),
// `given`'s flags winning where set. Throws hba::Error naming report.json
// when its dataset entry is empty or names what is no longer there, and
// saying where the path came from in any error opening it.
io::Dataset openEarlierDataset(const nlohmann::json& report, const std::filesystem::path& folder,
                               DatasetArgs given);

// The run's optimized sensor poses (folder/pose.json), one per scan of
// `dataset`. Throws hba::Error naming pose.json when the counts differ, and
// why they may (a keyframed recording whose report does not record its
// keyframes).
std::vector<Pose> earlierPoses(const io::Dataset& dataset, const nlohmann::json& report,
                               const std::filesystem::path& folder);

}  // namespace hba::cli
