#pragma once
// Eigenvalues of a symmetric 3x3 matrix in closed form.
#include <Eigen/Eigenvalues>

#include "hba/core/types.hpp"

namespace hba {

// Ascending eigenvalues of the symmetric `m`, from the roots of its
// characteristic polynomial (Eigen's computeDirect, which shifts and scales
// the matrix first). About eight times faster than the iterative solver, and
// as accurate in absolute terms (a small multiple of machine epsilon times
// the largest eigenvalue): what plane costs and plane tests need, which ask
// for no eigenvectors.
//
// The closed form resolves two nearly equal eigenvalues only to about the
// square root of epsilon; where the two smallest are that close (points
// along a line, whose smallest is a cost) the iterative solver answers.
inline Vec3 symmetricEigenvalues(const Mat3& m) {
  Eigen::SelfAdjointEigenSolver<Mat3> solver;
  solver.computeDirect(m, Eigen::EigenvaluesOnly);
  const Vec3 values = solver.eigenvalues();
  if (values(1) - values(0) > 1e-3 * (values(2) - values(0))) return values;  // NaN: not taken
  return Eigen::SelfAdjointEigenSolver<Mat3>(m, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace hba
