#pragma once
// The closure stage's pose graph (docs/closure.md): the input trajectory's
// own steps, softly, plus the verified loop closures and the position
// priors. Its solution is the hierarchy's start: loops closed and the frame
// set by the priors before any window runs, so that the windows and the top
// BA see each revisited place in one piece.
//
// Loops and priors that the others contradict are dropped one by one (the
// worst first) until every one left agrees with the solution, and may come
// back once the solution has moved; what was dropped is reported.
#include <cstddef>
#include <vector>

#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"
#include "hba/graph/factors.hpp"

namespace hba::closure {

// How far the input's step between consecutive frames may be wrong (one
// sigma per axis): a floor plus a share of the step's length. Sets how a
// loop's correction spreads along the path: evenly by distance. Generous,
// because odometry drift is a bias more than noise: a loop must close
// whatever the drift, and the loops and priors are judged against each
// other, not against the input's steps. (Dense priors may therefore bend
// the start locally by their noise; the BAs after it hold the local shape
// to the planes.)
struct OdometryNoise {
  double translation_m = 0.02;
  double translation_per_m = 0.02;
  double rotation_deg = 0.05;
  double rotation_deg_per_m = 0.05;
};

struct ClosureGraphSettings {
  OdometryNoise odometry;
  // A loop is dropped when e^T Omega e exceeds `loop_gate` and it is off by
  // more than the tolerances (stiff loops from dense planes may disagree by
  // millimetres without being wrong); a prior when its e^T Omega e exceeds
  // `prior_gate`. The gates are the 99.9 % points of chi-square with 6 and
  // 3 degrees of freedom.
  double loop_gate = 22.46;
  double loop_tolerance_m = 0.05;
  double loop_tolerance_deg = 0.5;
  double prior_gate = 16.27;
  int max_rounds = 50;
  int threads = 0;  // of the Ceres solve; 0 = all
};

struct ClosureGraphResult {
  std::vector<Pose> poses;
  std::vector<bool> loop_kept;    // per loop given
  std::vector<bool> prior_kept;   // per prior given
  std::vector<double> loop_chi2;  // e^T Omega e at `poses`
  std::vector<double> prior_chi2;
  int rounds = 0;  // solves
  // Every loop and prior already held at the input (none beyond its gate
  // and tolerance): nothing was solved and `poses` is the input, so a
  // map whose loops are closed stays where it is.
  bool held_at_input = false;
};

// `input` is the trajectory to correct (its steps become the soft factors,
// except the step into a session's first frame: `session_starts`, see
// sessions.hpp); loops and priors index into it. A session that no loop or
// prior ties to the others keeps its input poses. Throws hba::Error for
// invalid factors.
ClosureGraphResult solveClosureGraph(const std::vector<Pose>& input,
                                     const std::vector<graph::LoopClosureFactor>& loops,
                                     const std::vector<graph::PositionPriorFactor>& priors,
                                     const ClosureGraphSettings& settings,
                                     const std::vector<std::size_t>& session_starts = {});

// How stiffly the final poses' own steps hold when priors re-anchor them: a
// fifth of the input's noise, so the map stays as crisp as the BA left it
// while its shape may still bend over kilometres.
inline OdometryNoise finalStepNoise() { return {0.0004, 0.001, 0.002, 0.002}; }

// The optimized poses moved onto the priors (the BAs after the closure stage
// do not see them): the closure graph of the poses' own steps, held by
// finalStepNoise(), and the priors; priors that the stiff shape
// contradicts are dropped as there.
ClosureGraphResult anchorToPriors(const std::vector<Pose>& poses,
                                  const std::vector<graph::PositionPriorFactor>& priors,
                                  const ClosureGraphSettings& settings,
                                  const std::vector<std::size_t>& session_starts = {});

// The soft factor of the input's step from frame k to k + 1.
graph::RelativePoseFactor odometryFactor(const std::vector<Pose>& input, std::size_t k,
                                         const OdometryNoise& noise);

}  // namespace hba::closure
