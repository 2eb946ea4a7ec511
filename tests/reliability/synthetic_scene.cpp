#include "synthetic_scene.hpp"

#include <cmath>
#include <random>
#include <string>

#include "hba/io/pcd.hpp"
#include "hba/io/pose_file.hpp"

namespace hba::test {
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Points on axis-aligned planes: each plane fixes one coordinate and spans a
// box in the other two.
struct Face {
  int fixed_axis;
  double value;
  Vec3 lo, hi;  // the box the free coordinates are drawn from
};

std::vector<Vec3> sampleFaces(const std::vector<Face>& faces, std::size_t count, std::mt19937_64& rng) {
  std::vector<Vec3> points;
  points.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Face& face = faces[i % faces.size()];
    Vec3 p;
    for (int axis = 0; axis < 3; ++axis) p[axis] = uniform(rng, face.lo[axis], face.hi[axis]);
    p[face.fixed_axis] = face.value;
    points.push_back(p);
  }
  return points;
}

}  // namespace

SceneSampler roomScene(std::size_t points_per_scan) {
  return [points_per_scan](const Vec3&, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    const Vec3 lo(-6, -6, 0), hi(6, 6, 4);
    const std::vector<Face> faces = {{2, 0.0, lo, hi}, {2, 4.0, lo, hi},  {0, -6.0, lo, hi},
                                     {0, 6.0, lo, hi}, {1, -6.0, lo, hi}, {1, 6.0, lo, hi}};
    return sampleFaces(faces, points_per_scan, rng);
  };
}

SceneSampler corridorScene(std::size_t points_per_scan) {
  return [points_per_scan](const Vec3& position, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    // Only the stretch within 10 m is seen, so no scan sees an end wall.
    const Vec3 lo(position.x() - 10, -1.5, 0), hi(position.x() + 10, 1.5, 3);
    const std::vector<Face> faces = {{2, 0.0, lo, hi}, {2, 3.0, lo, hi}, {1, -1.5, lo, hi}, {1, 1.5, lo, hi}};
    return sampleFaces(faces, points_per_scan, rng);
  };
}

SceneSampler featurelessScene(std::size_t points_per_scan) {
  return [points_per_scan](const Vec3& position, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<Vec3> points;
    while (points.size() < points_per_scan) {
      const Vec3 p(uniform(rng, -8, 8), uniform(rng, -8, 8), uniform(rng, -8, 8));
      if (p.norm() <= 8.0) points.push_back(position + p);
    }
    return points;
  };
}

std::vector<Pose> straightPath(std::size_t count) {
  std::vector<Pose> poses;
  for (std::size_t i = 0; i < count; ++i) {
    const double yaw = 0.02 * static_cast<double>(i);
    poses.emplace_back(Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())),
                       Vec3(0.4 * static_cast<double>(i), 0.0, 1.5));
  }
  return poses;
}

std::vector<Pose> perturbed(const std::vector<Pose>& poses, double metres, double degrees,
                            std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Pose> out;
  for (const Pose& pose : poses) {
    const Vec3 shift(normal(rng), normal(rng), normal(rng));
    const Vec3 axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Quat turn(Eigen::AngleAxisd(degrees * kPi / 180.0 * normal(rng), axis));
    out.emplace_back((turn * pose.q).normalized(), pose.t + metres * shift);
  }
  return out;
}

void writeSceneDataset(const fs::path& dir, const SceneSampler& scene, const std::vector<Pose>& truth,
                       const std::vector<Pose>& initial) {
  fs::create_directories(dir / "pcd");
  std::mt19937_64 noise_rng(99);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Pose to_sensor = truth[i].inverse();
    PointCloud cloud;
    for (const Vec3& world : scene(truth[i].t, 1000 + i)) {
      const Vec3 p = to_sensor * world + Vec3(noise(noise_rng), noise(noise_rng), noise(noise_rng));
      cloud.add(p.cast<float>(), 1.0f);
    }
    io::writePcd(dir / "pcd" / (std::to_string(i) + ".pcd"), cloud);
  }
  writeHbaPoses(dir, initial);
}

void writeHbaPoses(const fs::path& dir, const std::vector<Pose>& poses) {
  Trajectory trajectory;
  trajectory.poses = poses;
  io::writePoses(dir / "pose.json", trajectory, io::PoseFormat::Hba);
}

}  // namespace hba::test
