#include <gtest/gtest.h>

#include "hba/core/error.hpp"
#include "hba/pyramid/settings_file.hpp"

namespace hba::pyramid {
namespace {

TEST(SettingsFile, DefaultsAreThePapers) {
  const HbaSettings s;
  EXPECT_EQ(s.window, 10);
  EXPECT_EQ(s.stride, 5);
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
  EXPECT_EQ(s.window, 10);
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
  EXPECT_EQ(json.at("window"), 10);
  EXPECT_EQ(json.at("scan_window_voxel"), 2.0);
  EXPECT_EQ(json.at("local").at("voxel_size"), 4.0);
  EXPECT_EQ(json.at("global").at("eigen_ratio"), 0.1);
}

}  // namespace
}  // namespace hba::pyramid
