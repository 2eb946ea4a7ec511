#include "refine_stage.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>

#include "consistency.hpp"
#include "group_refinement.hpp"
#include "hba/ba/global_refinement.hpp"
#include "hba/core/release_memory.hpp"
#include "hba/core/stopwatch.hpp"
#include "hba/voxel/downsample.hpp"
#include "keyframe_store.hpp"
#include "refinement_priors.hpp"
#include "spilled_scan_source.hpp"

namespace hba::pyramid {
namespace {

// Regions of the per-region self-check: about 100 frames each, 4 to 20.
std::size_t regionCount(std::size_t frames) { return std::clamp<std::size_t>(frames / 100, 4, 20); }

void warn(HbaReport& report, std::string message) {
  spdlog::warn("{}", message);
  report.warnings.push_back(std::move(message));
}

// Path (m) between consecutive poses.
std::vector<double> stepLengths(const std::vector<Pose>& poses) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < poses.size(); ++i) steps.push_back((poses[i].t - poses[i - 1].t).norm());
  return steps;
}

std::vector<Pose> slice(const std::vector<Pose>& poses, std::size_t first, std::size_t end) {
  return {poses.begin() + static_cast<long>(first), poses.begin() + static_cast<long>(end)};
}

// The scans of one block, at the refinement's density.
struct Block {
  std::size_t first = 0;
  std::size_t end = 0;
  std::vector<PointCloud> clouds;
  std::size_t points = 0;
};

// Loads frames from `first` on until `max_points` are held (at least two
// frames, unless the sequence ends), and never beyond `last_end`.
Block loadBlock(const io::ScanSource& scans, std::size_t first, std::size_t max_points, double voxel,
                std::size_t last_end = SIZE_MAX) {
  Block block;
  block.first = first;
  block.end = first;
  const std::size_t batch = 64;
  const std::size_t stop = std::min(scans.size(), last_end);
  while (block.end < stop && (block.points < max_points || block.end - first < 2)) {
    const std::size_t end = std::min(stop, block.end + batch);
    std::vector<PointCloud> loaded(end - block.end);
    tbb::parallel_for(block.end, end, [&](std::size_t i) {
      PointCloud& cloud = loaded[i - block.end];
      // Scans at the scan voxel taken to twice it: about 2 points a cell.
      cloud = voxel > 0.0 ? voxel::downsample(scans.load(i), voxel, 2) : scans.load(i);
      cloud.intensity = {};  // planes need positions only
    });
    for (PointCloud& cloud : loaded) {
      if (block.points >= max_points && block.end - first >= 2) break;
      block.points += cloud.size();
      block.clouds.push_back(std::move(cloud));
      ++block.end;
    }
  }
  return block;
}

// Running sums of squared plane distances and points over blocks.
struct RmsSum {
  double squares = 0.0;
  double points = 0.0;
  void add(double rms, double n) {
    squares += rms * rms * n;
    points += n;
  }
  double rms() const { return points > 0.0 ? std::sqrt(squares / points) : 0.0; }
};

// Frames [first, end) of one block.
struct FrameSpan {
  std::size_t first = 0;
  std::size_t end = 0;
};

// The self-check's figures for one stretch of frames.
struct RegionFigures {
  std::size_t first_frame = 0;
  double input_rms = 0.0;
  double final_rms = 0.0;
};

void addRegions(const FixedPlaneMap& fixed, const std::vector<double>& region_input,
                const std::vector<double>& region_final, std::size_t first, std::vector<RegionFigures>& out) {
  for (std::size_t k = 0; k < fixed.regions(); ++k) {
    out.push_back({first + fixed.regionStarts()[k], region_input[k], region_final[k]});
  }
}

// A block's input poses, moved rigidly onto `result` at its first frame.
std::vector<Pose> inputOnto(const std::vector<Pose>& initial, const std::vector<Pose>& result,
                            std::size_t first, std::size_t end) {
  const Pose onto = result[first] * initial[first].inverse();
  std::vector<Pose> input = slice(initial, first, end);
  for (Pose& pose : input) pose = onto * pose;
  return input;
}

// Each block's fixed map, kept on disk for the re-measured self-check (44
// bytes a plane cluster, hundreds of MB on long sequences), so that the groups'
// result is measured without reading and voxelizing every block again, and
// without holding the maps in memory while later blocks are refined. The
// folder (a KeyframeStore of no keyframes: a private temporary folder,
// removed at the end and on Ctrl-C) is made with the first map.
struct BlockMaps {
  std::unique_ptr<KeyframeStore> folder;
  std::vector<std::filesystem::path> files;  // per block
  void keep(const FixedPlaneMap& map) {
    if (!folder) folder = std::make_unique<KeyframeStore>(0);
    files.push_back(folder->folder() / ("map-" + std::to_string(files.size()) + ".bin"));
    map.save(files.back());
  }
};

// The final poses measured again on each block's fixed map (the groups
// moved them after the blocks were checked): figures only.
double remeasure(const std::vector<Pose>& initial, const std::vector<Pose>& result,
                 const std::vector<FrameSpan>& spans, const BlockMaps& kept,
                 std::vector<RegionFigures>& regions) {
  RmsSum final_sum;
  regions.clear();
  for (std::size_t b = 0; b < spans.size(); ++b) {
    const FrameSpan& span = spans[b];
    const std::vector<Pose> input = inputOnto(initial, result, span.first, span.end);
    const std::vector<Pose> poses = slice(result, span.first, span.end);
    const FixedPlaneMap fixed = FixedPlaneMap::load(kept.files[b]);
    const FixedPlaneMap::Figures at_final = fixed.figures(poses);
    final_sum.add(at_final.rms, fixed.points());
    addRegions(fixed, fixed.regionRms(input), at_final.region_rms, span.first, regions);
  }
  return final_sum.rms();
}

}  // namespace

std::vector<Pose> refineAndCheck(const io::ScanSource& scans, const std::vector<Pose>& initial,
                                 const std::vector<Pose>& hierarchy, const HbaSettings& settings,
                                 HbaReport& report, const std::vector<graph::PositionPriorFactor>& priors,
                                 bool scans_kept) {
  const auto start = Clock::now();
  const ba::RefinementSettings rs = settings.refinementBa();
  const std::vector<double> steps = stepLengths(initial);
  ConsistencyReport& c = report.consistency;
  RefinementReport& r = report.refinement;
  RmsSum input_sum, hierarchy_sum, final_sum, refine_before, refine_after;

  std::vector<Pose> result = hierarchy;
  std::vector<RegionFigures> regions;
  std::vector<FrameSpan> spans;  // of each block
  std::size_t first = 0;
  std::size_t blocks = 0;
  // A sequence longer than one block is read again: the blocks overlap, and
  // the groups read every scan once more. There each scan is parsed and
  // downsampled once and then kept on disk; a sequence of one block reads
  // its scans once here.
  // Layer 1 counted the scans' points at a finer voxel: more than a block
  // there means a second block, so scans are kept from the first on (else
  // from the second block, should one follow after all).
  std::unique_ptr<SpilledScanSource> spilled;
  const io::ScanSource* source = &scans;
  const bool several_blocks =
      !report.layer_reports.empty() && report.layer_reports.front().cloud_points > settings.refine_max_points;
  if (several_blocks && settings.refine && report.layers > 1 && !scans_kept) {
    spilled = std::make_unique<SpilledScanSource>(scans);
    source = spilled.get();
  }
  BlockMaps kept_maps;  // for the groups' re-measure, when they run
  const bool groups_follow = settings.refine && settings.refine_groups && report.layers > 1;
  while (first + 1 < initial.size() || blocks == 0) {
    releaseFreedMemory();  // what the hierarchy or the block before left
    const Block block = loadBlock(*source, first, settings.refine_max_points, settings.refine_scan_voxel);
    ++blocks;
    spans.push_back({block.first, block.end});
    r.scan_points += block.points;
    std::vector<const PointCloud*> pointers;
    for (const PointCloud& cloud : block.clouds) pointers.push_back(&cloud);
    // The input of this block, moved rigidly onto the result at its first
    // frame (the whole input when the block is the sequence).
    const std::vector<Pose> input = inputOnto(initial, result, block.first, block.end);
    const std::vector<Pose> current = slice(result, block.first, block.end);

    const FixedPlaneMap fixed(pointers, input, rs.planes, rs.reject_ratio, regionCount(input.size()));
    // The plane problem the map was made from (hundreds of MB in small
    // pieces): returned, so that the refinement's association does not
    // stack its peak on it (1000 frames: 1295 -> 1211 MiB with the release
    // in ba::associate).
    releaseFreedMemory();
    const FixedPlaneMap::Figures at_input = fixed.figures(input);
    const double input_rms = at_input.rms;
    const double current_rms = fixed.rms(current);
    c.planes += fixed.planes();
    input_sum.add(input_rms, fixed.points());
    hierarchy_sum.add(current_rms, fixed.points());
    std::vector<Pose> poses = current;
    const bool refines_block = settings.refine && report.layers > 1;
    // A margin of 0.5 %: equal maps differ by rounding and plane edges.
    if (!(current_rms <= input_rms * 1.005)) {  // NaN counts as worse
      c.hierarchy_rejected = true;
      poses = input;
      // Said as it is: without the refinement the hierarchy's work is
      // simply lost here (--no-refine returns the input, loops closed).
      warn(report, fmt::format("frames {}-{}: the hierarchy made the map less consistent than the "
                               "input (plane RMS {:.4f} -> {:.4f} m on the input's planes): {}",
                               block.first, block.end - 1, input_rms, current_rms,
                               refines_block ? "refining from the input"
                                             : "keeping the input poses (with the closure stage's loops), "
                                               "unrefined"));
    }
    if (refines_block) {  // one layer is one global BA already
      const std::vector<double> block_steps(steps.begin() + static_cast<long>(block.first),
                                            steps.begin() + static_cast<long>(block.end - 1));
      const ba::PositionPriors positions =
          blockPriors(priors, block.first, block.end, rs.motion_prior.point_sigma);
      ba::RefinementSettings block_rs = rs;
      // Later blocks stay held at their first frame, which the block before
      // placed: no seam where they overlap.
      block_rs.lm.hold_first = blocks > 1 || !positions.defineTheFrame(kPriorSpreadForGauge);
      r.position_priors += positions.terms().size();
      if (!positions.empty()) {
        spdlog::info("refinement: frames {}-{} held by {} position priors, first frame {}", block.first,
                     block.end - 1, positions.terms().size(), block_rs.lm.hold_first ? "held" : "free");
      }
      const ba::RefinementResult refined =
          ba::refineGlobally(pointers, poses, block_rs, block_steps, input, positions);
      r.ran = true;
      r.planes += refined.planes;
      r.observations += refined.observations;
      r.plane_points += refined.plane_points;
      refine_before.add(refined.rms_before, static_cast<double>(refined.plane_points));
      refine_after.add(refined.rms_after, static_cast<double>(refined.plane_points));
      r.iterations += refined.iterations;
      r.cg_products += refined.cg_products;
      r.rounds += refined.rounds;
      r.held_pairs += refined.held_pairs;
      if (refined.still_sliding > 0) {
        r.still_sliding += refined.still_sliding;
        warn(report, fmt::format("frames {}-{}: {} pairs of neighbouring frames still move apart "
                                 "beyond what odometry plausibly gets wrong, though held",
                                 block.first, block.end - 1, refined.still_sliding));
      }
      report.seconds_voxelize += refined.seconds_associate;
      report.seconds_solve += refined.seconds_solve;
      poses = refined.poses;
    }
    FixedPlaneMap::Figures at_final = fixed.figures(poses);
    double final_rms = at_final.rms;
    if (!(final_rms <= input_rms * 1.005)) {
      c.final_rejected = true;
      warn(report, fmt::format("frames {}-{}: the result is less consistent than the input (plane "
                               "RMS {:.4f} -> {:.4f} m on the input's planes): keeping the input "
                               "poses there",
                               block.first, block.end - 1, input_rms, final_rms));
      poses = input;
      final_rms = input_rms;
      at_final = at_input;
    }
    final_sum.add(final_rms, fixed.points());
    addRegions(fixed, at_input.region_rms, at_final.region_rms, block.first, regions);
    std::copy(poses.begin(), poses.end(), result.begin() + static_cast<long>(block.first));
    if (groups_follow && !(block.end >= initial.size() && blocks == 1)) kept_maps.keep(fixed);
    if (block.end >= initial.size()) break;
    if (!spilled && !scans_kept) {
      spilled = std::make_unique<SpilledScanSource>(scans);
      source = spilled.get();
    }
    // The next block overlaps this one by a quarter, so that no frame is
    // refined only at a block's edge.
    first = std::max(block.first + 1, block.end - (block.end - block.first) / 4);
  }
  c.final_rms = final_sum.rms();
  if (blocks > 1 && groups_follow) {
    // Blocks of consecutive frames cannot see planes shared by passes far
    // apart in time, nor bends longer than a block: rigid groups of the
    // blocks' frames are placed as a whole, and the checks measured again.
    std::vector<Pose> grouped = refineGroups(*source, initial, result, settings, report);
    GroupRefinementReport& g = r.groups;
    if (g.ran && !g.rejected) {
      std::vector<RegionFigures> grouped_regions;
      const double grouped_rms = remeasure(initial, grouped, spans, kept_maps, grouped_regions);
      // The output is never less consistent than the input (as for each block).
      if (grouped_rms <= input_sum.rms() * 1.005) {
        result = std::move(grouped);
        c.final_rms = grouped_rms;
        regions = std::move(grouped_regions);
      } else {
        g.rejected = true;
        warn(report, fmt::format("refinement: the groups' placement made the map less consistent "
                                 "than the input (plane RMS {:.4f} -> {:.4f} m on the input's "
                                 "planes): keeping the blocks' result",
                                 input_sum.rms(), grouped_rms));
      }
    }
  }
  for (const RegionFigures& region : regions) {
    c.region_first_frame.push_back(region.first_frame);
    c.region_input_rms.push_back(region.input_rms);
    c.region_final_rms.push_back(region.final_rms);
    // The input's own planes favour the input a little where a loop
    // closure pulls frames towards earlier scans (the region's RMS rises a
    // little while the map's entropy drops): warn only beyond that.
    if (region.final_rms > region.input_rms * 1.10) {
      warn(report, fmt::format("frames from {}: less consistent than the input (plane RMS "
                               "{:.4f} -> {:.4f} m)",
                               region.first_frame, region.input_rms, region.final_rms));
    }
  }
  c.input_rms = input_sum.rms();
  c.hierarchy_rms = hierarchy_sum.rms();
  r.rms_before = refine_before.rms();
  r.rms_after = refine_after.rms();
  r.blocks = blocks;
  r.seconds = secondsSince(start);
  if (r.ran) {
    spdlog::info(
        "refinement: {} frames ({} points) in {} block(s), {} planes, {} observations, plane RMS "
        "{:.4f} -> {:.4f} m (first association), {} associations, {} LM iterations",
        initial.size(), r.scan_points, blocks, r.planes, r.observations, r.rms_before, r.rms_after, r.rounds,
        r.iterations);
    if (r.held_pairs > 0) {
      spdlog::info(
          "refinement: {} pairs of neighbouring frames slid beyond the motion prior and "
          "were held near the input's relative poses",
          r.held_pairs);
    }
  }
  spdlog::info(
      "map consistency (plane RMS on the input's {} planes): input {:.4f} m, hierarchy "
      "{:.4f} m, final {:.4f} m",
      c.planes, c.input_rms, c.hierarchy_rms, c.final_rms);
  return result;
}

}  // namespace hba::pyramid
