#include "group_refinement.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>

#include "consistency.hpp"
#include "core/progress.hpp"
#include "core/stopwatch.hpp"
#include "hba/ba/global_refinement.hpp"
#include "hba/core/error.hpp"
#include "hba/voxel/downsample.hpp"

namespace hba::refine {
namespace {

std::vector<GroupSpan> planGroups(std::size_t frames, std::size_t size) {
  std::vector<GroupSpan> groups;
  for (std::size_t first = 0; first < frames; first += size) {
    groups.push_back({first, std::min(frames, first + size)});
  }
  // A short last group would be held by few planes: it joins the one before.
  if (groups.size() > 1 && groups.back().end - groups.back().first < size / 2) {
    groups[groups.size() - 2].end = groups.back().end;
    groups.pop_back();
  }
  return groups;
}

// The group's scans in the frame of its first scan (with the relative
// poses of `poses`), merged and downsampled.
PointCloud mergeGroup(const io::ScanSource& scans, const std::vector<Pose>& poses, GroupSpan group,
                      double voxel) {
  const Pose to_group = poses[group.first].inverse();
  PointCloud merged;
  for (std::size_t i = group.first; i < group.end; ++i) {
    const PointCloud scan = scans.load(i);
    const Pose relative = to_group * poses[i];
    const Eigen::Matrix3f R = relative.R().cast<float>();
    const Vec3f t = relative.t.cast<float>();
    // No exact reserve per scan: that reallocates on every scan of a
    // 40-frame group; geometric growth copies each point about twice.
    for (const Vec3f& p : scan.points) merged.points.push_back(R * p + t);
  }
  // Overlapping scans at twice the refinement's voxel: about 8 points a cell.
  return voxel > 0.0 ? voxel::downsample(merged, voxel, 8) : merged;
}

}  // namespace

std::vector<Pose> spreadGroupMoves(const std::vector<GroupSpan>& groups, const std::vector<Pose>& moves,
                                   const std::vector<Pose>& current) {
  if (moves.size() != groups.size() || (!groups.empty() && groups.back().end > current.size())) {
    throw Error("group moves: " + std::to_string(moves.size()) + " moves for " +
                std::to_string(groups.size()) + " groups over " + std::to_string(current.size()) + " frames");
  }
  std::vector<Pose> out = current;
  if (groups.empty()) return out;
  auto centre = [&](std::size_t k) { return 0.5 * static_cast<double>(groups[k].first + groups[k].end - 1); };
  for (std::size_t k = 0; k < groups.size(); ++k) {
    for (std::size_t i = groups[k].first; i < groups[k].end; ++i) {
      const double at = static_cast<double>(i);
      // The centres either side of the frame: this group's and the nearer neighbour's.
      const bool before = at < centre(k);
      if ((before && k == 0) || (!before && k + 1 == groups.size()) || at == centre(k)) {
        out[i] = moves[k] * current[i];
        continue;
      }
      const std::size_t a = before ? k - 1 : k;
      const double s = (at - centre(a)) / (centre(a + 1) - centre(a));
      out[i] = interpolate(moves[a] * current[i], moves[a + 1] * current[i], s);
    }
  }
  return out;
}

std::size_t groupSize(std::size_t frames, std::size_t max_groups, std::size_t min_frames) {
  const std::size_t groups = std::max<std::size_t>(max_groups, 1);
  return std::max({min_frames, std::size_t{1}, (frames + groups - 1) / groups});
}

std::vector<Pose> refineGroups(const io::ScanSource& scans, const std::vector<Pose>& input,
                               const std::vector<Pose>& current, const RefineSettings& settings,
                               GroupRefinementReport& g, StageNotes& notes) {
  const auto start = Clock::now();
  const std::size_t size = groupSize(current.size(), settings.group_max_count, settings.group_min_frames);
  const std::vector<GroupSpan> groups = planGroups(current.size(), size);
  if (groups.size() < 3) return current;  // nothing a block would not see

  std::vector<PointCloud> clouds(groups.size());
  {
    Progress progress("merging groups", groups.size(), "groups");
    tbb::parallel_for(std::size_t{0}, groups.size(), [&](std::size_t k) {
      clouds[k] = mergeGroup(scans, current, groups[k], settings.group_voxel);
      progress.advance();
    });
  }
  std::vector<const PointCloud*> pointers;
  std::vector<Pose> start_poses;
  std::vector<Pose> reference;
  std::vector<double> path;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    pointers.push_back(&clouds[k]);
    g.points += clouds[k].size();
    start_poses.push_back(current[groups[k].first]);
    reference.push_back(input[groups[k].first]);
    if (k > 0) {
      double length = 0.0;
      for (std::size_t i = groups[k - 1].first; i < groups[k].first; ++i) {
        length += (input[i + 1].t - input[i].t).norm();
      }
      path.push_back(length);
    }
  }
  g.ran = true;
  g.groups = groups.size();
  g.frames_per_group = size;
  spdlog::info("refinement: {} frames tied into {} groups of {} ({} points at {} m)", current.size(),
               groups.size(), size, g.points, settings.group_voxel);

  ba::RefinementSettings rs = settings.ba;
  // Few unknowns, whose weak long-range modes are the point: exact steps.
  rs.lm.dense_max_frames = groups.size();
  // Every step that lowers the cost is taken: a weak long mode gains less
  // a step than fitting the noise would, and moving it is what the groups
  // are for (5000 simulated frames: 3.85 mm ATE with the blocks' step gate
  // here, 2.34 mm without).
  rs.step_gain = 0.0;
  // A dense solve is one process's: every member places the groups alike
  // (the same sums, whatever its thread count).
  rs.spread_over = nullptr;
  // The groups' own planes at their start poses judge the result; they are
  // the refinement's first association too, made once for both.
  ba::Association found = ba::refinementAssociation(pointers, start_poses, rs);
  const FixedPlaneMap fixed(found.problem, start_poses.size(), 1);
  const ba::RefinementResult refined =
      ba::refineGlobally(pointers, start_poses, rs, path, reference, ba::PositionPriors(), &found);
  notes.seconds_voxelize += refined.seconds_associate;
  notes.seconds_solve += refined.seconds_solve;
  if (refined.still_sliding > 0) {
    notes.warn(
        fmt::format("refinement: {} pairs of neighbouring groups still move apart beyond what odometry "
                    "plausibly gets wrong, though held",
                    refined.still_sliding));
  }

  g.planes = fixed.planes();
  g.rms_before = fixed.rms(start_poses);
  g.rms_after = fixed.rms(refined.poses);
  g.seconds = secondsSince(start);
  if (!(g.rms_after <= g.rms_before * kEqualMapMargin)) {
    g.rejected = true;
    notes.warn(
        fmt::format("refinement: placing the {} groups made their map blurrier (plane RMS {:.4f} -> {:.4f} "
                    "m): keeping the blocks' result",
                    groups.size(), g.rms_before, g.rms_after));
    return current;
  }
  std::vector<Pose> moves(groups.size());
  for (std::size_t k = 0; k < groups.size(); ++k) moves[k] = refined.poses[k] * start_poses[k].inverse();
  std::vector<Pose> out = spreadGroupMoves(groups, moves, current);
  for (std::size_t i = 0; i < out.size(); ++i)
    g.largest_move_m = std::max(g.largest_move_m, (out[i].t - current[i].t).norm());
  spdlog::info(
      "refinement: groups placed, plane RMS {:.4f} -> {:.4f} m on their {} planes, "
      "largest move {:.3f} m, {:.1f} s",
      g.rms_before, g.rms_after, g.planes, g.largest_move_m, g.seconds);
  return out;
}

}  // namespace hba::refine
