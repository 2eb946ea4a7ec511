#include "birds_eye_search.hpp"

#include "occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

namespace hba::closure {
namespace {

constexpr double kDegree = M_PI / 180.0;
// Range at which one heading step moves a point by one cell: most structure
// a scan neighbourhood sees is nearer than this.
constexpr double kHeadingLeverM = 20.0;

// A planar correction of the guess: heading about the guess's position, then a shift.
struct Offset {
  double dx = 0.0;
  double dy = 0.0;
  double yaw = 0.0;  // rad
};

struct Scored {
  Offset offset;
  double score = 0.0;
};

// Values centre + k * step covering [centre - half, centre + half], always centre itself.
std::vector<double> steps(double centre, double half, double step) {
  std::vector<double> values;
  if (!(half > 0.0) || !(step > 0.0)) return {centre};
  const long n = static_cast<long>(std::ceil(half / step - 1e-9));
  for (long k = -n; k <= n; ++k) values.push_back(centre + static_cast<double>(k) * step);
  return values;
}

// Every offset of the level, scored.
std::vector<Scored> scoreLevel(const OccupancyGrid& grid, const std::vector<Vec2>& queries, const Vec2& pivot,
                               const std::vector<double>& xs, const std::vector<double>& ys,
                               const std::vector<double>& yaws) {
  std::vector<Scored> scored;
  std::vector<Vec2> turned(queries.size());
  for (const double yaw : yaws) {
    const Eigen::Rotation2Dd rotation(yaw);
    for (std::size_t k = 0; k < queries.size(); ++k) turned[k] = rotation * (queries[k] - pivot) + pivot;
    const std::vector<std::uint32_t> hits = countHits(grid, turned, xs, ys);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      for (std::size_t j = 0; j < ys.size(); ++j) {
        const double share =
            queries.empty() ? 0.0 : static_cast<double>(hits[i * ys.size() + j]) / queries.size();
        scored.push_back({{xs[i], ys[j], yaw}, share});
      }
    }
  }
  return scored;
}

// The first best (a fixed order, so ties are deterministic).
std::size_t bestOf(const std::vector<Scored>& scored) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < scored.size(); ++k) {
    if (scored[k].score > scored[best].score) best = k;
  }
  return best;
}

std::vector<Vec2> queryPoints(const std::vector<ColumnStats>& columns, const Pose& guess) {
  std::vector<Vec2> queries;
  queries.reserve(columns.size());
  for (const ColumnStats& c : columns) {
    const Vec3 p = guess * (c.sum / static_cast<double>(c.count));
    queries.emplace_back(p.x(), p.y());
  }
  return queries;
}

Pose corrected(const Pose& guess, const Offset& offset) {
  const Mat3 Rz = Eigen::AngleAxisd(offset.yaw, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 pivot = guess.t;
  const Pose correction(Rz, pivot + Vec3(offset.dx, offset.dy, 0.0) - Rz * pivot);
  return correction * guess;
}

bool farApart(const Offset& a, const Offset& b, const BirdsEyeSearchSettings& settings) {
  return std::hypot(a.dx - b.dx, a.dy - b.dy) > settings.ambiguous_distance_m ||
         std::abs(a.yaw - b.yaw) > settings.ambiguous_yaw_deg * kDegree;
}

// The best offsets that lie far apart from each other, best first, at most `count`.
std::vector<Offset> peaks(std::vector<Scored> scored, std::size_t count,
                          const BirdsEyeSearchSettings& settings) {
  std::stable_sort(scored.begin(), scored.end(),
                   [](const Scored& a, const Scored& b) { return a.score > b.score; });
  std::vector<Offset> found;
  for (const Scored& s : scored) {
    if (found.size() == count) break;
    bool far = true;
    for (const Offset& f : found) far = far && farApart(s.offset, f, settings);
    if (far) found.push_back(s.offset);
  }
  return found;
}

// A coarse level over many offsets, scored only where a level four times
// coarser peaks: the same best wherever that level's peaks hold it, at a
// fraction of the cost (a session's frame may be a full turn off).
std::vector<Scored> scoreAroundPeaks(const PointCloud& from_map, const PointCloud& to_map, const Pose& guess,
                                     const OccupancyGrid& grid, const std::vector<Vec2>& queries,
                                     const Vec2& pivot, const BirdsEyeSearchSettings& settings) {
  const double cell = settings.cell_m;
  const double rough_cell = 4.0 * cell;
  const double rough_yaw_step = std::atan(rough_cell / kHeadingLeverM);
  const double yaw_step = std::atan(cell / kHeadingLeverM);
  const auto to_rough = structureColumns(to_map, rough_cell, settings.structure_height_m);
  const OccupancyGrid rough_grid(structureColumns(from_map, rough_cell, settings.structure_height_m),
                                 rough_cell, 1);
  const std::vector<Scored> rough = scoreLevel(
      rough_grid, queryPoints(to_rough, guess), pivot, steps(0.0, settings.radius_m, rough_cell),
      steps(0.0, settings.radius_m, rough_cell), steps(0.0, settings.yaw_deg * kDegree, rough_yaw_step));
  std::vector<Scored> scored;
  for (const Offset& peak : peaks(rough, 8, settings)) {
    const std::vector<Scored> near = scoreLevel(
        grid, queries, pivot, steps(peak.dx, rough_cell, cell), steps(peak.dy, rough_cell, cell),
        settings.yaw_deg > 0.0 ? steps(peak.yaw, rough_yaw_step, yaw_step) : std::vector<double>{0.0});
    scored.insert(scored.end(), near.begin(), near.end());
  }
  return scored;
}

// Above this many offsets the coarse level is scored around a rougher
// level's peaks only.
constexpr std::size_t kFullSearchOffsets = 40000;

}  // namespace

BirdsEyeMatch searchBirdsEye(const PointCloud& from_map, const PointCloud& to_map, const Pose& guess,
                             const BirdsEyeSearchSettings& settings) {
  BirdsEyeMatch match;
  match.relative = guess;
  const Vec2 pivot = guess.t.head<2>();

  // Coarse: the whole range, on a grid dilated by a cell (the true offset
  // lies up to half a step from the nearest one tried).
  const double coarse_cell = settings.cell_m;
  const double coarse_yaw_step = std::atan(coarse_cell / kHeadingLeverM);
  const auto to_coarse = structureColumns(to_map, coarse_cell, settings.structure_height_m);
  match.structure_cells = to_coarse.size();
  if (to_coarse.empty()) return match;
  const OccupancyGrid coarse_grid(structureColumns(from_map, coarse_cell, settings.structure_height_m),
                                  coarse_cell, 1);
  const std::vector<double> coarse_xs = steps(0.0, settings.radius_m, coarse_cell);
  const std::vector<double> coarse_yaws = steps(0.0, settings.yaw_deg * kDegree, coarse_yaw_step);
  const std::vector<Vec2> coarse_queries = queryPoints(to_coarse, guess);
  const std::vector<Scored> coarse =
      coarse_xs.size() * coarse_xs.size() * coarse_yaws.size() > kFullSearchOffsets
          ? scoreAroundPeaks(from_map, to_map, guess, coarse_grid, coarse_queries, pivot, settings)
          : scoreLevel(coarse_grid, coarse_queries, pivot, coarse_xs, coarse_xs, coarse_yaws);
  const Scored best = coarse[bestOf(coarse)];
  match.score = best.score;
  for (const Scored& s : coarse) {
    if (farApart(s.offset, best.offset, settings)) match.second_score = std::max(match.second_score, s.score);
  }

  // Fine: half the cell, around the coarse best, undilated.
  const double fine_cell = 0.5 * coarse_cell;
  const auto to_fine = structureColumns(to_map, fine_cell, settings.structure_height_m);
  const OccupancyGrid fine_grid(structureColumns(from_map, fine_cell, settings.structure_height_m), fine_cell,
                                0);
  const std::vector<double> yaws = settings.yaw_deg > 0.0
                                       ? steps(best.offset.yaw, coarse_yaw_step, 0.25 * coarse_yaw_step)
                                       : std::vector<double>{0.0};
  const std::vector<double> xs = settings.radius_m > 0.0
                                     ? steps(best.offset.dx, coarse_cell, 0.25 * coarse_cell)
                                     : std::vector<double>{0.0};
  const std::vector<double> ys = settings.radius_m > 0.0
                                     ? steps(best.offset.dy, coarse_cell, 0.25 * coarse_cell)
                                     : std::vector<double>{0.0};
  const std::vector<Scored> fine = scoreLevel(fine_grid, queryPoints(to_fine, guess), pivot, xs, ys, yaws);
  match.relative = corrected(guess, fine[bestOf(fine)].offset);
  return match;
}

}  // namespace hba::closure
