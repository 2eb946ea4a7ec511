// Raw sweeps: point times read in every unit drivers use, each point moved
// to the stamp's sensor frame by the motion, checked against points made
// from a known motion; PCD files keep the times; a dataset deskews as it loads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "hba/io/dataset.hpp"
#include "hba/io/deskew.hpp"
#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"
#include "test_dataset_support.hpp"
#include "test_log_capture.hpp"
#include "test_scan_helpers.hpp"

namespace hba::io {
namespace {

// 10 m/s forward while turning at 30 deg/s: the sensor at time t (s).
Pose movingSensor(double t) {
  const double yaw = 30.0 * M_PI / 180.0 * t;
  return Pose(Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())), Vec3(10.0 * t, 0.5 * t, 0.2));
}

// World points 2-40 m around, each seen at its own time in [start, start + duration)
// from the moving sensor: the cloud holds them in the sensor frame of that
// time, `truth` in the frame of `stamp`.
struct Sweep {
  PointCloud cloud;
  std::vector<Vec3f> truth;
  std::vector<double> seconds;  // since the stamp
};

Sweep makeSweep(double stamp, double start, std::size_t n = 5000, double duration = 0.1) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> range(2.0, 40.0), angle(-M_PI, M_PI), height(-2.0, 5.0);
  Sweep sweep;
  const Pose at_stamp = movingSensor(stamp).inverse();
  for (std::size_t i = 0; i < n; ++i) {
    const double a = angle(rng), r = range(rng);
    const Vec3 world(r * std::cos(a), r * std::sin(a), height(rng));
    const double since = start + duration * static_cast<double>(i) / static_cast<double>(n);
    sweep.cloud.add((movingSensor(stamp + since).inverse() * world).cast<float>());
    sweep.truth.push_back((at_stamp * world).cast<float>());
    sweep.seconds.push_back(since);
  }
  return sweep;
}

double largestError(const PointCloud& cloud, const std::vector<Vec3f>& truth) {
  double largest = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    largest = std::max(largest, static_cast<double>((cloud.points[i] - truth[i]).norm()));
  }
  return largest;
}

TEST(PointTimes, ReadsEachUnitRelativeOrAbsolute) {
  struct Case {
    std::vector<double> raw;
    double stamp;
    double scale;
    bool absolute;
  };
  const double now = 1.7e9;  // a real clock's stamp, s
  const Case cases[] = {
      {{0.0, 0.05, 0.0999}, 12.0, 1.0, false},                // Velodyne: float s from the stamp
      {{-0.0999, -0.05, 0.0}, now, 1.0, false},               // stamped at the sweep's end
      {{0.0, 50.0, 99.9}, now, 1e-3, false},                  // ms
      {{0.0, 5e4, 99900.0}, now, 1e-6, false},                // us
      {{0.0, 5e7, 9.99e7}, now, 1e-9, false},                 // Ouster t, Livox offset_time: ns
      {{now, now + 0.05, now + 0.0999}, now, 1.0, true},      // Hesai: absolute s
      {{now * 1e9, now * 1e9 + 5e7}, now, 1e-9, true},        // Livox driver 2: absolute ns
      {{now * 1e6, now * 1e6 + 5e4}, now + 0.01, 1e-6, true}  // absolute us
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.raw.back());
    const std::optional<PointTimeReading> reading = readPointTimes(c.raw, c.stamp);
    ASSERT_TRUE(reading.has_value());
    EXPECT_EQ(reading->scale, c.scale);
    EXPECT_EQ(reading->absolute, c.absolute);
  }
}

TEST(PointTimes, TimesThatDoNotSpreadOrFitNoUnitAreNotRead) {
  EXPECT_FALSE(readPointTimes({0.0, 0.0, 0.0}, 5.0).has_value());
  EXPECT_FALSE(readPointTimes({}, 5.0).has_value());
  EXPECT_FALSE(readPointTimes({1e12, 3e12}, 5.0).has_value());  // nothing a sweep lasts
}

// One point a sweep at 5.0 (a driver's stray value) once made the largest
// time decide: read as ms, the whole sweep lasted 0.1 ms and stayed warped.
TEST(PointTimes, AFewStrayValuesDoNotDecideTheUnit) {
  std::vector<double> seconds = makeSweep(0.0, 0.0, 2000).seconds;
  seconds[700] = 5.0;
  std::optional<PointTimeReading> reading = readPointTimes(seconds, 12.0);
  ASSERT_TRUE(reading.has_value());
  EXPECT_EQ(reading->describe(), "s since the scan's stamp");
  // ns from the stamp, with 1 % of the points stray: the one at 5 s and 19
  // at a real clock's ns (absolute-looking).
  std::vector<double> ns;
  for (const double t : seconds) ns.push_back(t * 1e9);
  for (std::size_t i = 1; i < 20; ++i) ns[i * 97] = 1.7e18;
  reading = readPointTimes(ns, 1.7e9);
  ASSERT_TRUE(reading.has_value());
  EXPECT_EQ(reading->describe(), "ns since the scan's stamp");
}

TEST(Deskew, MovesEveryPointToTheStampsFrame) {
  // The stamp at the sweep's start (times 0..0.1 s) and at its end (-0.1..0 s).
  for (const double start : {0.0, -0.1}) {
    SCOPED_TRACE(start);
    const double stamp = 3.0;
    Sweep sweep = makeSweep(stamp, start);
    ASSERT_GT(largestError(sweep.cloud, sweep.truth), 0.5);  // raw: the sweep is warped by metres
    sweep.cloud.time = sweep.seconds;
    deskew(sweep.cloud, PointTimeReading{1.0, false, 0.0}, stamp, movingSensor, "sweep");
    EXPECT_LT(largestError(sweep.cloud, sweep.truth), 5e-4);
    EXPECT_FALSE(sweep.cloud.hasTime());
  }
}

TEST(Deskew, ReadsAbsoluteNanosecondsOnTheRecordingsClock) {
  const double stamp = 1.7e9, offset = 0.25;  // the clouds' clock runs 0.25 s behind the poses'
  // The motion of movingSensor, on a clock that reads `stamp` at its start.
  const auto pose_at = [stamp](double t) { return movingSensor(t - stamp); };
  Sweep sweep = makeSweep(0.0, 0.0);
  for (const double since : sweep.seconds) sweep.cloud.time.push_back((stamp - offset + since) * 1e9);
  std::optional<PointTimeReading> reading = readPointTimes(sweep.cloud.time, stamp - offset);
  ASSERT_TRUE(reading.has_value());
  EXPECT_EQ(reading->describe(), "absolute ns");
  reading->clock_offset = offset;
  deskew(sweep.cloud, *reading, stamp, pose_at, "sweep");
  // ns stamps near 1.7e18 keep ~0.2 us in a double: well under a millimetre of motion.
  EXPECT_LT(largestError(sweep.cloud, sweep.truth), 1e-3);
}

TEST(Deskew, RefusesTimesFarFromTheStamp) {
  Sweep sweep = makeSweep(0.0, 0.0, 10);
  sweep.cloud.time.assign(sweep.cloud.size(), 0.0);
  sweep.cloud.time.back() = 5.0;
  test::expectErrorMentioning(
      [&] { deskew(sweep.cloud, PointTimeReading{}, 0.0, movingSensor, "scan 7"); },
      {"scan 7", "1 of 10 points", "5 s from the scan's stamp", "more than 1 %", "--deskew off"});
}

// Up to 1 % of a sweep with times far from its stamp: those points are left
// out (their instant is unknown) and counted; the rest is deskewed.
TEST(Deskew, LeavesOutAFewPointsWithStrayTimes) {
  const double stamp = 3.0;
  Sweep sweep = makeSweep(stamp, 0.0, 2000);
  sweep.cloud.intensity.assign(sweep.cloud.size(), 1.0f);
  sweep.cloud.time = sweep.seconds;
  for (const std::size_t i : {300, 1999}) {  // a stray time, and one that is not a number
    sweep.cloud.intensity[i] = 9.0f;
  }
  sweep.cloud.time[300] = 5.0;
  sweep.cloud.time[1999] = NAN;
  const StrayTimes stray =
      deskew(sweep.cloud, PointTimeReading{1.0, false, 0.0}, stamp, movingSensor, "sweep");
  EXPECT_EQ(stray.count, 2u);
  ASSERT_EQ(sweep.cloud.size(), 1998u);
  ASSERT_EQ(sweep.cloud.intensity.size(), 1998u);
  EXPECT_EQ(std::count(sweep.cloud.intensity.begin(), sweep.cloud.intensity.end(), 9.0f), 0);
  sweep.truth.erase(sweep.truth.begin() + 1999);
  sweep.truth.erase(sweep.truth.begin() + 300);
  EXPECT_LT(largestError(sweep.cloud, sweep.truth), 5e-4);
}

TEST(PcdTimes, RoundTripInEveryEncodingAndStayAlignedWhenPointsAreDropped) {
  test::TempDir dir;
  PointCloud cloud = test::makeCloud(200, true);
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud.time.push_back(1.7e9 + 1e-6 * static_cast<double>(i));
  cloud.points[10].x() = NAN;  // dropped on reading, with its time
  for (const PcdEncoding encoding :
       {PcdEncoding::Ascii, PcdEncoding::Binary, PcdEncoding::BinaryCompressed}) {
    SCOPED_TRACE(static_cast<int>(encoding));
    writePcd(dir / "sweep.pcd", cloud, encoding);
    const PointCloud back = readPcd(dir / "sweep.pcd");
    ASSERT_EQ(back.size(), cloud.size() - 1);
    ASSERT_EQ(back.time.size(), back.size());
    EXPECT_EQ(back.time[9], cloud.time[9]);
    EXPECT_EQ(back.time[10], cloud.time[11]);  // exact: absolute stamps keep every digit
    EXPECT_EQ(back.points[10], cloud.points[11]);
  }
}

// An Ouster-like point: x y z float, intensity float, t uint32 ns, ring uint16.
TEST(PcdTimes, ReadsAnIntegerTimeFieldAmongOthers) {
  test::TempDir dir;
  std::string text =
      "VERSION 0.7\nFIELDS x y z intensity t reflectivity ring\nSIZE 4 4 4 4 4 2 2\nTYPE F F F F U U U\n"
      "COUNT 1 1 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA binary\n";
  for (std::uint32_t i = 0; i < 3; ++i) {
    const float values[4] = {1.0f + static_cast<float>(i), 2.0f, 3.0f, 7.0f};
    const std::uint32_t t = 50000000u * i;
    const std::uint16_t extra[2] = {9, 3};
    text.append(reinterpret_cast<const char*>(values), sizeof(values));
    text.append(reinterpret_cast<const char*>(&t), sizeof(t));
    text.append(reinterpret_cast<const char*>(extra), sizeof(extra));
  }
  test::writeText(dir / "ouster.pcd", text);
  const PointCloud cloud = readPcd(dir / "ouster.pcd");
  ASSERT_EQ(cloud.time.size(), 3u);
  EXPECT_EQ(cloud.time[2], 1e8);
  EXPECT_EQ(cloud.points[2].x(), 3.0f);
  EXPECT_EQ(cloud.intensity[1], 7.0f);
  EXPECT_EQ(readPointTimes(cloud.time, 1.7e9)->describe(), "ns since the scan's stamp");
}

// Changes scan k's sweep before it is written (its times, its points).
using SweepChange = std::function<void(std::size_t k, double stamp, Sweep& sweep)>;

// A folder of raw sweeps: 10 Hz stamps, poses of the moving sensor.
void writeSweepFolder(const std::filesystem::path& dir, std::size_t scans,
                      std::vector<std::vector<Vec3f>>& truth, bool with_times = true, bool with_stamps = true,
                      const SweepChange& change = {}) {
  std::filesystem::create_directories(dir / "pcd");
  Trajectory poses;
  std::string times;
  for (std::size_t k = 0; k < scans; ++k) {
    const double stamp = 0.1 * static_cast<double>(k);
    Sweep sweep = makeSweep(stamp, 0.0, 2000);
    if (with_times) sweep.cloud.time = sweep.seconds;
    if (change) change(k, stamp, sweep);
    writePcd(dir / "pcd" / (std::to_string(k) + ".pcd"), sweep.cloud);
    truth.push_back(sweep.truth);
    poses.poses.push_back(movingSensor(stamp));
    times += std::to_string(stamp) + "\n";
  }
  writePoses(dir / "pose.json", poses, PoseFormat::Hba);
  if (with_stamps) test::writeText(dir / "times.txt", times);
}

TEST(DatasetDeskew, AFolderOfRawSweepsLoadsDeskewed) {
  test::TempDir dir;
  std::vector<std::vector<Vec3f>> truth;
  writeSweepFolder(dir.path(), 6, truth);
  const Dataset dataset = Dataset::open(dir.path());
  ASSERT_TRUE(dataset.pointTimes().has_value());
  EXPECT_TRUE(test::anyNoteMentions(dataset, "deskewed"));
  for (std::size_t k = 0; k < dataset.size(); ++k) {
    // Poses 0.1 s apart interpolate the turn as an arc: within a few millimetres.
    EXPECT_LT(largestError(dataset.loadScan(k), truth[k]), 0.01) << "scan " << k;
  }
  DatasetOverrides off;
  off.deskew = DeskewMode::Off;
  const Dataset raw = Dataset::open(dir.path(), off);
  EXPECT_FALSE(raw.pointTimes().has_value());
  const PointCloud as_recorded = raw.loadScan(2);
  EXPECT_GT(largestError(as_recorded, truth[2]), 0.5);
  EXPECT_FALSE(as_recorded.hasTime());
}

TEST(DatasetDeskew, DeskewsByBetterPosesWhenGiven) {
  test::TempDir dir;
  std::vector<std::vector<Vec3f>> truth;
  writeSweepFolder(dir.path(), 4, truth);
  Dataset dataset = Dataset::open(dir.path());
  const double by_input = largestError(dataset.loadScan(1), truth[1]);
  // Poses that do not move: the sweep stays as recorded.
  dataset.deskewBy(std::vector<Pose>(dataset.size(), Pose::identity()));
  EXPECT_GT(largestError(dataset.loadScan(1), truth[1]), 0.5);
  EXPECT_LT(by_input, 0.01);
  test::expectErrorMentioning([&] { dataset.deskewBy({Pose::identity()}); }, {"1 poses for 4 scans"});
}

TEST(DatasetDeskew, OnIsRefusedWhereItCannotBeDone) {
  DatasetOverrides on;
  on.deskew = DeskewMode::On;
  {
    test::TempDir dir;
    std::vector<std::vector<Vec3f>> truth;
    writeSweepFolder(dir.path(), 3, truth, /*with_times=*/false);
    test::expectErrorMentioning([&] { Dataset::open(dir.path(), on); },
                                {"0.pcd", "--deskew on", "no per-point time", "offset_time"});
    EXPECT_FALSE(Dataset::open(dir.path()).pointTimes().has_value());  // auto: nothing to do, silently
  }
  {
    test::TempDir dir;
    std::vector<std::vector<Vec3f>> truth;
    writeSweepFolder(dir.path(), 3, truth, true, /*with_stamps=*/false);
    test::expectErrorMentioning([&] { Dataset::open(dir.path(), on); }, {"--deskew on", "no stamps"});
    const Dataset left = Dataset::open(dir.path());
    EXPECT_FALSE(left.pointTimes().has_value());
    EXPECT_TRUE(test::anyNoteMentions(left, "left as recorded"));
  }
}

// Issue 57: one point a sweep at 5.0 s. The unit was read as ms from it and
// every sweep stayed warped by metres (ATE 63.8 mm against 1.2 mm); now the
// bulk of the times decides, the stray point is left out with a warning
// naming the file, and the sweeps are deskewed.
TEST(DatasetDeskew, AStrayTimeInEverySweepLeavesTheRestDeskewed) {
  test::TempDir dir;
  std::vector<std::vector<Vec3f>> truth;
  writeSweepFolder(dir.path(), 5, truth, true, true, [](std::size_t, double, Sweep& sweep) {
    sweep.cloud.time.back() = 5.0;  // the last point: the others keep their truth's index
  });
  DatasetOverrides on;
  on.deskew = DeskewMode::On;
  const Dataset dataset = Dataset::open(dir.path(), on);
  ASSERT_TRUE(dataset.pointTimes().has_value());
  EXPECT_EQ(dataset.pointTimes()->describe(), "s since the scan's stamp");
  test::LogCapture log;
  for (std::size_t k = 0; k < dataset.size(); ++k) {
    const PointCloud scan = dataset.loadScan(k);
    ASSERT_EQ(scan.size(), 1999u);
    EXPECT_LT(largestError(scan, truth[k]), 0.01) << "scan " << k;
  }
  const std::string said = log.text();
  EXPECT_NE(said.find("0.pcd: 1 of 2000 points have times more than 1 s from the scan's stamp"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("left out"), std::string::npos);
}

// More than 1 % of a sweep far from its stamp: the times are misread; the
// scan is refused, as docs/recordings.md says.
TEST(DatasetDeskew, ManyTimesFarFromTheStampAreRefused) {
  test::TempDir dir;
  std::vector<std::vector<Vec3f>> truth;
  writeSweepFolder(dir.path(), 5, truth, true, true, [](std::size_t k, double, Sweep& sweep) {
    if (k == 3) std::fill(sweep.cloud.time.end() - 100, sweep.cloud.time.end(), 5.0);
  });
  const Dataset dataset = Dataset::open(dir.path());
  EXPECT_LT(largestError(dataset.loadScan(2), truth[2]), 0.01);
  test::expectErrorMentioning([&] { dataset.loadScan(3); },
                              {"3.pcd", "100 of 2000 points", "more than 1 %", "--deskew off"});
}

// The first sweep a driver sends is often partial: its ns times span 1 ms,
// which alone reads as us (and the full sweeps then as 100 s long, refused).
// The unit comes from scans sampled along the run.
TEST(DatasetDeskew, TheUnitComesFromScansAlongTheRunNotTheFirstAlone) {
  test::TempDir dir;
  std::vector<std::vector<Vec3f>> truth;
  writeSweepFolder(dir.path(), 12, truth, true, true, [](std::size_t k, double stamp, Sweep& sweep) {
    if (k == 0) sweep = makeSweep(stamp, 0.0, 2000, 0.001);
    sweep.cloud.time = sweep.seconds;
    for (double& t : sweep.cloud.time) t = std::round(t * 1e9);
  });
  const Dataset dataset = Dataset::open(dir.path());
  ASSERT_TRUE(dataset.pointTimes().has_value());
  EXPECT_EQ(dataset.pointTimes()->describe(), "ns since the scan's stamp");
  EXPECT_TRUE(test::anyNoteMentions(dataset, "scan 0 would read as us since the scan's stamp"));
  for (std::size_t k = 0; k < dataset.size(); ++k) {
    EXPECT_LT(largestError(dataset.loadScan(k), truth[k]), 0.01) << "scan " << k;
  }
  // Without a majority, no unit is chosen: auto leaves the scans, on refuses.
  test::TempDir split;
  writeSweepFolder(split.path(), 2, truth, true, true, [](std::size_t k, double, Sweep& sweep) {
    if (k == 1) {
      for (double& t : sweep.cloud.time) t *= 1e3;  // ms
    }
  });
  EXPECT_FALSE(Dataset::open(split.path()).pointTimes().has_value());
  DatasetOverrides on;
  on.deskew = DeskewMode::On;
  test::expectErrorMentioning([&] { Dataset::open(split.path(), on); },
                              {"--deskew on", "scan 0 read as s since the scan's stamp", "scan 1 as ms"});
}

}  // namespace
}  // namespace hba::io
