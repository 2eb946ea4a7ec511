#include "refinement.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <utility>

#include "block.hpp"
#include "block_maps.hpp"
#include "core/release_memory.hpp"
#include "core/stopwatch.hpp"
#include "group_refinement.hpp"
#include "io/spilled_scan_source.hpp"

namespace hba::refine {
namespace {

// A region this much blurrier than the input is warned of: the input's own
// planes favour the input a little where a loop closure pulls frames
// towards earlier scans (the region's RMS rises a little while the map's
// entropy drops).
constexpr double kRegionWarnRatio = 1.10;

// Path (m) between consecutive poses.
std::vector<double> stepLengths(const std::vector<Pose>& poses) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < poses.size(); ++i) steps.push_back((poses[i].t - poses[i - 1].t).norm());
  return steps;
}

// The blocks' outcomes summed, in block order.
struct BlockSums {
  RmsSum input, hierarchy, final, refine_before, refine_after;
  std::vector<RegionFigures> regions;
  std::vector<FrameSpan> spans;

  void add(const Block& block, const BlockOutcome& b, RefineOutcome& out) {
    spans.push_back({block.first, block.end});
    ConsistencyReport& c = out.consistency;
    RefinementReport& r = out.refinement;
    r.scan_points += block.points;
    c.planes += b.map.planes();
    input.add(b.input_rms, b.map.points());
    hierarchy.add(b.hierarchy_rms, b.map.points());
    final.add(b.final_rms, b.map.points());
    c.hierarchy_rejected = c.hierarchy_rejected || b.hierarchy_rejected;
    c.hierarchy_insignificant = c.hierarchy_insignificant || b.hierarchy_insignificant;
    c.final_rejected = c.final_rejected || b.final_rejected;
    addRegions(b.map, b.region_input_rms, b.region_final_rms, block.first, regions);
    r.position_priors += b.position_priors;
    out.notes.add(b.notes);
    if (!b.refined) return;
    const ba::RefinementResult& refined = b.refinement;
    r.converged = (!r.ran || r.converged) && refined.converged;
    r.converged_at_start = (!r.ran || r.converged_at_start) && refined.converged_at_start;
    r.gain_over_noise = std::max(r.gain_over_noise, refined.last_gain_over_noise);
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
    r.still_sliding += refined.still_sliding;
  }
};

// Blocks of consecutive frames cannot see planes shared by passes far apart
// in time, nor bends longer than a block: rigid groups of the blocks'
// frames are placed as a whole, and the self-check measured again. The
// output is never less consistent than the input (as for each block).
void placeGroups(const io::ScanSource& scans, const std::vector<Pose>& initial, const BlockMaps& kept_maps,
                 const RefineSettings& settings, BlockSums& sums, RefineOutcome& out) {
  GroupRefinementReport& g = out.refinement.groups;
  std::vector<Pose> grouped = refineGroups(scans, initial, out.poses, settings, g, out.notes);
  if (!g.ran || g.rejected) return;
  std::vector<RegionFigures> grouped_regions;
  const double grouped_rms = remeasure(initial, grouped, sums.spans, kept_maps, grouped_regions);
  if (grouped_rms <= sums.input.rms() * kEqualMapMargin) {
    out.poses = std::move(grouped);
    out.consistency.final_rms = grouped_rms;
    sums.regions = std::move(grouped_regions);
  } else {
    g.rejected = true;
    out.notes.warn(
        fmt::format("refinement: the groups' placement made the map less consistent "
                    "than the input (plane RMS {:.4f} -> {:.4f} m on the input's "
                    "planes): keeping the blocks' result",
                    sums.input.rms(), grouped_rms));
  }
}

void reportRegions(const std::vector<RegionFigures>& regions, RefineOutcome& out) {
  ConsistencyReport& c = out.consistency;
  for (const RegionFigures& region : regions) {
    c.region_first_frame.push_back(region.first_frame);
    c.region_input_rms.push_back(region.input_rms);
    c.region_final_rms.push_back(region.final_rms);
    if (region.final_rms > region.input_rms * kRegionWarnRatio) {
      out.notes.warn(
          fmt::format("frames from {}: less consistent than the input (plane RMS "
                      "{:.4f} -> {:.4f} m)",
                      region.first_frame, region.input_rms, region.final_rms));
    }
  }
}

void logSummary(const RefineOutcome& out, std::size_t frames) {
  const RefinementReport& r = out.refinement;
  const ConsistencyReport& c = out.consistency;
  if (r.ran) {
    spdlog::info(
        "refinement: {} frames ({} points) in {} block(s), {} planes, {} observations, plane RMS "
        "{:.4f} -> {:.4f} m (first association), {} associations, {} LM iterations",
        frames, r.scan_points, r.blocks, r.planes, r.observations, r.rms_before, r.rms_after, r.rounds,
        r.iterations);
    if (r.converged_at_start) {
      spdlog::info(
          "refinement: converged at its start (the first association gained {:.2f} times what fitting "
          "the points' noise would): its start kept",
          r.gain_over_noise);
    } else if (r.converged) {
      spdlog::info(
          "refinement: converged (the last association gained {:.2f} times what fitting the points' "
          "noise would, and was not taken)",
          r.gain_over_noise);
    }
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
}

// The hierarchy was more than one global BA: the blocks refine it.
bool refinesAfter(const HierarchyFacts& facts, const RefineSettings& settings) {
  return settings.refine && facts.layers > 1;
}

// A sequence longer than one block is read again: the blocks overlap, and
// the groups read every scan once more. There each scan is parsed and
// downsampled once and then kept on disk. Layer 1 counted the scans'
// points at a finer voxel: more than a block there means a second block,
// so scans are kept from the first on (else from the second block,
// should one follow after all).
std::unique_ptr<io::SpilledScanSource> keptFromTheStart(const io::ScanSource& scans,
                                                        const HierarchyFacts& facts,
                                                        const RefineSettings& settings) {
  if (refinesAfter(facts, settings) && facts.layer_one_points > settings.max_points && !facts.scans_kept)
    return std::make_unique<io::SpilledScanSource>(scans);
  return nullptr;
}

}  // namespace

struct PreparedStart::Parts {
  std::unique_ptr<io::SpilledScanSource> spilled;  // what the blocks read through, when set
  Block block;
  InputPlanes planes;
};

PreparedStart::PreparedStart() = default;
PreparedStart::PreparedStart(PreparedStart&&) noexcept = default;
PreparedStart& PreparedStart::operator=(PreparedStart&&) noexcept = default;
PreparedStart::~PreparedStart() = default;

PreparedStart prepareStart(const io::ScanSource& scans, const std::vector<Pose>& initial,
                           const HierarchyFacts& facts, const RefineSettings& settings) {
  PreparedStart prepared;
  prepared.parts = std::make_unique<PreparedStart::Parts>();
  PreparedStart::Parts& p = *prepared.parts;
  p.spilled = keptFromTheStart(scans, facts, settings);
  p.block = loadBlock(p.spilled ? *p.spilled : scans, 0, settings.max_points, settings.scan_voxel);
  std::vector<const PointCloud*> pointers;
  for (const PointCloud& cloud : p.block.clouds) pointers.push_back(&cloud);
  // As refineBlock finds them where the hierarchy kept the first frame.
  p.planes.poses = slice(initial, 0, p.block.end);
  p.planes.association = ba::refinementAssociation(pointers, p.planes.poses, settings.ba);
  return prepared;
}

void StageNotes::warn(std::string message) {
  spdlog::warn("{}", message);
  warnings.push_back(std::move(message));
}

void StageNotes::add(const StageNotes& other) {
  warnings.insert(warnings.end(), other.warnings.begin(), other.warnings.end());
  seconds_voxelize += other.seconds_voxelize;
  seconds_solve += other.seconds_solve;
}

RefineOutcome refineAndCheck(const io::ScanSource& scans, const std::vector<Pose>& initial,
                             const std::vector<Pose>& hierarchy, const HierarchyFacts& facts,
                             const std::vector<graph::PositionPriorFactor>& priors,
                             const RefineSettings& settings, PreparedStart* prepared) {
  const auto start = Clock::now();
  RefineOutcome out;
  out.poses = hierarchy;
  const std::vector<double> steps = stepLengths(initial);
  const bool refines = refinesAfter(facts, settings);  // one layer is one global BA already
  const bool groups_follow = refines && settings.groups;
  std::unique_ptr<io::SpilledScanSource> spilled =
      prepared ? std::move(prepared->parts->spilled) : keptFromTheStart(scans, facts, settings);
  const io::ScanSource* source = spilled ? spilled.get() : &scans;
  BlockSums sums;
  BlockMaps kept_maps;  // for the groups' re-measure, when they run
  std::size_t first = 0;
  for (std::size_t index = 0;; ++index) {
    releaseFreedMemory();  // what the hierarchy or the block before left
    const bool ready = index == 0 && prepared != nullptr;
    const Block block = ready ? std::move(prepared->parts->block)
                              : loadBlock(*source, first, settings.max_points, settings.scan_voxel);
    const BlockOutcome b = refineBlock(block, index, initial, out.poses, steps, priors, settings, refines,
                                       ready ? &prepared->parts->planes : nullptr);
    sums.add(block, b, out);
    std::copy(b.poses.begin(), b.poses.end(), out.poses.begin() + static_cast<long>(block.first));
    const bool last = block.end >= initial.size();
    if (groups_follow && !(last && index == 0)) kept_maps.keep(b.map);
    if (last) break;
    if (!spilled && !facts.scans_kept) {
      spilled = std::make_unique<io::SpilledScanSource>(scans);
      source = spilled.get();
    }
    // The next block overlaps this one by a quarter, so that no frame is
    // refined only at a block's edge.
    first = std::max(block.first + 1, block.end - (block.end - block.first) / 4);
    if (first + 1 >= initial.size()) break;  // no block of one frame
  }
  out.refinement.blocks = sums.spans.size();
  out.consistency.final_rms = sums.final.rms();
  if (out.refinement.blocks > 1 && groups_follow)
    placeGroups(*source, initial, kept_maps, settings, sums, out);
  reportRegions(sums.regions, out);
  out.consistency.input_rms = sums.input.rms();
  out.consistency.hierarchy_rms = sums.hierarchy.rms();
  out.refinement.rms_before = sums.refine_before.rms();
  out.refinement.rms_after = sums.refine_after.rms();
  out.refinement.seconds = secondsSince(start);
  logSummary(out, initial.size());
  return out;
}

}  // namespace hba::refine
