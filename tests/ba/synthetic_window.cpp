#include "synthetic_window.hpp"

#include <cmath>
#include <random>

#include "hba/core/lie.hpp"

namespace hba::test {
namespace {

struct Patch {
  Vec3 center;
  Vec3 normal;
};

// Patch normals cover all three axes and some oblique directions; centres
// are at grid cell centres so each patch fills one root voxel of that size.
std::vector<Patch> makePatches(double grid) {
  const std::vector<std::pair<Vec3, Vec3>> cells_and_normals = {
      {{0, 0, -1}, {0, 0, 1}},   {{1, 1, -1}, {0, 0.2, 1}}, {{2, 0, 0}, {1, 0, 0}},
      {{-2, 1, 0}, {1, 0.3, 0}}, {{0, 2, 0}, {0, 1, 0}},    {{1, -2, 0}, {0.2, 1, 0}},
      {{-1, -1, 1}, {1, 1, 1}},  {{1, 1, 1}, {-1, 1, 0.5}}, {{-1, 1, -1}, {0.3, -0.4, 1}},
  };
  std::vector<Patch> patches;
  for (const auto& [cell, normal] : cells_and_normals) {
    patches.push_back({(cell + Vec3::Constant(0.5)) * grid, normal.normalized()});
  }
  return patches;
}

Pose perturb(const Pose& pose, double angle_deg, double translation, std::mt19937& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Vec3 axis = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
  const Vec3 shift = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
  const double angle = angle_deg * M_PI / 180.0;
  return Pose(Mat3(so3Exp(angle * axis) * pose.R()), Vec3(pose.t + translation * shift));
}

}  // namespace

std::vector<const PointCloud*> SyntheticWindow::scanPointers() const {
  std::vector<const PointCloud*> out;
  for (const PointCloud& scan : scans) out.push_back(&scan);
  return out;
}

SyntheticWindow makeSyntheticWindow(const SyntheticWindowSpec& spec) {
  std::mt19937 rng(spec.seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  std::normal_distribution<double> noise(0.0, spec.noise_sigma > 0 ? spec.noise_sigma : 1.0);
  const std::vector<Patch> patches = makePatches(spec.grid);

  SyntheticWindow window;
  for (int f = 0; f < spec.frames; ++f) {
    // A short walk with some turning, as in consecutive scans.
    const Vec3 position(0.4 * f, 0.15 * f, 0.02 * f);
    const Vec3 rotation(0.01 * f, -0.005 * f, 0.05 * f);
    window.truth.emplace_back(so3Exp(rotation), position);
  }
  for (int f = 0; f < spec.frames; ++f) {
    const Pose to_sensor = window.truth[f].inverse();
    PointCloud scan;
    for (const Patch& patch : patches) {
      const Vec3 e1 = patch.normal.unitOrthogonal();
      const Vec3 e2 = patch.normal.cross(e1);
      for (int k = 0; k < spec.points_per_patch; ++k) {
        Vec3 q = patch.center + spec.patch_size * (unit(rng) * e1 + unit(rng) * e2);
        if (spec.noise_sigma > 0) q += noise(rng) * patch.normal;
        scan.add((to_sensor * q).cast<float>());
      }
    }
    window.scans.push_back(std::move(scan));
    window.initial.push_back(perturb(window.truth[f], spec.perturb_angle_deg, spec.perturb_translation, rng));
  }
  return window;
}

RelativeError relativePoseError(const std::vector<Pose>& estimate, const std::vector<Pose>& truth) {
  RelativeError error;
  for (std::size_t i = 1; i < estimate.size(); ++i) {
    const Pose diff = relative(relative(truth[0], truth[i]), relative(estimate[0], estimate[i]));
    error.max_angle_deg = std::max(error.max_angle_deg, so3Log(diff.q).norm() * 180.0 / M_PI);
    error.max_translation = std::max(error.max_translation, diff.t.norm());
  }
  return error;
}

ba::BaSettings patchBaSettings(const SyntheticWindowSpec& spec) {
  ba::BaSettings settings;
  settings.planes.voxel_size = spec.grid;
  settings.final_voxel_size = 0.0;
  settings.association_rounds = 3;
  return settings;
}

}  // namespace hba::test
