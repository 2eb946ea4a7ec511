#pragma once
// The last stage of hba optimize: one plane BA over every layer-1 frame at
// the finest voxel, started from the hierarchy's poses (already within
// centimetres), solved by the sparse LM of sparse_lm.hpp. The pyramid finds
// the large corrections cheaply; this stage recovers what the pyramid's
// windows cannot see (planes shared by frames of different windows).
#include <vector>

#include "hba/ba/association.hpp"
#include "hba/ba/motion_prior.hpp"
#include "hba/ba/position_prior.hpp"
#include "hba/ba/sparse_lm.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"
#include "hba/dist/group.hpp"
#include "hba/voxel/plane_map.hpp"

namespace hba::ba {

struct RefinementSettings {
  voxel::PlaneSettings planes;  // voxel 1 m, theta 0.05: the local windows' final planes
  double reject_ratio = 0.05;
  // Associations, each followed by an LM: the planes found at the
  // hierarchy's poses are not all the planes at better poses (a sparse,
  // jittery sequence needs several; a dense one stops after one or two).
  // Another round runs only while the last one cut its plane cost by at
  // least `round_gain` (a share of the cost it started from).
  int association_rounds = 6;
  double round_gain = 0.02;
  // A round is taken only if it lowers the cost by more than this many times
  // what re-fitting the poses to the points' noise alone gains in
  // expectation (sigma^2 per degree of freedom of the poses, sigma from the
  // planes' residuals); otherwise its poses are dropped and the refinement
  // has converged. So a converged map, refined again, stays where it is
  // (moves along directions the planes barely hold are not made), while a
  // real correction gains tens of times more (hku1, nclt: 13x and 28x).
  // 1.5, not 1: the first of two blocks of a converged 1000-frame sequence
  // gained 1.15x, moved, and the group pass then put the map back 1 mm
  // from where it was; the least real gain measured is nclt's second
  // association, 1.9x.
  double significant_gain = 1.5;
  // An LM step that gains less than this many times what fitting the noise
  // gains ends the round's LM (0: only lm.relative_cost_tolerance does).
  // After the first step or two the steps of a round gain hundreds of times
  // less than the first and creep along modes the planes barely hold, at
  // 50 conjugate-gradient products each: 1000 simulated HDL-32 frames' refinement took
  // 6 steps, 213 products and 8.5 s for 0.591 mm ATE; stopped at 1, 4 steps,
  // 112 products, 7.3 s for 0.595 mm; hku1 and nclt end as crisp or crisper.
  double step_gain = 1.0;
  // Neighbouring frames whose relative pose leaves the reference's by more
  // than `slide_sigmas` sigmas of `slide_prior` (hba optimize: the
  // refinement's own prior) slid where the planes do not hold them
  // firmly: the prior between them (and two pairs either side) is made
  // `hold_factor` times stiffer and the refinement solved again, at most
  // `max_holds` times; pairs still sliding then stay held (`still_sliding`).
  MotionPriorSettings slide_prior;
  double slide_sigmas = 5.0;
  double hold_factor = 100.0;
  int max_holds = 2;
  SparseLmSettings lm;
  MotionPriorSettings motion_prior;
  // The processes that share the work (docs/mpi.md), each calling with the
  // same scans and settings; null: this process alone. The poses are those
  // of one process, bit for bit.
  const dist::Group* spread_over = nullptr;
  RefinementSettings() {
    planes.voxel_size = 1.0;
    // Tighter than the windows' prior: it holds neighbouring frames at the
    // odometry's relative poses, right to a few centimetres. Looser, frames that the planes barely constrain
    // (a narrow field of view over open ground) slid by metres along the free directions while re-association
    // fed them noise; this still lets the planes move a frame by centimetres where they see it.
    motion_prior.translation_sigma = 0.05;
    motion_prior.translation_per_m = 0.05;
    motion_prior.rotation_sigma_deg = 0.5;
    motion_prior.rotation_per_m_deg = 0.1;
  }
};

// What moving `frames` poses (the first held) lowers a plane cost by when
// they only fit the points' noise, in expectation: sigma^2 per degree of
// freedom, 6 (frames - 1), sigma^2 the cost per point left after each of
// `planes` planes' own fit (3 per plane). 0 without such points.
double noiseFittingGain(double plane_cost, double points, double planes, std::size_t frames);

struct RefinementResult {
  std::vector<Pose> poses;
  // Plane cost (sum of squared point-to-plane distances, m^2) of the first
  // association, before and after its LM: the same planes and points, so a
  // like-for-like measure of how much crisper the map got (later rounds
  // re-associate and are not counted here).
  double cost_before = 0.0;
  double cost_after = 0.0;
  double rms_before = 0.0;  // sqrt(cost / plane points), m
  double rms_after = 0.0;
  std::size_t planes = 0;
  std::size_t observations = 0;  // (frame, plane) clusters
  std::size_t plane_points = 0;
  int iterations = 0;
  int cg_products = 0;  // conjugate-gradient products H x, summed
  int rounds = 0;       // of the last solve
  // The last round gained no more than `significant_gain` times what
  // fitting the noise gains: its poses were not taken. `converged_at_start`:
  // already the first round did not, and `poses` are the start's.
  bool converged = false;
  bool converged_at_start = false;
  double last_gain_over_noise = 0.0;  // the last round's gain, in units of fitting the noise
  std::size_t held_pairs = 0;         // neighbouring pairs held after sliding
  std::size_t still_sliding = 0;      // of those, pairs beyond the limit even when held
  double seconds_associate = 0.0;
  double seconds_solve = 0.0;
};

// `path_m[k]`: path between frames k and k+1 for the motion prior (empty:
// straight distances). The prior holds neighbouring frames at their
// relative pose in `reference` (the odometry; empty: `initial`), whose
// local steps are usually better than those of a window that slid.
// `positions` hold frames near absolute positions (with settings.lm.
// hold_first off where they define the frame). Scans are only read.
// `at_initial`, when given: refinementAssociation(scans, initial,
// settings) made already (the self-check's, when the refinement starts
// from the input), taken as the first round's instead of the same
// association made again; it is moved from.
// The refinement's association at `poses` (each round's, at the poses the
// round starts from), without the planes' point indices, which the LM does
// not need.
Association refinementAssociation(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& poses,
                                  const RefinementSettings& settings);

RefinementResult refineGlobally(const std::vector<const PointCloud*>& scans, const std::vector<Pose>& initial,
                                const RefinementSettings& settings, const std::vector<double>& path_m = {},
                                const std::vector<Pose>& reference = {}, const PositionPriors& positions = {},
                                Association* at_initial = nullptr);

}  // namespace hba::ba
