// The windows' errors against a reference: each error lands in its layer's
// row, on its axis, in degrees or metres, measured in the window's first frame.
#include <gtest/gtest.h>

#include <cmath>

#include "hba/core/error.hpp"
#include "hba/pipeline/window_errors.hpp"

namespace hba::pipeline {
namespace {

Pose yawed(double deg, const Vec3& t) {
  return Pose(Quat(Eigen::AngleAxisd(deg * M_PI / 180.0, Vec3::UnitZ())), t);
}

// Four scans along x, turning left 90 degrees between scans 1 and 2.
std::vector<Pose> referencePath() {
  return {yawed(0, {0, 0, 0}), yawed(0, {1, 0, 0}), yawed(90, {2, 0, 0}), yawed(90, {2, 1, 0})};
}

WindowRecord windowOf(int layer, const std::vector<std::size_t>& nodes, const std::vector<Pose>& poses) {
  WindowRecord record;
  record.iteration = 1;
  record.layer = layer;
  record.nodes = nodes;
  for (std::size_t node : nodes) {
    record.start.push_back(poses[node]);
    record.optimized.push_back(poses[node]);
  }
  return record;
}

TEST(WindowErrors, ExactPosesHaveNoErrorAndLayersGetARowEach) {
  const std::vector<Pose> truth = referencePath();
  // Moved as a whole: only relative poses count.
  std::vector<Pose> moved;
  for (const Pose& pose : truth) moved.push_back(yawed(30, {5, -2, 1}) * pose);
  const std::vector<WindowRecord> records = {windowOf(1, {0, 1, 2}, moved), windowOf(1, {2, 3}, moved),
                                             windowOf(2, {0, 2}, moved)};
  const auto rows = windowErrors(records, moved, moved, moved, truth);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].layer, 1);
  EXPECT_EQ(rows[0].windows, 2u);
  EXPECT_EQ(rows[0].pairs, 3u);
  EXPECT_EQ(rows[1].layer, 2);
  EXPECT_EQ(rows[1].pairs, 1u);
  for (const auto& row : rows) {
    for (const RelativeErrorRms* e : {&row.input, &row.start, &row.window, &row.hierarchy, &row.final}) {
      EXPECT_NEAR(e->rotation_rms_deg, 0.0, 1e-9);
      EXPECT_NEAR(e->translation_rms_m, 0.0, 1e-12);
    }
  }
}

// A window's frame turned 0.2 degrees about its own x axis after a 90
// degree turn: in the window's first frame that is a turn about y, and
// only the column the error is in shows it.
TEST(WindowErrors, AnErrorShowsOnItsAxisInTheFirstFramesCoordinates) {
  const std::vector<Pose> truth = referencePath();
  WindowRecord record = windowOf(1, {0, 1, 2}, truth);
  record.optimized[2] =
      record.optimized[2] * Pose(Quat(Eigen::AngleAxisd(0.2 * M_PI / 180.0, Vec3::UnitX())), Vec3(0, 0, 0));
  record.start[1].t += Vec3(0.03, 0, 0);  // began 3 cm ahead on x
  const auto rows = windowErrors({record}, truth, truth, truth, truth);
  ASSERT_EQ(rows.size(), 1u);
  const LayerWindowErrors& row = rows[0];
  const double rms = 0.2 / std::sqrt(2.0);  // one of two pairs
  EXPECT_NEAR(row.window.rotation_deg[0], 0.0, 1e-9);
  EXPECT_NEAR(row.window.rotation_deg[1], rms, 1e-9);
  EXPECT_NEAR(row.window.rotation_deg[2], 0.0, 1e-9);
  EXPECT_NEAR(row.window.rotation_rms_deg, rms, 1e-9);
  EXPECT_NEAR(row.window.translation_rms_m, 0.0, 1e-12);
  EXPECT_NEAR(row.start.translation_m[0], 0.03 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(row.start.translation_m[1], 0.0, 1e-12);
  EXPECT_NEAR(row.start.rotation_rms_deg, 0.0, 1e-9);
  EXPECT_NEAR(row.input.rotation_rms_deg, 0.0, 1e-9);
}

TEST(WindowErrors, PosesOfAnotherLengthAreRefused) {
  const std::vector<Pose> truth = referencePath();
  const std::vector<Pose> short_path(truth.begin(), truth.end() - 1);
  EXPECT_THROW(windowErrors({}, truth, truth, short_path, truth), Error);
  WindowRecord beyond = windowOf(1, {0, 1}, truth);
  beyond.nodes[1] = 7;
  EXPECT_THROW(windowErrors({beyond}, truth, truth, truth, truth), Error);
}

}  // namespace
}  // namespace hba::pipeline
