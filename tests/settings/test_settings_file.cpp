#include <gtest/gtest.h>

#include "hba/pipeline/window_size.hpp"

#include "hba/core/error.hpp"
#include "hba/settings/settings_file.hpp"

namespace hba::settings {
namespace {

TEST(SettingsFile, DefaultsAreThePapers) {
  const HbaSettings s;
  EXPECT_EQ(s.window, 0);                                        // automatic: the paper's 10 for dense scans
  EXPECT_EQ(s.stride, 0);                                        // half the window: the paper's 5
  EXPECT_EQ(pipeline::chooseWindowSize(s, 36000.0).window, 10);  // a simulated HDL-32 scan
  EXPECT_EQ(pipeline::chooseWindowSize(s, 36000.0).stride, 5);
  EXPECT_DOUBLE_EQ(s.local.planes.eigen_ratio, 0.05);
  EXPECT_DOUBLE_EQ(s.global.planes.eigen_ratio, 0.1);
  EXPECT_DOUBLE_EQ(s.local.planes.voxel_size, 4.0);
  EXPECT_DOUBLE_EQ(s.global.planes.voxel_size, 4.0);
  EXPECT_DOUBLE_EQ(s.scan_window_voxel, 2.0);  // ours, not the paper's (docs/pyramid.md)
  EXPECT_NO_THROW(checkSettings(s));
}

TEST(SettingsFile, AppliesOnlyTheKeysGiven) {
  HbaSettings s;
  applySettingsYaml("window: 12\nstride: 4\nglobal:\n  eigen_ratio: 0.2\ntop_down: direct_assign\n",
                    "test.yaml", s);
  EXPECT_EQ(s.window, 12);
  EXPECT_EQ(s.stride, 4);
  EXPECT_DOUBLE_EQ(s.global.planes.eigen_ratio, 0.2);
  EXPECT_DOUBLE_EQ(s.local.planes.eigen_ratio, 0.05);
  EXPECT_EQ(s.top_down, TopDownMode::DirectAssign);
  applySettingsYaml("scan_window_voxel: 0\n", "test.yaml", s);
  EXPECT_DOUBLE_EQ(s.scan_window_voxel, 0.0);
}

TEST(SettingsFile, EmptyFileChangesNothing) {
  HbaSettings s;
  applySettingsYaml("", "empty.yaml", s);
  EXPECT_EQ(s.window, 0);
}

void expectErrorMentions(const std::string& yaml, const std::string& needle) {
  HbaSettings s;
  try {
    applySettingsYaml(yaml, "bad.yaml", s);
    FAIL() << "expected an error for: " << yaml;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bad.yaml"), std::string::npos) << message;
    EXPECT_NE(message.find(needle), std::string::npos) << message;
  }
}

// Issue 57 item 12: a second YAML document was dropped without a word.
TEST(SettingsFile, ASecondYamlDocumentIsRefusedNamingItsLine) {
  expectErrorMentions("window: 12\n---\nstride: 4\n", "a second starts at line 2 ('---')");
  expectErrorMentions("---\nwindow: 12\n---\n# the second run\nstride: 4\n", "line 3");
  expectErrorMentions("---\n---\nwindow: 12\n--- {stride: 4}\n", "line 4");
  try {
    HbaSettings s;
    applySettingsYaml("window: 12\n---\nstride: 4\n", "two.yaml", s);
    FAIL() << "expected a refusal";
  } catch (const ValueError&) {  // the caller's to fix: the tool exits 2
  }
  // One document, with its markers or an empty one after it, is read as before.
  HbaSettings s;
  applySettingsYaml("---\nwindow: 12\n...\n", "one.yaml", s);
  EXPECT_EQ(s.window, 12);
  applySettingsYaml("window: 14\n---\n", "trailing.yaml", s);
  EXPECT_EQ(s.window, 14);
}

TEST(SettingsFile, BadInputIsAClearError) {
  expectErrorMentions("windw: 10\n", "unknown setting 'windw'");
  expectErrorMentions("local:\n  voxel: 1\n", "unknown setting 'local.voxel'");
  expectErrorMentions("window: ten\n", "'window'");
  expectErrorMentions("- 1\n- 2\n", "map");
  expectErrorMentions("window: [1, 2\n", "not valid YAML");
  expectErrorMentions("top_down: sideways\n", "top_down");
}

TEST(SettingsFile, RangeChecks) {
  HbaSettings s;
  s.window = 10;
  s.stride = s.window;
  EXPECT_THROW(checkSettings(s), Error);
  s = HbaSettings();
  s.local.planes.voxel_size = -1;
  EXPECT_THROW(checkSettings(s), Error);
  s = HbaSettings();
  s.global.planes.eigen_ratio = 1.5;
  EXPECT_THROW(checkSettings(s), Error);
  s = HbaSettings();
  s.scan_window_voxel = -2.0;
  EXPECT_THROW(checkSettings(s), Error);
}

TEST(SettingsFile, JsonHasEverySetting) {
  const auto json = settingsToJson(HbaSettings());
  EXPECT_EQ(json.at("window"), 0);
  EXPECT_EQ(json.at("voxel_scans"), 2.0);
  EXPECT_EQ(json.at("local").at("voxel_size"), 4.0);
  EXPECT_EQ(json.at("global").at("eigen_ratio"), 0.1);
}

// --print-config's YAML reads back to the very same settings.
TEST(SettingsFile, PrintedYamlReadsBackToTheSameSettings) {
  HbaSettings changed;
  changed.window = 14;
  changed.stride = 6;
  changed.outer_iterations = 3;
  changed.scan_voxel = 0.15;
  changed.scan_window_voxel = 1.5;
  changed.top_down = TopDownMode::DirectAssign;
  changed.factor_pairs = FactorPairs::FromFirst;
  changed.refine = false;
  changed.setMotionPrior(false);
  changed.refinement.round_gain = 0.035;
  changed.local.planes.eigen_ratio = 0.07;
  changed.global.reject_ratio = 0.1;
  changed.global.check_fixed_map = false;
  HbaSettings read;
  applySettingsYaml(settingsToYaml(changed), "printed", read);
  EXPECT_EQ(settingsToJson(read), settingsToJson(changed));
  // Defaults too: nothing is left out of the file.
  HbaSettings defaults, from_defaults = changed;
  applySettingsYaml(settingsToYaml(defaults), "printed", from_defaults);
  EXPECT_EQ(settingsToJson(from_defaults), settingsToJson(defaults));
}

// Keys named like the flags set the same settings; both names at once is an error.
TEST(SettingsFile, FlagNamedKeysAreTheSameSettings) {
  HbaSettings s;
  applySettingsYaml("iterations: 2\nvoxel: 3\ntheta_local: 0.06\nreject: 0.1\npairs: all\n", "flags", s);
  EXPECT_EQ(s.outer_iterations, 2);
  EXPECT_EQ(s.scan_window_voxel, 3.0);
  EXPECT_EQ(s.local.planes.voxel_size, 3.0);
  EXPECT_EQ(s.global.planes.voxel_size, 3.0);
  EXPECT_EQ(s.local.planes.eigen_ratio, 0.06);
  EXPECT_EQ(s.global.reject_ratio, 0.1);
  EXPECT_EQ(s.factor_pairs, FactorPairs::AllPairs);
  try {
    applySettingsYaml("iterations: 2\nouter_iterations: 3\n", "both.yaml", s);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'iterations' and 'outer_iterations' are the same setting"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hba::settings

namespace hba::settings {
namespace {

std::string errorOf(const std::string& yaml) {
  HbaSettings s;
  try {
    applySettingsYaml(yaml, "cfg.yaml", s);
  } catch (const ValueError& e) {  // the caller's to fix: the tool exits 2
    return e.what();
  }
  return "";
}

// yaml-cpp keeps both entries of a repeated key and reads the first: the
// later line, which looks like it wins, would be ignored in silence.
TEST(SettingsFile, AKeyGivenTwiceIsAnErrorNamingBothLines) {
  EXPECT_EQ(errorOf("window: 10\nstride: 4\nwindow: 12\n"),
            "cfg.yaml: 'window' is given twice (lines 1 and 3); give it once");
  EXPECT_EQ(errorOf("local:\n  voxel_size: 2\n  max_depth: 2\n  voxel_size: 3\n"),
            "cfg.yaml: 'local.voxel_size' is given twice (lines 2 and 4); give it once");
  EXPECT_EQ(errorOf("local:\n  voxel_size: 2\nlocal:\n  max_depth: 2\n"),
            "cfg.yaml: 'local' is given twice (lines 1 and 3); give it once");
  EXPECT_EQ(errorOf("{window: 10, window: 12}\n"),
            "cfg.yaml: 'window' is given twice (both on line 1); give it once");
  // The same value twice is still twice.
  EXPECT_NE(errorOf("refine: false\nrefine: false\n"), "");
  EXPECT_EQ(errorOf("window: 10\nlocal:\n  window: 3\n").find("twice"), std::string::npos);
}

TEST(SettingsFile, BadNumbersSayWhatTheyGotAndWhy) {
  EXPECT_EQ(errorOf("window: -3\n"), "cfg.yaml: setting window must be 0 (automatic) or >= 2, got -3");
  EXPECT_EQ(errorOf("window: 99999999999999999999\n"),
            "cfg.yaml: setting window must be 0 (automatic) or >= 2, got 99999999999999999999 (too large: at "
            "most 2147483647)");
  EXPECT_EQ(errorOf("window: 2.5\n"),
            "cfg.yaml: 'window' has a value of the wrong type; it takes 0 (automatic) or >= 2");
  EXPECT_NE(errorOf("window: 10.0\n"), "");  // a whole number is written as one, as Python's window=10.0
  EXPECT_EQ(errorOf("voxel: 500\n"), "cfg.yaml: setting voxel must be [0.01, 100], got 500 (too large)");
  EXPECT_NE(errorOf("downsample_scans: .nan\n"), "");
  EXPECT_EQ(errorOf("local:\n  voxel_size: .inf\n"),
            "cfg.yaml: setting local.voxel_size must be [0.01, 1000], got inf (not finite)");
  EXPECT_EQ(errorOf("voxel: -.inf\n"), "cfg.yaml: setting voxel must be [0.01, 100], got -inf (not finite)");
}

}  // namespace
}  // namespace hba::settings
