// Replays every saved fuzz input (fuzz/regressions/<target>/*, crashes found
// and fixed) and every seed (fuzz/corpus/<target>/*) through the same harness
// the fuzzers run: each must be accepted or rejected with hba::Error, never
// crash or throw anything else. One test per file, so a failure names it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "harness.hpp"

namespace hba {
namespace {
namespace fs = std::filesystem;

struct SavedInput {
  std::string target;
  fuzz::Harness feed = nullptr;
  fs::path file;
};

// Printed by gtest (and so in ctest's test names) as the file, not as the
// struct's raw bytes, which hold pointers and change from build to build.
void PrintTo(const SavedInput& input, std::ostream* os) { *os << input.file.filename().string(); }

std::vector<SavedInput> savedInputs(const fs::path& root) {
  std::vector<SavedInput> inputs;
  for (const fuzz::Target& target : fuzz::allTargets()) {
    const fs::path folder = root / target.name;
    if (!fs::is_directory(folder)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
      if (entry.is_regular_file()) inputs.push_back({target.name, target.feed, entry.path()});
    }
  }
  std::sort(inputs.begin(), inputs.end(),
            [](const SavedInput& a, const SavedInput& b) { return a.file < b.file; });
  return inputs;
}

std::string testName(const testing::TestParamInfo<SavedInput>& info) {
  std::string name = info.param.target + "_" + info.param.file.filename().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name + "_" + std::to_string(info.index);  // unique even if names collide
}

class FuzzRegression : public testing::TestWithParam<SavedInput> {};

TEST_P(FuzzRegression, RejectedWithErrorOrAccepted) {
  const SavedInput& input = GetParam();
  EXPECT_NO_THROW(input.feed(input.file)) << input.file;
}

INSTANTIATE_TEST_SUITE_P(Regressions, FuzzRegression,
                         testing::ValuesIn(savedInputs(HBA_FUZZ_DIR "/regressions")), testName);
INSTANTIATE_TEST_SUITE_P(Seeds, FuzzRegression, testing::ValuesIn(savedInputs(HBA_FUZZ_DIR "/corpus")),
                         testName);

// The seeds are the parsers' good inputs: a harness wired to the wrong folder
// would replay nothing and pass, so insist every target has seeds.
TEST(FuzzCorpus, EveryTargetHasSeeds) {
  const std::vector<SavedInput> seeds = savedInputs(HBA_FUZZ_DIR "/corpus");
  for (const fuzz::Target& target : fuzz::allTargets()) {
    const auto count = std::count_if(seeds.begin(), seeds.end(),
                                     [&](const SavedInput& s) { return s.target == target.name; });
    EXPECT_GE(count, 1) << target.name;
  }
}

}  // namespace
}  // namespace hba
