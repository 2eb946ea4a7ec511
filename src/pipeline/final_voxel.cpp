#include "hba/pipeline/final_voxel.hpp"

#include <algorithm>
#include <unordered_map>
#include <vector>

#include "hba/core/error.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::pipeline {
namespace {

// Σ n² and Σ n over the cells of `scan` at `size`.
std::pair<double, double> cellSums(const PointCloud& scan, double size) {
  std::unordered_map<voxel::VoxelKey, std::size_t, voxel::VoxelKeyHash> counts;
  counts.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) ++counts[voxel::VoxelKey::of(scan.world(i), size)];
  double squares = 0.0, points = 0.0;
  for (const auto& [key, n] : counts) {
    squares += static_cast<double>(n) * static_cast<double>(n);
    points += static_cast<double>(n);
  }
  return {squares, points};
}

}  // namespace

double scanPointsPerVoxel(const PointCloud& scan, double size) {
  const auto [squares, points] = cellSums(scan, size);
  return points > 0.0 ? squares / points : 0.0;
}

double scanPointsWanted(const HbaSettings& settings) {
  if (settings.window < 1)
    throw Error("the final voxel needs the window size worked out (window 0 is automatic)");
  return settings.local.planes.min_points / 2.0 * kPaperWindow / settings.window;
}

FinalVoxel chooseFinalVoxel(const HbaSettings& settings,
                            const std::function<double(double)>& points_per_voxel) {
  FinalVoxel out;
  out.setting = out.chosen = settings.local.final_voxel_size;
  const double root = settings.local.planes.voxel_size;
  if (!settings.adapt_final_voxel || !(out.setting > 0.0) || out.setting >= root) return out;
  const double wanted = scanPointsWanted(settings);
  out.scan_points_at_setting = out.scan_points_at_chosen = points_per_voxel(out.setting);
  while (out.scan_points_at_chosen < wanted && out.chosen * 2.0 <= root) {
    out.chosen *= 2.0;
    out.scan_points_at_chosen = points_per_voxel(out.chosen);
  }
  out.coarsened = out.chosen > out.setting;
  return out;
}

FinalVoxel chooseFinalVoxel(const HbaSettings& settings, const std::vector<PointCloud>& sample) {
  return chooseFinalVoxel(settings, [&sample](double size) {
    double squares = 0.0, points = 0.0;
    for (const PointCloud& scan : sample) {
      const auto [s, p] = cellSums(scan, size);
      squares += s;
      points += p;
    }
    return points > 0.0 ? squares / points : 0.0;
  });
}

HbaSettings withFinalVoxel(HbaSettings settings, const FinalVoxel& voxel) {
  for (ba::BaSettings* ba : {&settings.local, &settings.global}) {
    if (ba->final_voxel_size > 0.0)
      ba->final_voxel_size = std::min(std::max(ba->final_voxel_size, voxel.chosen), ba->planes.voxel_size);
  }
  return settings;
}

}  // namespace hba::pipeline
