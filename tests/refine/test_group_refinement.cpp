// The coarse, whole-sequence half of the refinement: rigid groups of
// consecutive frames placed by one plane BA, for sequences longer than a
// refinement block.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include <Eigen/Geometry>

#include "hba/core/error.hpp"
#include "hba/eval/trajectory_error.hpp"
#include "hba/sim/simulation.hpp"
#include "refine/group_refinement.hpp"
#include "refine_runs.hpp"
#include "settings/refine_settings.hpp"
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

// Each group's move holds at its centre frame and is blended towards its
// neighbours' in between: the frames' corrections change a little from
// frame to frame instead of stepping by the whole difference at a group's
// edge.
TEST(GroupRefinement, GroupMovesSpreadWithoutStepsAtTheEdges) {
  std::vector<Pose> current;
  for (int i = 0; i < 33; ++i) current.emplace_back(Mat3::Identity(), Vec3(0.5 * i, 0.01 * i, 0.0));
  const std::vector<GroupSpan> groups = {{0, 11}, {11, 22}, {22, 33}};  // centres 5, 16, 27
  const Mat3 turn = Eigen::AngleAxisd(0.002, Vec3::UnitZ()).toRotationMatrix();
  const std::vector<Pose> moves = {Pose(), Pose(turn, Vec3(0.0, 0.2, 0.0)),
                                   Pose(Mat3::Identity(), Vec3(0.0, 0.2, 0.1))};
  const std::vector<Pose> out = spreadGroupMoves(groups, moves, current);
  ASSERT_EQ(out.size(), current.size());
  auto expectPose = [](const Pose& a, const Pose& b, const std::string& what) {
    EXPECT_LT((a.t - b.t).norm(), 1e-12) << what;
    EXPECT_LT(a.q.angularDistance(b.q), 1e-12) << what;
  };
  // Up to the first centre and from the last one on: that group's move.
  for (int i = 0; i <= 5; ++i) expectPose(out[i], moves[0] * current[i], "frame " + std::to_string(i));
  for (int i = 27; i < 33; ++i) expectPose(out[i], moves[2] * current[i], "frame " + std::to_string(i));
  expectPose(out[16], moves[1] * current[16], "the middle group's centre");
  // Between centres 5 and 16, frame 10 is 5/11 of the way.
  expectPose(out[10], interpolate(moves[0] * current[10], moves[1] * current[10], 5.0 / 11.0), "frame 10");
  double largest_step = 0.0;
  for (int i = 0; i + 1 < 33; ++i) {
    const Vec3 here = out[i].t - current[i].t;
    const Vec3 next = out[i + 1].t - current[i + 1].t;
    largest_step = std::max(largest_step, (next - here).norm());
  }
  // Group by group, frames 10 and 11 would part by the whole 0.2 m.
  EXPECT_LT(largest_step, 0.03);
  EXPECT_THROW(spreadGroupMoves(groups, {Pose()}, current), Error);
}

// The groups' BA is there to move weak, long modes, which gain less a
// step than fitting the noise would: it takes every step that lowers its
// cost, whatever the blocks' step gate (refine_step_gain). With the gate
// honoured, 5000 simulated frames ended at 3.85 mm ATE instead of 2.34.
TEST(GroupRefinement, GroupsTakeEveryStepWhateverTheBlocksStepGate) {
  const io::MemoryScanSource source(lap().scans);
  std::vector<Pose> placed[2];
  const double gates[2] = {0.0, 1e6};
  for (int k = 0; k < 2; ++k) {
    HbaSettings settings;
    settings.refinement.step_gain = gates[k];
    GroupRefinementReport report;
    StageNotes notes;
    placed[k] = refineGroups(source, lap().initial, lap().initial, settings::refineSettingsOf(settings),
                             report, notes);
    ASSERT_TRUE(report.ran);
    ASSERT_FALSE(report.rejected);
  }
  ASSERT_EQ(placed[0].size(), placed[1].size());
  for (std::size_t i = 0; i < placed[0].size(); ++i) {
    EXPECT_EQ(placed[0][i].t, placed[1][i].t) << "frame " << i;
    EXPECT_EQ(placed[0][i].q.coeffs(), placed[1][i].q.coeffs()) << "frame " << i;
  }
  EXPECT_LT(ate(placed[0]), 0.5 * ate(lap().initial));  // and they did move
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
