// The coarse, whole-sequence half of the refinement: rigid groups of
// consecutive frames placed by one plane BA, for sequences longer than a
// refinement block.
#include <gtest/gtest.h>

#include <cstdio>

#include "hba/eval/trajectory_error.hpp"
#include "hba/sim/simulation.hpp"
#include "refine/group_refinement.hpp"
#include "refine_runs.hpp"
#include "simulated_sequence.hpp"

namespace hba::refine {
using pipeline::HbaReport;
namespace {

using test::Sequence;

// 1.25 laps of a 100 m block: the last 25 m drive over the first.
const Sequence& lap() {
  static const Sequence sequence = [] {
    sim::SimulationConfig config;
    config.seed = 3;
    config.trajectory.frames = 250;
    config.downsample_voxel = 0.2;
    config.drift.translation = 0.02;
    config.drift.rotation_deg_per_m = 0.02;
    return test::simulateSequence(config);
  }();
  return sequence;
}

double ate(const std::vector<Pose>& poses) {
  Trajectory estimate;
  estimate.poses = poses;
  return eval::evaluateTrajectory(lap().truth, estimate).ate.translation_m.rmse;
}

std::size_t totalPoints() {
  std::size_t points = 0;
  for (const PointCloud& scan : lap().scans) points += scan.size();
  return points;
}

std::vector<Pose> run(const HbaSettings& settings, HbaReport& report) {
  const io::MemoryScanSource source(lap().scans);
  return refineAs3Layers(source, lap().initial, lap().initial, settings, report);
}

TEST(GroupRefinement, GroupSizeKeepsTheGroupCountBounded) {
  EXPECT_EQ(groupSize(5000, 500, 10), 10u);
  EXPECT_EQ(groupSize(20000, 500, 10), 40u);
  EXPECT_EQ(groupSize(20001, 500, 10), 41u);
  EXPECT_EQ(groupSize(300, 500, 10), 10u);
  EXPECT_EQ(groupSize(300, 0, 0), 300u);  // nonsense settings still give one group
}

// Blocks of consecutive frames lose the planes the last stretch shares
// with the first; the groups, placed after the blocks, see the whole lap at
// once and give most of that back: closer to one block over everything
// than to blocks alone.
TEST(GroupRefinement, GroupsRecoverWhatBlocksLoseOnARevisit) {
  HbaSettings whole;
  whole.refine_max_points = 2 * totalPoints();
  HbaReport whole_report;
  const double one_block = ate(run(whole, whole_report));
  ASSERT_EQ(whole_report.refinement.blocks, 1u);
  EXPECT_FALSE(whole_report.refinement.groups.ran);  // one block sees everything already

  HbaSettings blocks = whole;
  blocks.refine_max_points = totalPoints() / 5;
  blocks.refine_groups = false;
  HbaReport blocks_report;
  const double blocks_only = ate(run(blocks, blocks_report));
  ASSERT_GE(blocks_report.refinement.blocks, 5u);

  HbaSettings grouped = blocks;
  grouped.refine_groups = true;
  HbaReport grouped_report;
  const double with_groups = ate(run(grouped, grouped_report));
  const GroupRefinementReport& g = grouped_report.refinement.groups;
  EXPECT_TRUE(g.ran);
  EXPECT_EQ(g.groups, 25u);
  EXPECT_EQ(g.frames_per_group, 10u);
  EXPECT_LT(g.rms_after, g.rms_before);
  EXPECT_FALSE(g.rejected);
  std::printf("ATE input %.4f m, one block %.4f m, blocks %.4f m, blocks then groups %.4f m\n",
              ate(lap().initial), one_block, blocks_only, with_groups);
  // The self-check is measured again after the groups moved: figures for
  // every stretch, and the map crisper than the input.
  const ConsistencyReport& c = grouped_report.consistency;
  EXPECT_EQ(c.region_final_rms.size(), blocks_report.consistency.region_final_rms.size());
  EXPECT_LT(c.final_rms, c.input_rms);
  EXPECT_LT(with_groups, blocks_only);
  EXPECT_LT(with_groups - one_block, 0.5 * (blocks_only - one_block));
}

}  // namespace
}  // namespace hba::refine
