// The refinement's plane BA over many frames (ba::refineGlobally): an
// association made already at its start poses (the self-check's, the
// groups' judge) is taken as its first round's instead of being made again.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "hba/ba/association.hpp"
#include "hba/ba/global_refinement.hpp"
#include "same_poses.hpp"
#include "synthetic_window.hpp"

namespace hba::ba {
namespace {

test::SyntheticWindow refinementWindow() {
  test::SyntheticWindowSpec spec;
  spec.frames = 12;
  spec.points_per_patch = 60;
  spec.noise_sigma = 0.01;
  spec.perturb_angle_deg = 0.3;
  spec.perturb_translation = 0.05;
  spec.seed = 7;
  return test::makeSyntheticWindow(spec);
}

RefinementSettings settingsFor() {
  RefinementSettings settings;
  settings.planes.voxel_size = 4.0;
  settings.planes.min_frames = 2;
  return settings;
}

TEST(GlobalRefinement, AnAssociationMadeAtTheStartIsTheFirstRoundsOwn) {
  const test::SyntheticWindow window = refinementWindow();
  const std::vector<const PointCloud*> scans = window.scanPointers();
  const RefinementSettings settings = settingsFor();
  const RefinementResult fresh = refineGlobally(scans, window.initial, settings);
  ASSERT_GT(fresh.planes, 0u);
  ASSERT_GT(fresh.iterations, 0);

  Association given = refinementAssociation(scans, window.initial, settings);
  const RefinementResult reused = refineGlobally(scans, window.initial, settings, {}, {}, {}, &given);
  test::expectSamePoses(reused.poses, fresh.poses);
  EXPECT_EQ(reused.iterations, fresh.iterations);
  EXPECT_EQ(reused.cg_products, fresh.cg_products);
  EXPECT_EQ(reused.rounds, fresh.rounds);
  EXPECT_EQ(reused.cost_before, fresh.cost_before);
  EXPECT_EQ(reused.cost_after, fresh.cost_after);
  EXPECT_EQ(given.problem.numPlanes(), 0u);  // moved from

  // And it is taken, not made again: one found with another outlier share
  // starts the refinement from other planes.
  RefinementSettings other_share = settings;
  other_share.reject_ratio = 0.5;
  Association other = refinementAssociation(scans, window.initial, other_share);
  const std::size_t other_planes = other.problem.numPlanes();
  ASSERT_LT(other_planes, fresh.planes);
  const RefinementResult from_other = refineGlobally(scans, window.initial, settings, {}, {}, {}, &other);
  EXPECT_EQ(from_other.planes, other_planes);
  EXPECT_NE(from_other.cost_before, fresh.cost_before);
}

TEST(GlobalRefinement, ItsOwnResultRefinedAgainStaysPut) {
  const test::SyntheticWindow window = refinementWindow();
  const std::vector<const PointCloud*> scans = window.scanPointers();
  const RefinementSettings settings = settingsFor();
  const RefinementResult first = refineGlobally(scans, window.initial, settings);
  // From the perturbed start, a round gains far more than fitting the
  // points' noise would.
  EXPECT_FALSE(first.converged_at_start);
  EXPECT_LT(first.cost_after, first.cost_before);
  const RefinementResult again = refineGlobally(scans, first.poses, settings);
  EXPECT_TRUE(again.converged_at_start);
  EXPECT_LE(again.last_gain_over_noise, settings.significant_gain);
  test::expectSamePoses(again.poses, first.poses);
  EXPECT_EQ(again.cost_after, again.cost_before);
  // With the gate off, the same call moves the poses: the fixed point is
  // the gate's doing, not a solver that found nothing to do.
  RefinementSettings ungated = settings;
  ungated.significant_gain = 0.0;
  const RefinementResult moved = refineGlobally(scans, first.poses, ungated);
  EXPECT_FALSE(moved.converged_at_start);
  double largest = 0.0;
  for (std::size_t k = 0; k < moved.poses.size(); ++k)
    largest = std::max(largest, (moved.poses[k].t - first.poses[k].t).norm());
  EXPECT_GT(largest, 0.0);
}

}  // namespace
}  // namespace hba::ba
