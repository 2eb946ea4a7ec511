#pragma once
// Helpers for the io tests: fixture paths, hand-made folders of scans, and
// checking that an hba::Error names what it should.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "hba/core/error.hpp"
#include "hba/io/dataset.hpp"
#include "test_support.hpp"

namespace hba::test {

inline std::filesystem::path datasetDir(const std::string& name) { return dataDir() / "datasets" / name; }

// Creates `dir` with empty files of these names: discovery never reads them.
inline void makeScans(const std::filesystem::path& dir, const std::vector<std::string>& names) {
  std::filesystem::create_directories(dir);
  for (const std::string& name : names) writeText(dir / name, "");
}

inline std::string kittiPoseLines(std::size_t n) {
  std::string text;
  for (std::size_t i = 0; i < n; ++i) text += "1 0 0 " + std::to_string(i) + " 0 1 0 0 0 0 1 0\n";
  return text;
}

inline std::string hbaPoseLines(std::size_t n) {
  std::string text;
  for (std::size_t i = 0; i < n; ++i) text += std::to_string(i) + " 0 0 1 0 0 0\n";
  return text;
}

inline bool anyNoteMentions(const io::Dataset& dataset, const std::string& piece) {
  for (const io::DatasetNote& note : dataset.notes()) {
    if (note.text.find(piece) != std::string::npos) return true;
  }
  return false;
}

// Runs `action`, expects an hba::Error whose message contains every piece.
template <typename Action>
void expectErrorMentioning(Action action, const std::vector<std::string>& pieces) {
  try {
    action();
    ADD_FAILURE() << "expected an hba::Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const std::string& piece : pieces) {
      EXPECT_NE(message.find(piece), std::string::npos) << "'" << piece << "' not in: " << message;
    }
  }
}

}  // namespace hba::test
