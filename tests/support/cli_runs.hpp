#pragma once
// Helpers for tests that drive the `hba` tool end to end: run a command
// that must succeed, read a JSON report, and score a trajectory with
// `hba eval`. Header-only: only tests that link nlohmann-json include it.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "test_support.hpp"

namespace hba::test {

inline std::string hbaTool() { return cliPath().string(); }

// Fails the test (with the command's output) unless `command` exits 0.
inline void runOk(const std::string& command) {
  const CommandResult result = runCommand(command);
  ASSERT_EQ(result.exit_code, 0) << command << "\n" << result.output;
}

inline nlohmann::json readJson(const std::filesystem::path& path) {
  return nlohmann::json::parse(readText(path));
}

// RMSE (m) of `hba eval`'s translation error of `est` against `gt`:
// `what` is "ate" or "rpe"; `flags` are more eval flags (--align, --delta).
inline double evalRmse(const std::string& what, const std::filesystem::path& gt,
                       const std::filesystem::path& est, const std::filesystem::path& scratch,
                       const std::string& flags = "") {
  const std::filesystem::path json = scratch / (what + ".json");
  const CommandResult result = runCommand(hbaTool() + " -q eval --gt " + gt.string() + " --est " +
                                          est.string() + " " + flags + " --force --json " + json.string());
  EXPECT_EQ(result.exit_code, 0) << result.output;
  return readJson(json).at(what).at("translation_m").at("rmse").get<double>();
}

// ATE translation RMSE (m) of `est` against `gt` in gt's frame, unaligned:
// for results that must come out in a given frame.
inline double ateInFrame(const std::filesystem::path& gt, const std::filesystem::path& est,
                         const std::filesystem::path& scratch) {
  return evalRmse("ate", gt, est, scratch, "--align none");
}

}  // namespace hba::test
