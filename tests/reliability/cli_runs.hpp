#pragma once
// Running the built `hba` tool and checking what it wrote.
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

// Largest translation (m) and rotation (deg) between matching poses.
double largestTranslation(const std::vector<Pose>& a, const std::vector<Pose>& b);
double largestRotationDeg(const std::vector<Pose>& a, const std::vector<Pose>& b);

}  // namespace hba::test
