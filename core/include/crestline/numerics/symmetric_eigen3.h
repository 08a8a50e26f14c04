#pragma once
// Eigen-decomposition of a symmetric 3×3 matrix: the shape operator's
// (curvature/shape_operator.cpp), once per vertex.
#include <Eigen/Core>

namespace crestline {

struct SymmetricEigen3 {
  Eigen::Vector3d values;   // ascending
  Eigen::Matrix3d vectors;  // unit eigenvectors, column i for values[i]
};

/// What Eigen::SelfAdjointEigenSolver<Matrix3d>::compute returns, bit for
/// bit (eigenvalues(), eigenvectors()): the same arithmetic in the same
/// order (scaling to [−1, 1], the closed-form 3×3 Householder
/// tridiagonalization, implicit symmetric QR steps with Wilkinson shifts,
/// then a selection sort), unrolled for 3×3 so that the tridiagonal matrix
/// and Q stay in registers, where Eigen loops over dynamic-size views of Q
/// (compute_curvature's per-vertex loop: 1015 M → 848 M instructions at
/// 1.1M triangles). Reads only the lower triangle (s(0,0), s(1,0), s(2,0),
/// s(1,1), s(2,1), s(2,2)). A matrix with a non-finite coefficient goes to
/// Eigen's solver itself.
SymmetricEigen3 symmetric_eigen3(const Eigen::Matrix3d& s);

}  // namespace crestline
