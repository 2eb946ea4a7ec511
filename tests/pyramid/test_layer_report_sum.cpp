// A layer's report sums its windows' figures.
#include <gtest/gtest.h>

#include <cmath>

#include "layer_report_sum.hpp"

namespace hba::pyramid {
namespace {

WindowSummary summary(std::size_t planes, double rms_before, double rms_after, bool trusted) {
  WindowSummary s;
  s.outcome.has_planes = planes > 0;
  s.planes = planes;
  s.plane_points = 20 * planes;
  s.cost_before = 2.0 * static_cast<double>(planes);
  s.cost_after = 0.5 * static_cast<double>(planes);
  s.sq_rms_before = static_cast<double>(planes) * rms_before * rms_before;
  s.sq_rms_after = static_cast<double>(planes) * rms_after * rms_after;
  s.iterations = static_cast<int>(planes) + 1;
  s.rounds = 2;
  s.trusted = trusted;
  return s;
}

TEST(LayerReportSum, SumsCountsAndCostsOverWindows) {
  WindowSummary settled_again = summary(3, 0.02, 0.01, true);
  settled_again.settled = true;
  settled_again.solved_again = true;
  const LayerReport r =
      sumLayerReport({settled_again, summary(1, 0.06, 0.03, false), summary(0, 0.0, 0.0, true)});
  EXPECT_EQ(r.windows, 3u);
  EXPECT_EQ(r.planes, 4u);
  EXPECT_EQ(r.plane_points, 80u);
  EXPECT_EQ(r.lm_iterations, 4u + 2u + 1u);
  EXPECT_EQ(r.association_rounds, 6u);
  EXPECT_DOUBLE_EQ(r.cost_before, 8.0);
  EXPECT_DOUBLE_EQ(r.cost_after, 2.0);
  EXPECT_EQ(r.windows_without_planes, 1u);
  EXPECT_EQ(r.windows_untrusted, 1u);
  EXPECT_EQ(r.windows_settled, 1u);
  EXPECT_EQ(r.windows_solved_again, 1u);
}

TEST(LayerReportSum, RmsWeighsEveryPlaneAlike) {
  const LayerReport r = sumLayerReport({summary(3, 0.02, 0.01, true), summary(1, 0.06, 0.03, true)});
  // Over four planes, not the mean of the two windows' RMS.
  EXPECT_NEAR(r.rms_before, std::sqrt((3 * 0.02 * 0.02 + 0.06 * 0.06) / 4.0), 1e-15);
  EXPECT_NEAR(r.rms_after, std::sqrt((3 * 0.01 * 0.01 + 0.03 * 0.03) / 4.0), 1e-15);
}

TEST(LayerReportSum, NoPlanesGivesZeroRmsAndLeavesTheCallersFieldsAlone) {
  const LayerReport r = sumLayerReport({summary(0, 0.0, 0.0, true)});
  EXPECT_EQ(r.rms_before, 0.0);
  EXPECT_EQ(r.rms_after, 0.0);
  EXPECT_EQ(r.frames, 0u);
  EXPECT_EQ(r.cloud_points, 0u);
  EXPECT_EQ(sumLayerReport({}).windows, 0u);
}

}  // namespace
}  // namespace hba::pyramid
