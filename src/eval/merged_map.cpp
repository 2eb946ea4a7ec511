#include "hba/eval/merged_map.hpp"

#include <cmath>
#include <utility>

#include "core/progress.hpp"
#include "hba/core/error.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::eval {

VoxelMerger::VoxelMerger(const MapSettings& settings, const Vec3& origin)
    : settings_(settings), origin_(origin) {}

void VoxelMerger::add(const PointCloud& scan, const Pose& pose, std::uint32_t scan_index) {
  if (!scan.hasIntensity()) has_intensity_ = false;
  const Mat3 R = pose.R();
  const Vec3 t = pose * scan.origin;
  const bool keep_all = !(settings_.voxel > 0.0);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Vec3 world = R * scan.points[i].cast<double>() + t;
    std::uint32_t slot = 0;
    if (keep_all) {
      slot = static_cast<std::uint32_t>(cells_.size());
      cells_.emplace_back();
    } else {
      bool inserted = false;
      slot = index_.insert(voxel::VoxelKey::of(world, settings_.voxel), inserted);
      if (inserted) cells_.emplace_back();
    }
    Cell& cell = cells_[slot];
    const Vec3 local = world - origin_;
    if (cell.count == 0) {
      cell.first = local.cast<float>();
      cell.first_scan = scan_index;
    }
    cell.sum += local;
    if (scan.hasIntensity()) cell.intensity_sum += scan.intensity[i];
    ++cell.count;
  }
}

PointCloud VoxelMerger::result() const {
  PointCloud out;
  const bool with_intensity = settings_.color != MapColor::None || has_intensity_;
  out.reserve(cells_.size(), with_intensity);
  out.origin = origin_;
  for (const Cell& cell : cells_) {
    const Vec3f p = settings_.rule == VoxelRule::Centroid
                        ? Vec3f((cell.sum / static_cast<double>(cell.count)).cast<float>())
                        : cell.first;
    if (!with_intensity) {
      out.add(p);
      continue;
    }
    float value = 0.0f;
    switch (settings_.color) {
      case MapColor::None:
        value = static_cast<float>(cell.intensity_sum / cell.count);
        break;
      case MapColor::Scan:
        value = static_cast<float>(cell.first_scan);
        break;
      case MapColor::Height:
        value = static_cast<float>(origin_.z() + p.z());
        break;
    }
    out.add(p, value);
  }
  return out;
}

std::vector<std::uint32_t> VoxelMerger::firstScans() const {
  std::vector<std::uint32_t> scans;
  scans.reserve(cells_.size());
  for (const Cell& cell : cells_) scans.push_back(cell.first_scan);
  return scans;
}

PointCloud buildMergedMap(const io::ScanSource& scans, const std::vector<Pose>& poses,
                          const MapSettings& settings, std::vector<std::uint32_t>* first_scans) {
  if (poses.size() != scans.size()) {
    throw Error("there are " + std::to_string(scans.size()) + " scans but " + std::to_string(poses.size()) +
                " poses were given");
  }
  // Relative to where the first scan lies when that is far out (UTM: its
  // pose, or the origin of world points given with identity poses): float
  // coordinates would lose centimetres there, and the writers then store float64.
  PointCloud first = scans.size() > 0 ? scans.load(0) : PointCloud{};
  const Vec3 first_place = poses.empty() ? Vec3::Zero() : Vec3(poses.front() * first.origin);
  const bool far = first_place.cwiseAbs().maxCoeff() > 1e4;
  VoxelMerger merger(settings, far ? first_place : Vec3::Zero());
  Progress progress("merging the map", scans.size(), "scans");
  for (std::size_t i = 0; i < scans.size(); ++i) {
    merger.add(i == 0 ? std::move(first) : scans.load(i), poses[i], static_cast<std::uint32_t>(i));
    // The output cloud is still to come: a point and an intensity a voxel.
    if (settings.budget.exceeded(merger.voxelCount() * (sizeof(Vec3f) + sizeof(float)))) {
      throw settings.budget.exceededBy("the merged map (" + std::to_string(merger.voxelCount()) +
                                       " points after " + std::to_string(i + 1) + " of " +
                                       std::to_string(scans.size()) + " scans)");
    }
    progress.advance();
  }
  if (first_scans) *first_scans = merger.firstScans();
  return merger.result();
}

PointCloud downsampleMap(const PointCloud& cloud, const MapSettings& settings) {
  VoxelMerger merger(settings, cloud.origin);
  merger.add(cloud, Pose::identity(), 0);
  return merger.result();
}

}  // namespace hba::eval
