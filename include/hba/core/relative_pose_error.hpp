#pragma once
// The residual of a relative-pose factor and its analytic Jacobians.
//
// For a measured relative pose M = (R_m, t_m) of node b seen from node a, the
// error pose is E = M^-1 * T_a^-1 * T_b (identity when the poses agree with the
// measurement) and the residual is
//     e = ( t_E , Log(R_E) ) = ( R_m^T (R_a^T (t_b - t_a) - t_m) , Log(R_m^T R_a^T R_b) ),
// translation first as in hba/core/lie.hpp. To first order around E = I it
// equals se3Log(E), so an information matrix computed at the measurement is
// valid for either; this form is cheaper and its Jacobians are simpler.
//
// Jacobians are taken w.r.t. the world-frame perturbations of the BA
// (hba/ba/window_ba.hpp): R <- Exp(dphi) R, t <- t + dt, coordinates (dt, dphi).
#include "hba/core/pose.hpp"
#include "hba/core/types.hpp"

namespace hba {

Vec6 relativePoseError(const Pose& measurement, const Pose& from, const Pose& to);

struct RelativePoseErrorJacobians {
  Vec6 error;
  Mat6 d_from;  // d error / d (dt_a, dphi_a)
  Mat6 d_to;    // d error / d (dt_b, dphi_b)
};

RelativePoseErrorJacobians relativePoseErrorJacobians(const Pose& measurement, const Pose& from,
                                                      const Pose& to);

}  // namespace hba
