#include "cli_runs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>

#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"

namespace hba::test {
namespace fs = std::filesystem;

namespace {

int countNulls(const nlohmann::json& value) {
  if (value.is_null()) return 1;
  int nulls = 0;
  if (value.is_structured()) {
    for (const nlohmann::json& child : value) nulls += countNulls(child);
  }
  return nulls;
}

}  // namespace

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

CommandResult runHba(const std::string& arguments) {
  CommandResult result = runCommand(quoted(cliPath()) + " " + arguments);
  // For writing RELIABILITY.md: what the tool said in each scenario.
  if (std::getenv("HBA_SHOW_CLI_OUTPUT")) {
    std::cout << "$ hba " << arguments << "\n" << result.output << "(exit " << result.exit_code << ")\n";
  }
  return result;
}

CommandResult runOptimize(const fs::path& data, const fs::path& out, const std::string& extra, int threads) {
  return runHba("-j " + std::to_string(threads) + " optimize " + quoted(data) + " -o " + quoted(out) + " " +
                extra);
}

std::vector<Pose> readOptimizedPoses(const fs::path& out) {
  try {
    return io::readPoses(out / "pose.json", io::PoseFormat::Hba).poses;
  } catch (const Error& e) {
    ADD_FAILURE() << e.what();
    return {};
  }
}

void expectFiniteOptimizeOutputs(const fs::path& out, std::size_t pose_count) {
  // The pose readers reject NaN and Inf, so parsing is the finiteness check.
  const std::vector<std::pair<std::string, io::PoseFormat>> files = {
      {"pose.json", io::PoseFormat::Hba},
      {"poses_kitti.txt", io::PoseFormat::Kitti},
      {"poses_tum.txt", io::PoseFormat::Tum}};
  for (const auto& [name, format] : files) {
    try {
      EXPECT_EQ(io::readPoses(out / name, format).size(), pose_count) << name;
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
    }
  }
  // nlohmann::json writes NaN and Inf as null.
  const std::string report = readText(out / "report.json");
  ASSERT_TRUE(nlohmann::json::accept(report)) << report;
  EXPECT_EQ(countNulls(nlohmann::json::parse(report)), 0) << report;
}

double largestTranslation(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    largest = std::max(largest, (a[i].t - b[i].t).norm());
  }
  return largest;
}

double largestRotationDeg(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double largest = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    largest = std::max(largest, a[i].q.angularDistance(b[i].q) * 180.0 / 3.14159265358979323846);
  }
  return largest;
}

}  // namespace hba::test
