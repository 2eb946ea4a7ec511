// warnAboutFile: once per file, a few files per folder, then one line.
#include <gtest/gtest.h>

#include <string>

#include "io/file_warnings.hpp"
#include "test_log_capture.hpp"

namespace hba::io {
namespace {

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

TEST(FileWarnings, NamesEachFileOnceAndAFewFilesPerFolder) {
  const test::LogCapture log;
  for (int round = 0; round < 2; ++round) {
    for (int i = 0; i < 10; ++i) {
      warnAboutFile("/data/a/" + std::to_string(i) + ".pcd", "test problem", "no points");
    }
  }
  warnAboutFile("/data/b/0.pcd", "test problem", "no points");
  warnAboutFile("/data/a/0.pcd", "other problem", "something else");
  const std::string text = log.text();
  EXPECT_EQ(occurrences(text, ": no points"), kNamedFilesPerProblem + 1) << text;
  EXPECT_EQ(occurrences(text, "/data/a/0.pcd: no points"), 1u) << text;
  EXPECT_EQ(occurrences(text, "/data/b/0.pcd: no points"), 1u) << text;
  EXPECT_EQ(occurrences(text, "/data/a: more files in this folder have the same problem (test problem)"), 1u)
      << text;
  EXPECT_EQ(occurrences(text, "/data/a/0.pcd: something else"), 1u) << text;
}

}  // namespace
}  // namespace hba::io
