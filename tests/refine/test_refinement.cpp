// The last stage on its own: the self-check on the input's planes and the
// sparse refinement over every frame, on simulated scans held in memory.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

#include "hba/ba/association.hpp"
#include "hba/core/error.hpp"
#include "hba/core/lie.hpp"
#include "hba/eval/trajectory_error.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/sim/simulation.hpp"
#include "hba/voxel/downsampled_scan_source.hpp"
#include "refine/consistency.hpp"
#include "refine_runs.hpp"
#include "simulated_sequence.hpp"

namespace hba::refine {
using pipeline::HbaReport;
namespace {

using test::Sequence;

const Sequence& simulated() {
  static const Sequence sequence = [] {
    sim::SimulationConfig config;
    config.seed = 5;
    config.trajectory.frames = 60;
    config.sensor = sim::sensorPreset(sim::SensorModel::Livox);
    config.drift.translation = 0.02;
    return test::simulateSequence(config);
  }();
  return sequence;
}

double ate(const std::vector<Pose>& poses) {
  Trajectory estimate;
  estimate.poses = poses;
  return eval::evaluateTrajectory(simulated().truth, estimate).ate.translation_m.rmse;
}

std::vector<Pose> run(const std::vector<Pose>& hierarchy, const HbaSettings& settings, HbaReport& report) {
  // The refinement is given layer-1 scans at the scan voxel, as the pyramid passes them.
  const io::MemoryScanSource scans(simulated().scans);
  const voxel::DownsampledScanSource source(scans, settings.scan_voxel);
  return refineAs3Layers(source, simulated().initial, hierarchy, settings, report);
}

// A long refinement keeps its blocks' self-check maps on disk: read back,
// a map measures any poses exactly as the map it was written from.
TEST(RefineStage, KeptSelfCheckMapReadsBackTheSame) {
  const auto& seq = simulated();
  std::vector<const PointCloud*> scans;
  for (const PointCloud& scan : seq.scans) scans.push_back(&scan);
  voxel::PlaneSettings planes;
  planes.voxel_size = 1.0;
  const FixedPlaneMap map(ba::associate(scans, seq.initial, planes, 0.05).problem, seq.initial.size(), 4);
  ASSERT_GT(map.planes(), 10u);
  const std::string path = ::testing::TempDir() + "kept_map.bin";
  map.save(path);
  const FixedPlaneMap back = FixedPlaneMap::load(path);
  std::remove(path.c_str());
  EXPECT_EQ(back.planes(), map.planes());
  EXPECT_EQ(back.points(), map.points());
  EXPECT_EQ(back.regionStarts(), map.regionStarts());
  for (const std::vector<Pose>* poses : {&seq.initial, &seq.truth.poses}) {
    EXPECT_EQ(back.rms(*poses), map.rms(*poses));
    EXPECT_EQ(back.regionRms(*poses), map.regionRms(*poses));
    // Both figures from one evaluation: the same as each on its own.
    const FixedPlaneMap::Figures figures = map.figures(*poses);
    EXPECT_EQ(figures.rms, map.rms(*poses));
    EXPECT_EQ(figures.region_rms, map.regionRms(*poses));
  }
  EXPECT_THROW(FixedPlaneMap::load(path), Error);  // gone: a clear error, not an empty map
}

// From the drifting input itself (as when the hierarchy is refused), the
// refinement alone removes most of a 2 % drift over 60 frames.
TEST(RefineStage, RefinementReducesDriftAndReportsConsistency) {
  HbaReport report;
  const std::vector<Pose> result = run(simulated().initial, HbaSettings(), report);
  EXPECT_LT(ate(result), 0.5 * ate(simulated().initial));
  EXPECT_TRUE(report.refinement.ran);
  EXPECT_EQ(report.refinement.blocks, 1u);
  EXPECT_GT(report.consistency.planes, 10u);
  EXPECT_LT(report.consistency.final_rms, report.consistency.input_rms);
  EXPECT_FALSE(report.consistency.final_rejected);
  EXPECT_EQ(report.consistency.region_first_frame.size(), report.consistency.region_final_rms.size());
  EXPECT_LT((result.front().t - simulated().initial.front().t).norm(), 1e-9);  // gauge
}

// A hierarchy that slid a stretch of frames by half a metre sideways is
// caught on the input's planes: the stage starts again from the input,
// warns, and still ends crisper than the input.
TEST(RefineStage, RefusesAHierarchyThatBlurredTheMap) {
  std::vector<Pose> broken = simulated().initial;
  for (std::size_t i = 30; i < broken.size(); ++i) broken[i].t += Vec3(0.0, 0.5, 0.0);
  HbaSettings settings;
  settings.refine = false;
  HbaReport report;
  const std::vector<Pose> result = run(broken, settings, report);
  EXPECT_TRUE(report.consistency.hierarchy_rejected);
  EXPECT_GT(report.consistency.hierarchy_rms, report.consistency.input_rms);
  ASSERT_FALSE(report.warnings.empty());
  // Without the refinement nothing is refined: the warning says what is returned.
  EXPECT_NE(report.warnings.front().find("keeping the input poses"), std::string::npos)
      << report.warnings.front();
  EXPECT_EQ(report.warnings.front().find("refining"), std::string::npos) << report.warnings.front();
  for (std::size_t i = 0; i < result.size(); ++i) {
    EXPECT_LT((result[i].t - simulated().initial[i].t).norm(), 1e-9) << "frame " << i;
  }
  // With it, the refinement starts from the input, and says so.
  HbaReport refined;
  run(broken, HbaSettings(), refined);
  ASSERT_FALSE(refined.warnings.empty());
  EXPECT_NE(refined.warnings.front().find("refining from the input"), std::string::npos)
      << refined.warnings.front();
}

// From a drifting start the planes found first are not all the planes:
// the stage associates again while a round still cuts the cost, which ends
// closer to the truth than one association; a round gain of 100 % allows
// one round only.
TEST(RefineStage, ReassociatesWhileARoundStillGains) {
  HbaSettings once;
  once.refinement.round_gain = 1.0;
  HbaReport report_once;
  const std::vector<Pose> single = run(simulated().initial, once, report_once);
  HbaReport report;
  const std::vector<Pose> repeated = run(simulated().initial, HbaSettings(), report);
  EXPECT_EQ(report_once.refinement.rounds, 1);
  EXPECT_GT(report.refinement.rounds, 1);
  EXPECT_LE(report.refinement.rounds, HbaSettings().refinement.association_rounds);
  EXPECT_LT(ate(repeated), ate(single));
  std::printf("ATE one association %.4f m, %d associations %.4f m\n", ate(single), report.refinement.rounds,
              ate(repeated));
}

// A small point budget splits the sequence into overlapping blocks; the
// result is still far better than the input.
TEST(RefineStage, BlocksBoundTheMemoryAndStillRefine) {
  HbaSettings settings;
  std::size_t points = 0;
  for (const PointCloud& scan : simulated().scans) points += scan.size();
  settings.refine_max_points = std::max<std::size_t>(1000, points / 12);
  HbaReport report;
  const std::vector<Pose> result = run(simulated().initial, settings, report);
  EXPECT_GE(report.refinement.blocks, 3u);
  EXPECT_LT(ate(result), 0.7 * ate(simulated().initial));
  EXPECT_LE(report.consistency.final_rms, report.consistency.input_rms);
}

// The first block read and its input's planes found beforehand (beside
// the pose graph, in the pipeline) give the very outcome of the stage
// finding them itself: in one block and in several, its scans kept from
// the start or not, and where the hierarchy moved the first frame (its
// planes are then found again).
TEST(RefineStage, APreparedStartGivesTheSameOutcome) {
  const auto& seq = simulated();
  const io::MemoryScanSource scans(seq.scans);
  HbaSettings settings;
  const voxel::DownsampledScanSource source(scans, settings.scan_voxel);
  std::size_t points = 0;
  for (const PointCloud& scan : seq.scans) points += scan.size();
  // The truth, placed where the input has its first frame (as the
  // hierarchy holds it), and moved off it by a centimetre.
  const Pose onto = seq.initial.front() * seq.truth.poses.front().inverse();
  std::vector<Pose> held;
  for (const Pose& pose : seq.truth.poses) held.push_back(onto * pose);
  held.front() = seq.initial.front();
  std::vector<Pose> moved = held;
  for (Pose& pose : moved) pose.t += Vec3(0.01, 0.0, 0.0);
  for (const std::size_t max_points : {std::size_t{100000000}, std::max<std::size_t>(1000, points / 12)}) {
    for (const std::size_t layer_one_points : {std::size_t{0}, std::size_t{1} << 40}) {
      for (const std::vector<Pose>* hierarchy : {&held, &moved}) {
        settings.refine_max_points = max_points;
        const RefineSettings refining = settings::refineSettingsOf(settings);
        HierarchyFacts facts;
        facts.layers = 3;
        facts.layer_one_points = layer_one_points;
        const RefineOutcome found = refineAndCheck(source, seq.initial, *hierarchy, facts, {}, refining);
        PreparedStart prepared = prepareStart(source, seq.initial, facts, refining);
        const RefineOutcome given =
            refineAndCheck(source, seq.initial, *hierarchy, facts, {}, refining, &prepared);
        const std::string where = std::to_string(max_points) + " points a block, " +
                                  (hierarchy == &held ? "first frame held" : "first frame moved");
        ASSERT_EQ(found.poses.size(), given.poses.size()) << where;
        for (std::size_t i = 0; i < found.poses.size(); ++i) {
          ASSERT_EQ(found.poses[i].t, given.poses[i].t) << where << ", frame " << i;
          ASSERT_EQ(found.poses[i].q.coeffs(), given.poses[i].q.coeffs()) << where << ", frame " << i;
        }
        EXPECT_EQ(found.consistency.input_rms, given.consistency.input_rms) << where;
        EXPECT_EQ(found.consistency.final_rms, given.consistency.final_rms) << where;
        EXPECT_EQ(found.refinement.blocks, given.refinement.blocks) << where;
        if (max_points < 100000000) {
          EXPECT_GE(found.refinement.blocks, 2u) << where;
        }
      }
    }
  }
}

}  // namespace
}  // namespace hba::refine
