#pragma once
// What the last stage reported: the refinement over every layer-1 frame,
// its coarse whole-sequence groups, and the self-check against the input
// (docs/pyramid.md, "Refinement and self-check"). Plain data.
#include <cstddef>
#include <vector>

namespace hba::refine {

// The coarse, whole-sequence half of the refinement (rigid groups of frames).
struct GroupRefinementReport {
  bool ran = false;
  std::size_t groups = 0;
  std::size_t frames_per_group = 0;
  std::size_t points = 0;  // in the groups' merged clouds
  std::size_t planes = 0;
  double rms_before = 0.0;  // m, on the groups' planes found at the start
  double rms_after = 0.0;
  // Blurrier on the groups' planes, or less consistent than the input on
  // the self-check's: the blocks' result is kept.
  bool rejected = false;
  double largest_move_m = 0.0;  // of a group
  double seconds = 0.0;
};

struct RefinementReport {
  bool ran = false;
  GroupRefinementReport groups;
  std::size_t blocks = 0;       // consecutive, overlapping stretches of frames (memory bound)
  std::size_t scan_points = 0;  // points held, summed over blocks (at refine_scan_voxel)
  std::size_t planes = 0;
  std::size_t observations = 0;
  std::size_t plane_points = 0;
  double rms_before = 0.0;  // m, on the refinement's planes
  double rms_after = 0.0;
  int iterations = 0;
  int cg_products = 0;              // conjugate-gradient products H x, summed over blocks
  int rounds = 0;                   // associations, summed over blocks
  std::size_t held_pairs = 0;       // neighbouring pairs that slid and were held (summed over blocks)
  std::size_t still_sliding = 0;    // of those, pairs beyond the limit even when held
  std::size_t position_priors = 0;  // held by the blocks' LM, summed over blocks (overlaps count twice)
  // Every block's last association gained no more than fitting the points'
  // noise would (ba::RefinementSettings::significant_gain), so its poses were
  // not taken: converged. `converged_at_start`: already every block's first
  // did, and the refinement returned its start. `gain_over_noise`: the
  // largest last-round gain of a block, in those units.
  bool converged = false;
  bool converged_at_start = false;
  double gain_over_noise = 0.0;
  double seconds = 0.0;
};

// The self-check: RMS point-to-plane distance (m) on one fixed set of
// planes found at the input poses (finest voxel), for the input, the
// hierarchy's and the final poses; per region (stretches of the sequence)
// too. Lower is crisper.
struct ConsistencyReport {
  std::size_t planes = 0;
  double input_rms = 0.0;
  double hierarchy_rms = 0.0;
  double final_rms = 0.0;
  bool hierarchy_rejected = false;  // less consistent than the input: refined from the input
  // Not less consistent, but gaining no more than fitting the points' noise
  // would: the input is refined instead (a converged input stays put).
  bool hierarchy_insignificant = false;
  bool final_rejected = false;  // less consistent than the input: input poses returned
  std::vector<std::size_t> region_first_frame;
  std::vector<double> region_input_rms;
  std::vector<double> region_final_rms;
};

}  // namespace hba::refine
