#include "block.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>
#include <utility>

#include "core/release_memory.hpp"
#include "hba/voxel/downsample.hpp"
#include "refinement_priors.hpp"

namespace hba::refine {
namespace {

// Regions of the per-region self-check: about 100 frames each, 4 to 20.
std::size_t regionCount(std::size_t frames) { return std::clamp<std::size_t>(frames / 100, 4, 20); }

// The block's plane BA from `poses`, held by the priors among its frames.
// `at_start`: the association at out.poses, when made already.
void refineFrom(const Block& block, const std::vector<const PointCloud*>& pointers, std::size_t index,
                const std::vector<Pose>& input, const std::vector<double>& steps,
                const std::vector<graph::PositionPriorFactor>& priors, const RefineSettings& settings,
                ba::Association* at_start, BlockOutcome& out) {
  const std::vector<double> block_steps(steps.begin() + static_cast<long>(block.first),
                                        steps.begin() + static_cast<long>(block.end - 1));
  const ba::PositionPriors positions =
      blockPriors(priors, block.first, block.end, settings.ba.motion_prior.point_sigma);
  ba::RefinementSettings rs = settings.ba;
  // Later blocks stay held at their first frame, which the block before
  // placed: no seam where they overlap.
  rs.lm.hold_first = index > 0 || !positions.defineTheFrame(kPriorSpreadForGauge);
  out.position_priors = positions.terms().size();
  if (!positions.empty()) {
    spdlog::info("refinement: frames {}-{} held by {} position priors, first frame {}", block.first,
                 block.end - 1, positions.terms().size(), rs.lm.hold_first ? "held" : "free");
  }
  out.refinement = ba::refineGlobally(pointers, out.poses, rs, block_steps, input, positions, at_start);
  out.refined = true;
  out.poses = std::move(out.refinement.poses);
  out.refinement.poses.clear();
  if (out.refinement.still_sliding > 0) {
    out.notes.warn(
        fmt::format("frames {}-{}: {} pairs of neighbouring frames still move apart "
                    "beyond what odometry plausibly gets wrong, though held",
                    block.first, block.end - 1, out.refinement.still_sliding));
  }
  out.notes.seconds_voxelize += out.refinement.seconds_associate;
  out.notes.seconds_solve += out.refinement.seconds_solve;
}

}  // namespace

namespace {

// Bit for bit: planes found at other poses are other planes, and a pose
// made again from itself differs in its last bits.
bool samePose(const Pose& a, const Pose& b) { return a.t == b.t && a.q.coeffs() == b.q.coeffs(); }

}  // namespace

std::vector<Pose> slice(const std::vector<Pose>& poses, std::size_t first, std::size_t end) {
  return {poses.begin() + static_cast<long>(first), poses.begin() + static_cast<long>(end)};
}

std::vector<Pose> inputOnto(const std::vector<Pose>& initial, const std::vector<Pose>& result,
                            std::size_t first, std::size_t end) {
  // Where the result kept the first frame (the hierarchy holds it), the
  // input itself: P * P^-1 is the identity only to rounding, which moved a
  // converged input by 1e-16 on some toolchains (Debian 13), and it then
  // did not come back unchanged.
  if (samePose(result[first], initial[first])) return slice(initial, first, end);
  const Pose onto = result[first] * initial[first].inverse();
  std::vector<Pose> input = slice(initial, first, end);
  for (Pose& pose : input) pose = onto * pose;
  return input;
}

Block loadBlock(const io::ScanSource& scans, std::size_t first, std::size_t max_points, double voxel,
                std::size_t last_end) {
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

namespace {

bool samePoses(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), samePose);
}

// The hierarchy lowered the cost of the input's planes by more than
// `significant_gain` times what `frames` poses gain by fitting the noise.
bool hierarchyGainsBeyondNoise(const BlockOutcome& out, std::size_t frames, double significant_gain) {
  const double points = out.map.points();
  const double input_cost = out.input_rms * out.input_rms * points;
  const double gain = input_cost - out.hierarchy_rms * out.hierarchy_rms * points;
  const double noise =
      ba::noiseFittingGain(input_cost, points, static_cast<double>(out.map.planes()), frames);
  return gain > significant_gain * noise;
}

}  // namespace

BlockOutcome refineBlock(const Block& block, std::size_t index, const std::vector<Pose>& initial,
                         const std::vector<Pose>& result, const std::vector<double>& steps,
                         const std::vector<graph::PositionPriorFactor>& priors,
                         const RefineSettings& settings, bool refines, InputPlanes* found_before) {
  std::vector<const PointCloud*> pointers;
  for (const PointCloud& cloud : block.clouds) pointers.push_back(&cloud);
  // The input of this block, moved rigidly onto the result at its first
  // frame (the whole input when the block is the sequence).
  const std::vector<Pose> input = inputOnto(initial, result, block.first, block.end);
  const std::vector<Pose> current = slice(result, block.first, block.end);
  const ba::RefinementSettings& rs = settings.ba;
  // The input's planes, as the refinement associates them (kept whole while
  // the map judges the hierarchy: a refinement from the input starts on
  // this very association).
  ba::Association found = found_before != nullptr && samePoses(found_before->poses, input)
                              ? std::move(found_before->association)
                              : ba::refinementAssociation(pointers, input, rs);
  BlockOutcome out(FixedPlaneMap(found.problem, input.size(), regionCount(input.size())));
  const FixedPlaneMap::Figures at_input = out.map.figures(input);
  out.input_rms = at_input.rms;
  out.hierarchy_rms = out.map.rms(current);
  out.poses = current;
  if (!(out.hierarchy_rms <= out.input_rms * kEqualMapMargin)) {  // NaN counts as worse
    out.hierarchy_rejected = true;
    out.poses = input;
    // Said as it is: without the refinement the hierarchy's work is simply
    // lost here (--no-refine returns the input, loops closed).
    if (!refines) {
      out.notes.warn(fmt::format(
          "frames {}-{}: the hierarchy made the map less consistent than the input (plane RMS {:.4f} -> "
          "{:.4f} m on the input's planes): keeping the input poses (with the closure stage's loops), "
          "unrefined",
          block.first, block.end - 1, out.input_rms, out.hierarchy_rms));
    }
  } else if (!hierarchyGainsBeyondNoise(out, input.size(), settings.ba.significant_gain)) {
    // Not worse, but no more consistent than fitting the points' noise
    // would make it: at a converged input the hierarchy only perturbs it.
    out.hierarchy_insignificant = true;
    out.poses = input;
    spdlog::info(
        "frames {}-{}: the hierarchy's poses are not significantly more consistent than the input's "
        "(plane RMS {:.5f} -> {:.5f} m on the input's planes): {}",
        block.first, block.end - 1, out.input_rms, out.hierarchy_rms,
        refines ? "refining from the input" : "keeping the input poses (with the closure stage's loops)");
  }
  const bool from_input = refines && (out.hierarchy_rejected || out.hierarchy_insignificant);
  if (!from_input) {
    // The plane problem the map was made from (hundreds of MB in small
    // pieces): returned, so that the refinement's association does not
    // stack its peak on it.
    found = {};
    releaseFreedMemory();
  }
  if (refines)
    refineFrom(block, pointers, index, input, steps, priors, settings, from_input ? &found : nullptr, out);
  if (refines && out.hierarchy_rejected) {
    // A warning where the hierarchy's work is lost; where the refinement
    // finds the input converged, nothing was: the hierarchy could only
    // have perturbed it.
    const std::string said = fmt::format(
        "frames {}-{}: the hierarchy made the map less consistent than the input (plane RMS "
        "{:.4f} -> {:.4f} m on the input's planes)",
        block.first, block.end - 1, out.input_rms, out.hierarchy_rms);
    if (out.refinement.converged_at_start) {
      spdlog::info("{}; the input is converged (the refinement gains nothing from it): kept", said);
    } else {
      out.notes.warn(said + ": refining from the input");
    }
  }
  FixedPlaneMap::Figures at_final = out.map.figures(out.poses);
  out.final_rms = at_final.rms;
  if (!(out.final_rms <= out.input_rms * kEqualMapMargin)) {
    out.final_rejected = true;
    out.notes.warn(
        fmt::format("frames {}-{}: the result is less consistent than the input (plane "
                    "RMS {:.4f} -> {:.4f} m on the input's planes): keeping the input "
                    "poses there",
                    block.first, block.end - 1, out.input_rms, out.final_rms));
    out.poses = input;
    out.final_rms = out.input_rms;
    at_final = at_input;
  }
  out.region_input_rms = at_input.region_rms;
  out.region_final_rms = at_final.region_rms;
  return out;
}

}  // namespace hba::refine
