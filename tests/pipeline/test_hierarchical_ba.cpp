// The pyramid as a library: runHierarchicalBa on simulated scans held in
// memory (and once read from a folder).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <random>
#include <string>
#include <thread>

#include "hba/core/error.hpp"
#include "hba/eval/trajectory_error.hpp"
#include "hba/io/dataset.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"
#include "hba/pipeline/window_size.hpp"
#include "hba/sim/simulation.hpp"
#include "hba/voxel/downsample.hpp"
#include "simulated_sequence.hpp"
#include "test_support.hpp"
#include "threaded_group.hpp"

namespace hba::pipeline {
namespace {

using test::Sequence;

// A short simulated drive (solid-state sensor: small scans, fast test).
const Sequence& simulated() {
  static const Sequence sequence = [] {
    sim::SimulationConfig config;
    config.seed = 11;
    config.trajectory.frames = 40;
    config.sensor = sim::sensorPreset(sim::SensorModel::Livox);
    config.drift.translation = 0.03;
    config.drift.rotation_deg_per_m = 0.05;
    return test::simulateSequence(config);
  }();
  return sequence;
}

double ate(const Trajectory& truth, const std::vector<Pose>& poses) {
  Trajectory estimate;
  estimate.poses = poses;
  return eval::evaluateTrajectory(truth, estimate).ate.translation_m.rmse;
}

HbaResult optimize(const HbaSettings& settings) {
  // The scans as simulated: the pyramid downsamples them to settings.scan_voxel.
  const io::MemoryScanSource source(simulated().scans);
  return runHierarchicalBa(source, simulated().initial, settings);
}

// The paper's windows (10 frames every 5): 40 frames make a pyramid.
HbaSettings paperWindows() {
  HbaSettings settings;
  settings.window = 10;
  return settings;
}

TEST(HierarchicalBa, ReducesTheDriftOfASimulatedDrive) {
  const HbaResult result = optimize(paperWindows());
  const double before = ate(simulated().truth, simulated().initial);
  const double after = ate(simulated().truth, result.poses);
  EXPECT_LT(after, before / 5.0) << "before " << before << " after " << after;
  ASSERT_EQ(result.poses.size(), simulated().initial.size());
  // The gauge: the first pose is held.
  EXPECT_LT((result.poses.front().t - simulated().initial.front().t).norm(), 1e-9);
  EXPECT_GE(result.report.layers, 2);
  EXPECT_FALSE(result.report.iterations.empty());
  EXPECT_TRUE(result.report.warnings.empty());
}

// --window 0 (the default): chosen from the scans' points (small Livox
// scans: more than ten), reported, and the drift still goes; windows given
// are reported as given.
TEST(HierarchicalBa, AutomaticWindowsAreChosenFromThePointsAndReported) {
  const HbaResult result = optimize(HbaSettings());
  EXPECT_TRUE(result.report.windows.automatic);
  EXPECT_GT(result.report.windows.points_per_scan, 0.0);
  EXPECT_GT(result.report.windows.window, 10);
  EXPECT_GE(result.report.windows.window * result.report.windows.points_per_scan, kWindowPoints);
  EXPECT_EQ(result.report.windows.stride, result.report.windows.window / 2);
  EXPECT_LT(ate(simulated().truth, result.poses), ate(simulated().truth, simulated().initial) / 5.0);
  const HbaResult given = optimize(paperWindows());
  EXPECT_FALSE(given.report.windows.automatic);
  EXPECT_EQ(given.report.windows.window, 10);
  EXPECT_EQ(given.report.windows.stride, 5);
}

TEST(HierarchicalBa, DirectAssignAlsoImproves) {
  HbaSettings settings;
  settings.top_down = TopDownMode::DirectAssign;
  const HbaResult result = optimize(settings);
  EXPECT_LT(ate(simulated().truth, result.poses), ate(simulated().truth, simulated().initial));
}

TEST(HierarchicalBa, SameResultWithOneAndTwoThreads) {
  HbaSettings settings;
  settings.outer_iterations = 1;
  std::vector<Pose> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = optimize(settings).poses;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = optimize(settings).poses;
  }
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].t, two[i].t) << "frame " << i;
    EXPECT_EQ(one[i].q.coeffs(), two[i].q.coeffs()) << "frame " << i;
  }
}

// A layer's windows spread over 2 and 3 members (threads standing in for
// mpirun's processes): every member ends with the poses of one process,
// bit for bit, and the same layer reports.
TEST(HierarchicalBa, MembersOfAGroupGetThePosesOfOneProcess) {
  HbaSettings settings;
  settings.window = 6;  // three layers of 40 frames: upper layers are spread too
  settings.stride = 3;
  settings.layers = 3;
  settings.outer_iterations = 2;  // the second starts from the pose graph, which holds the priors
  const io::MemoryScanSource source(simulated().scans);
  // Position priors on three frames (the truth, 1 m off the input's frame):
  // the closure stage's outcome is shared by the first member.
  ClosureInputs closures;
  for (const std::size_t frame : {std::size_t{0}, std::size_t{20}, std::size_t{39}}) {
    graph::PositionPriorFactor prior;
    prior.node = frame;
    prior.position = simulated().truth.poses[frame].t + Vec3(1.0, 0.0, 0.0);
    prior.information = Mat3::Identity() * 100.0;
    closures.priors.push_back(prior);
  }
  const HbaResult alone = runHierarchicalBa(source, simulated().initial, settings, closures);
  ASSERT_EQ(alone.report.layers, 3);
  for (const int size : {2, 3}) {
    hba::test::ThreadedGroups groups(size);
    std::vector<HbaResult> results(static_cast<std::size_t>(size));
    std::vector<std::thread> members;
    for (int rank = 0; rank < size; ++rank) {
      members.emplace_back([&, rank] {
        results[static_cast<std::size_t>(rank)] =
            runHierarchicalBa(source, simulated().initial, settings, closures, groups.member(rank));
      });
    }
    for (std::thread& member : members) member.join();
    for (const HbaResult& result : results) {
      ASSERT_EQ(result.poses.size(), alone.poses.size());
      for (std::size_t i = 0; i < alone.poses.size(); ++i) {
        ASSERT_EQ(result.poses[i].t, alone.poses[i].t) << size << " members, frame " << i;
        ASSERT_EQ(result.poses[i].q.coeffs(), alone.poses[i].q.coeffs()) << size << " members, frame " << i;
      }
      ASSERT_EQ(result.report.layer_reports.size(), alone.report.layer_reports.size());
      for (std::size_t l = 0; l < alone.report.layer_reports.size(); ++l) {
        const LayerReport& a = alone.report.layer_reports[l];
        const LayerReport& b = result.report.layer_reports[l];
        EXPECT_EQ(b.windows, a.windows);
        EXPECT_EQ(b.planes, a.planes);
        EXPECT_EQ(b.cloud_points, a.cloud_points) << "layer " << l + 1;
        EXPECT_EQ(b.cost_after, a.cost_after) << "layer " << l + 1;
        EXPECT_EQ(a.exchange_bytes, 0u);  // one process sends nothing
        EXPECT_GT(b.exchange_bytes, b.exchange_bytes_largest);
        EXPECT_GT(b.exchange_bytes_largest, 0u);
      }
    }
  }
}

// The same scans from a dataset folder and from memory: the same poses, bit
// for bit; the report times reading and downsampling either way.
TEST(HierarchicalBa, ScansFromMemoryAndFromAFolderGiveTheSamePoses) {
  hba::test::TempDir dir;
  std::filesystem::create_directories(dir / "Scans");
  for (std::size_t i = 0; i < simulated().scans.size(); ++i) {
    io::writePcd(dir / "Scans" / (std::to_string(100000 + i) + ".pcd"), simulated().scans[i]);
  }
  io::writePoses(dir / "odom_poses.txt", Trajectory{simulated().initial, {}}, io::PoseFormat::Kitti);
  const io::Dataset dataset = io::Dataset::open(dir.path());
  HbaSettings settings;
  settings.outer_iterations = 1;
  const HbaResult from_folder =
      runHierarchicalBa(io::DatasetScanSource(dataset), simulated().initial, settings);
  const HbaResult from_memory = optimize(settings);
  ASSERT_EQ(from_folder.poses.size(), from_memory.poses.size());
  for (std::size_t i = 0; i < from_folder.poses.size(); ++i) {
    EXPECT_EQ(from_folder.poses[i].t, from_memory.poses[i].t) << "frame " << i;
    EXPECT_EQ(from_folder.poses[i].q.coeffs(), from_memory.poses[i].q.coeffs()) << "frame " << i;
  }
  for (const HbaReport* report : {&from_folder.report, &from_memory.report}) {
    EXPECT_GT(report->seconds_read, 0.0);
    EXPECT_GT(report->seconds_downsample, 0.0);
  }
}

// Window 6, stride 4 on 40 frames: the last layer-1 window holds 4 frames,
// so keyframes and direct assignment must follow the plan's uneven tail.
HbaSettings unevenTailSettings() {
  HbaSettings settings;
  settings.window = 6;
  settings.stride = 4;
  settings.top_down = TopDownMode::DirectAssign;
  settings.refine = false;
  return settings;
}

TEST(HierarchicalBa, UnevenLastWindowsStillImprove) {
  const HbaResult result = optimize(unevenTailSettings());
  EXPECT_GE(result.report.layers, 3);
  ASSERT_EQ(result.poses.size(), simulated().initial.size());
  EXPECT_LT(ate(simulated().truth, result.poses), ate(simulated().truth, simulated().initial) / 2.0);
}

TEST(HierarchicalBa, SameInputGivesTheSamePosesBitForBit) {
  for (const HbaSettings& settings : {HbaSettings(), unevenTailSettings()}) {
    const std::vector<Pose> first = optimize(settings).poses;
    const std::vector<Pose> second = optimize(settings).poses;
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
      EXPECT_EQ(first[i].t, second[i].t) << "frame " << i;
      EXPECT_EQ(first[i].q.coeffs(), second[i].q.coeffs()) << "frame " << i;
    }
  }
}

// The scans the run read, downsampled and kept, are handed on (for the
// picture): each is the scan downsampled at settings.scan_voxel, bit for bit.
TEST(HierarchicalBa, HandsOnTheScansAsItReadThem) {
  const io::MemoryScanSource source(simulated().scans);
  const HbaSettings settings;
  const HbaResult result = runHierarchicalBa(source, simulated().initial, settings);
  ASSERT_TRUE(result.scans);
  ASSERT_EQ(result.scans->size(), source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    const PointCloud kept = result.scans->load(i);
    const PointCloud expected = voxel::downsample(source.load(i), settings.scan_voxel);
    ASSERT_EQ(kept.size(), expected.size()) << "scan " << i;
    EXPECT_EQ(kept.origin, expected.origin) << "scan " << i;
    for (std::size_t k = 0; k < kept.size(); ++k)
      ASSERT_EQ(kept.points[k], expected.points[k]) << i << ", " << k;
  }
}

TEST(HierarchicalBa, FeaturelessScansLeavePosesUnchangedWithAWarning) {
  // Points filling a volume (foliage-like): no voxel passes the plane test.
  std::vector<PointCloud> scans(12);
  std::vector<Pose> poses(12);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-4.0f, 4.0f);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    poses[i].t = Vec3(0.2 * static_cast<double>(i), 0, 0);
    for (int k = 0; k < 3000; ++k) scans[i].add(Vec3f(coordinate(rng), coordinate(rng), coordinate(rng)));
  }
  const io::MemoryScanSource source(scans);
  HbaSettings settings;
  settings.scan_voxel = 0.0;  // every point of the volume
  const HbaResult result = runHierarchicalBa(source, poses, settings);
  ASSERT_EQ(result.poses.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(result.poses[i].t, poses[i].t);
  }
  ASSERT_FALSE(result.report.warnings.empty());
  EXPECT_NE(result.report.warnings.back().find("no plane features"), std::string::npos);
}

TEST(HierarchicalBa, RejectsMismatchedInput) {
  const io::MemoryScanSource source(std::vector<PointCloud>(3));
  EXPECT_THROW(runHierarchicalBa(source, std::vector<Pose>(4), HbaSettings()), Error);
  const io::MemoryScanSource empty(std::vector<PointCloud>{});
  EXPECT_THROW(runHierarchicalBa(empty, {}, HbaSettings()), Error);
}

// hba -j refuses more than kMostThreads: the library (and so hba.optimize) too.
TEST(HierarchicalBa, RefusesMoreThreadsThanHbaJTakes) {
  const io::MemoryScanSource source(std::vector<PointCloud>(3));
  HbaSettings settings;
  settings.threads = kMostThreads + 1;
  try {
    runHierarchicalBa(source, std::vector<Pose>(3), settings);
    ADD_FAILURE() << "expected an hba::Error";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("thread count must be from 0 (as many as allowed) to 4096, got 4097"),
        std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hba::pipeline
