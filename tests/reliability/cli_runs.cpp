#include "cli_runs.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "hba/core/error.hpp"
#include "hba/io/pose_file.hpp"

extern char** environ;

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

CommandResult runAndSignal(const std::vector<std::string>& arguments, int signal,
                           std::chrono::milliseconds delay, const fs::path& log) {
  std::vector<std::string> words = {cliPath().string(), "-q"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  const std::string log_path = log.empty() ? std::string("/dev/null") : log.string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw Error("cannot start " + words[0]);
  std::this_thread::sleep_for(delay);
  ::kill(pid, signal);
  int status = 0;
  ::waitpid(pid, &status, 0);
  CommandResult result;
  result.exit_code = WIFEXITED(status)     ? WEXITSTATUS(status)
                     : WIFSIGNALED(status) ? 128 + WTERMSIG(status)
                                           : -1;
  if (!log.empty()) result.output = readText(log);
  return result;
}

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
