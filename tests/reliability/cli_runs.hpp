#pragma once
// Running the built `hba` tool and checking what it wrote.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "hba/core/pose.hpp"
#include "test_support.hpp"

namespace hba::test {

std::string quoted(const std::filesystem::path& path);
// Runs `hba <arguments>` (arguments are passed to the shell as written).
CommandResult runHba(const std::string& arguments);
// `hba -j <threads> optimize <data> -o <out> <extra>`.
CommandResult runOptimize(const std::filesystem::path& data, const std::filesystem::path& out,
                          const std::string& extra = "", int threads = 1);

// The poses of out/pose.json; fails the test (returns empty) if unreadable.
std::vector<Pose> readOptimizedPoses(const std::filesystem::path& out);
// Every output of `hba optimize` exists, parses, and holds no NaN/Inf/null.
void expectFiniteOptimizeOutputs(const std::filesystem::path& out, std::size_t pose_count);

// Runs `hba -q <arguments...>` (no shell), sends it `signal` after `delay`
// unless it has finished, and waits for it. Its stdout is discarded, its
// stderr goes to `log` (discarded if empty). The exit code is 128 + signal
// when the signal ended it before it could handle it, as a shell says.
CommandResult runAndSignal(const std::vector<std::string>& arguments, int signal,
                           std::chrono::milliseconds delay, const std::filesystem::path& log = {});

// Largest translation (m) and rotation (deg) between matching poses.
double largestTranslation(const std::vector<Pose>& a, const std::vector<Pose>& b);
double largestRotationDeg(const std::vector<Pose>& a, const std::vector<Pose>& b);

}  // namespace hba::test
