#include "map_change.hpp"

#include <cmath>
#include <unordered_map>

#include "core/symmetric_eigenvalues.hpp"
#include "hba/voxel/voxel_key.hpp"

namespace hba::render {
namespace {

constexpr double kMinPoints = 10.0;
constexpr std::size_t kMinVoxelsPerSquare = 5;
constexpr double kMinMeanThinning = 0.002;  // m: below it, nothing worth a zoom changed
constexpr double kPlanarRatio = 0.15;       // lambda_min / lambda_mid below this: a plane

}  // namespace

std::uint32_t CellMoments::add(const Vec3& world) {
  const voxel::VoxelKey key = voxel::VoxelKey::of(world, cell_);
  const Vec3 local =
      world -
      Vec3(static_cast<double>(key.x), static_cast<double>(key.y), static_cast<double>(key.z)) * cell_;
  std::uint32_t number = 0;
  Moments& m = at(key, &number);
  m.count += 1.0;
  m.sum += local;
  m.outer += local * local.transpose();
  return number;
}

CellMoments::Moments& CellMoments::at(const voxel::VoxelKey& key, std::uint32_t* number) {
  bool inserted = false;
  const std::uint32_t i = index_.insert(key, inserted);
  if (number) *number = i;
  if (inserted) {
    keys_.push_back(key);
    moments_.emplace_back();
  }
  return moments_[i];
}

void CellMoments::reserve(std::size_t cells) {
  index_.reserve(cells);
  keys_.reserve(cells);
  moments_.reserve(cells);
}

void CellMoments::merge(const CellMoments& other) {
  for (std::size_t i = 0; i < other.size(); ++i) {
    const Moments& theirs = other.moments(i);
    Moments& m = at(other.key(i));
    m.count += theirs.count;
    m.sum += theirs.sum;
    m.outer += theirs.outer;
  }
}

PlaneThickness::PlaneThickness(const PointCloud& map, double cell)
    : PlaneThickness([&] {
        CellMoments moments(cell);
        for (std::size_t i = 0; i < map.size(); ++i) moments.add(map.world(i));
        return moments;
      }()) {}

float planeThicknessOf(const CellMoments::Moments& m) {
  if (m.count < kMinPoints) return -1.0f;
  const Vec3 mean = m.sum / m.count;
  // In closed form: a map holds hundreds of thousands of cells.
  const Vec3 eigen = symmetricEigenvalues(m.outer / m.count - mean * mean.transpose());
  return eigen(0) < kPlanarRatio * eigen(1) ? static_cast<float>(std::sqrt(std::max(0.0, eigen(0)))) : -1.0f;
}

PlaneThickness::PlaneThickness(const CellMoments& moments) : cell_(moments.cell()) {
  for (std::size_t i = 0; i < moments.size(); ++i)
    voxels_.emplace(moments.key(i), planeThicknessOf(moments.moments(i)));
}

std::vector<float> PlaneThickness::perPoint(const PointCloud& map) const {
  std::vector<float> out(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    const auto it = voxels_.find(voxel::VoxelKey::of(map.world(i), cell_));
    out[i] = it == voxels_.end() ? -1.0f : it->second;
  }
  return out;
}

std::optional<Box2> mostThinnedRegion(const PlaneThickness& before, const PlaneThickness& after,
                                      double side) {
  const double cell = after.cell();
  const auto& was = before.voxels();
  const auto& is = after.voxels();
  // Sum of the thinning of the voxels that are planes in both maps, per square.
  std::unordered_map<voxel::VoxelKey, std::pair<double, std::size_t>, voxel::VoxelKeyHash> squares;
  for (const auto& [key, now] : is) {
    const auto then = was.find(key);
    if (now < 0.0f || then == was.end() || then->second < 0.0f) continue;
    const Vec3 centre = (Vec3(key.x, key.y, key.z) + Vec3::Constant(0.5)) * cell;
    voxel::VoxelKey square = voxel::VoxelKey::of(centre, side);
    square.z = 0;
    auto& [drop, voxels] = squares[square];
    drop += then->second - now;
    ++voxels;
  }
  std::optional<Box2> best;
  double best_drop = 0.0;
  for (const auto& [square, sum] : squares) {
    const auto [drop, voxels] = sum;
    if (voxels < kMinVoxelsPerSquare || drop < kMinMeanThinning * static_cast<double>(voxels)) continue;
    if (drop <= best_drop) continue;
    best_drop = drop;
    best = Box2{square.x * side, square.y * side, (square.x + 1) * side, (square.y + 1) * side};
  }
  return best;
}

}  // namespace hba::render
