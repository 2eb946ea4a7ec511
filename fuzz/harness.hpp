#pragma once
// One entry per fuzz target: reads a file the way that target's parser does.
// Shared by the libFuzzer targets (fuzz/*.cpp) and by the regression test
// (tests/reliability), so a saved crash input is replayed through exactly the
// code the fuzzer ran.
//
// Each function returns normally when the parser accepted the input or threw
// hba::Error (the documented way to reject bad input). Any other exception
// escapes; a parser that returns data breaking its promises (NaN points,
// non-unit quaternions, mismatched intensity count) aborts.
#include <filesystem>
#include <string>
#include <vector>

namespace hba::fuzz {

using Harness = void (*)(const std::filesystem::path& input);

struct Target {
  std::string name;  // the fuzz target and the folder of its corpus/regressions
  Harness feed;
};

void feedPcd(const std::filesystem::path& input);
void feedPly(const std::filesystem::path& input);
void feedKittiBin(const std::filesystem::path& input);
void feedLas(const std::filesystem::path& input);
void feedHbaPoses(const std::filesystem::path& input);
void feedKittiPoses(const std::filesystem::path& input);
void feedTumPoses(const std::filesystem::path& input);
void feedSettingsYaml(const std::filesystem::path& input);
void feedLoopFile(const std::filesystem::path& input);
void feedPriorFile(const std::filesystem::path& input);
void feedReportJson(const std::filesystem::path& input);

// Recordings (harness_recordings.cpp).
void feedRos1Bag(const std::filesystem::path& input);
void feedDb3(const std::filesystem::path& input);
// The input is a rosbag2 folder's metadata.yaml, beside a fixed valid .db3.
void feedRosbag2Metadata(const std::filesystem::path& input);
// The input is one message: its first byte picks the type and serialization
// (harness_recordings.cpp), the rest is the message as a container stores it.
void feedRosMessage(const std::filesystem::path& input);

// Shared by the recording targets: a recording file read as every command
// reads it. The container (each channel's messages read and decoded by
// their type), then the recording (topics chosen, trajectory read, scans
// placed and loaded; then with the first cloud topic and a /tf trajectory
// named, and keyframes). A target for another container format calls this on
// its input (fuzz/CMakeLists.txt says how to add a target).
void feedRecordingFile(const std::filesystem::path& input);
void feedMcap(const std::filesystem::path& input);  // harness_mcap.cpp

// Every target, in the order scripts/fuzz.sh runs them.
const std::vector<Target>& allTargets();

}  // namespace hba::fuzz
