#include "pipeline/convention_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "hba/voxel/downsample.hpp"
#include "hba/voxel/key_table.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::pipeline {
namespace {

// The distinct voxels a map occupies: only their count is needed. A flat
// table, not a node per voxel (26 alternative maps fill one each).
class KeySet {
 public:
  void insert(const voxel::VoxelKey& key) {
    bool inserted = false;
    index_.insert(key, inserted);
  }
  std::size_t size() const { return index_.size(); }
  void clear() { index_.clear(); }

 private:
  voxel::VoxelIndex index_;
};

double rotationDeg(const Pose& a, const Pose& b) { return a.q.angularDistance(b.q) * 180.0 / M_PI; }

// Stretches of consecutive frames, spread over the sequence, each long
// enough (in path or turn) that wrong poses would smear the map visibly.
std::vector<std::vector<std::size_t>> pickStretches(const std::vector<Pose>& poses,
                                                    const ConventionSettings& s) {
  std::vector<std::vector<std::size_t>> stretches;
  const std::size_t n = poses.size();
  for (std::size_t k = 0; k < s.max_stretches; ++k) {
    const std::size_t first = n * k / s.max_stretches;
    double path = 0.0;
    std::size_t last = first;
    while (last + 1 < n && path < s.stretch_length &&
           rotationDeg(poses[first], poses[last]) < s.stretch_rotation_deg) {
      path += (poses[last + 1].t - poses[last].t).norm();
      ++last;
    }
    const bool moved =
        path >= s.stretch_length || rotationDeg(poses[first], poses[last]) >= s.stretch_rotation_deg;
    if (!moved || last == first) continue;
    std::vector<std::size_t> frames;
    const std::size_t count = std::min(s.stretch_scans, last - first + 1);
    for (std::size_t j = 0; j < count; ++j) frames.push_back(first + (last - first) * j / (count - 1));
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    if (stretches.empty() || stretches.back().front() != frames.front()) stretches.push_back(frames);
  }
  return stretches;
}

// The 24 rotations that map axes onto axes (signed permutation matrices
// with determinant +1), the identity first.
std::vector<Mat3> axisRotations() {
  std::vector<Mat3> rotations{Mat3::Identity()};
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& order : orders) {
    for (int signs = 0; signs < 8; ++signs) {
      Mat3 R = Mat3::Zero();
      for (int row = 0; row < 3; ++row) R(row, order[row]) = (signs >> row & 1) ? -1.0 : 1.0;
      if (R.determinant() > 0.0 && !R.isIdentity()) rotations.push_back(R);
    }
  }
  return rotations;
}

bool isCameraAxes(const Mat3& R) {
  Mat3 camera_to_sensor;  // a camera's x right, y down, z forward in a z-up, x-forward sensor
  camera_to_sensor << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return R.isApprox(camera_to_sensor.transpose());
}

std::string extrinsicText(const Mat3& R) {
  const Quat q(R);
  const auto clean = [](double v) { return std::abs(v) < 1e-12 ? 0.0 : v; };
  return fmt::format("0 0 0 {:.6g} {:.6g} {:.6g} {:.6g}", clean(q.x()), clean(q.y()), clean(q.z()),
                     clean(q.w()));
}

// Each point's voxel into `keys`, and into `also` when given (one key a point).
void addVoxels(const PointCloud& scan, const Pose& pose, double voxel, KeySet& keys, KeySet* also = nullptr) {
  const Mat3 R = pose.R();
  for (const Vec3f& p : scan.points) {
    const voxel::VoxelKey key = voxel::VoxelKey::of(R * p.cast<double>() + pose.t, voxel);
    keys.insert(key);
    if (also) also->insert(key);
  }
}

// From the scores: the verdict and the message that says it, unless the
// poses as given are clearly best.
void judgeConventions(ConventionCheck& check, const GivenConventions& given, const ConventionSettings& s) {
  const double best_other = std::min({check.inverted, check.in_world, check.turned,
                                      given.scans_in_world ? check.as_stored : check.as_given});
  if (best_other > s.decisive_ratio * check.as_given) return;
  const std::string scores = fmt::format(
      "merged over {} stretches of the path, the map occupies {:.2f} scans' worth of {} m voxels with the "
      "poses as given, {:.2f} with each pose inverted, {:.2f} with no poses at all, {:.2f} with the poses "
      "of a body turned against the sensor",
      check.stretches, check.as_given, s.voxel, check.inverted, check.in_world, check.turned);
  const std::string on_top = given.extrinsic ? " (on top of the --extrinsic or calibration given)" : "";
  if (given.scans_in_world && check.as_stored == best_other) {
    check.verdict = ConventionVerdict::ScansNotInWorld;
    check.message =
        "the scans line up as stored, in the sensor frame, not moved into the world: " + scores +
        fmt::format(", {:.2f} with the scans as stored. Run again without --scans-in-world", check.as_stored);
  } else if (check.turned == best_other) {
    check.verdict = ConventionVerdict::TurnedBody;
    const std::string turn = extrinsicText(check.turn);
    check.message =
        isCameraAxes(check.turn)
            ? "the poses look like a camera's (x right, y down, z forward, as KITTI's camera 0): " + scores +
                  ". hba needs poses of the scans' sensor: give the sensor-to-camera "
                  "transform with --calib calib.txt (KITTI's Tr) or --extrinsic"
            : "the poses look like those of a body (an IMU, a vehicle frame) whose axes are turned "
              "against the scans' sensor: " +
                  scores +
                  ". hba needs poses of the scans' sensor: give "
                  "the body-to-sensor transform with --extrinsic 'tx ty tz qx qy qz qw'; the turn that "
                  "fits best is --extrinsic '" +
                  turn + "' (add your lever arm)" + on_top;
  } else if (check.inverted == best_other) {
    check.verdict = ConventionVerdict::PosesInverted;
    check.message =
        "the poses look inverted (world-to-sensor): " + scores +
        ". hba expects sensor-to-world poses (p_world = R p + t); " +
        (given.invert_poses ? "run again without --invert-poses" : "run again with --invert-poses");
  } else {
    check.verdict = ConventionVerdict::ScansInWorld;
    check.message = "the scans look already moved into the world frame: " + scores +
                    ". hba expects scans in the sensor frame; run again with --scans-in-world";
    if (given.scans_in_world)
      check.message = "the scans still look moved into the world frame after --scans-in-world: " + scores;
  }
  check.message += " (or --no-convention-check to run as given)";
}

}  // namespace

ConventionCheck checkConventions(const io::ScanSource& scans, const std::vector<Pose>& poses,
                                 const GivenConventions& given, const ConventionSettings& s) {
  ConventionCheck check;
  const std::vector<std::vector<std::size_t>> stretches = pickStretches(poses, s);
  check.stretches = stretches.size();
  if (stretches.empty()) return check;
  const std::vector<Mat3> turns = axisRotations();
  std::vector<double> turned(turns.size(), 0.0);  // [0]: as given
  double inverted = 0.0, world = 0.0, stored = 0.0, single = 0.0;
  // One set a thread, emptied between maps: 24 sets held at once, each
  // grown by doubling into fresh memory, were most of the check's time (page
  // faults) and its memory.
  tbb::enumerable_thread_specific<KeySet> thread_sets;
  for (const std::vector<std::size_t>& frames : stretches) {
    KeySet as_inverted, as_world, as_stored;
    // Halving the voxel first keeps the counts and makes 26 merges cheap.
    std::vector<PointCloud> clouds(frames.size());
    tbb::parallel_for(std::size_t{0}, frames.size(), [&](std::size_t f) {
      clouds[f] = voxel::downsample(scans.load(frames[f]), 0.5 * s.voxel);
    });
    // Each alternative merges into a set of its own: the turns in parallel.
    tbb::parallel_for(std::size_t{0}, turns.size(), [&](std::size_t k) {
      KeySet& as_turned = thread_sets.local();
      as_turned.clear();
      for (std::size_t f = 0; f < frames.size(); ++f) {
        addVoxels(clouds[f], poses[frames[f]] * Pose(turns[k], Vec3::Zero()), s.voxel, as_turned);
      }
      turned[k] += static_cast<double>(as_turned.size());
    });
    for (std::size_t f = 0; f < frames.size(); ++f) {
      const std::size_t i = frames[f];
      const PointCloud& scan = clouds[f];
      KeySet& own = thread_sets.local();
      own.clear();
      addVoxels(scan, Pose::identity(), s.voxel, own, &as_world);  // as_world: merged with no poses
      single += static_cast<double>(own.size()) / static_cast<double>(frames.size());
      addVoxels(scan, poses[i].inverse(), s.voxel, as_inverted);
      // The source moved scans back by their pose; moving them twice
      // undoes that: the scans as stored, with their poses.
      if (given.scans_in_world) addVoxels(scan, poses[i] * poses[i], s.voxel, as_stored);
    }
    inverted += static_cast<double>(as_inverted.size());
    world += static_cast<double>(as_world.size());
    stored += static_cast<double>(as_stored.size());
  }
  if (single <= 0.0) return check;
  if (single < s.min_scan_voxels) {
    check.cannot_tell = fmt::format(
        "the scans hold too few points to tell: {:.1f} occupied {} m voxels a scan on average, at least {} "
        "needed",
        single, s.voxel, s.min_scan_voxels);
    return check;
  }
  const auto best_turn = std::min_element(turned.begin() + 1, turned.end());
  check.as_given = turned.front() / single;
  check.turned = *best_turn / single;
  check.turn = turns[static_cast<std::size_t>(best_turn - turned.begin())];
  check.inverted = inverted / single;
  check.in_world = world / single;
  check.as_stored = stored / single;
  judgeConventions(check, given, s);
  return check;
}

}  // namespace hba::pipeline
