#pragma once
// Eigen-decomposition of a symmetric 3×3 matrix: the shape operator's
// (curvature/shape_operator.cpp), once per vertex.
#include <Eigen/Core>
#include <array>
#include <cstddef>

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
/// Eigen's solver itself. Solved in a pair with the zero matrix (below).
SymmetricEigen3 symmetric_eigen3(const Eigen::Matrix3d& s);

/// A symmetric 3×3 matrix by its lower triangle: s(0,0), s(1,0), s(2,0),
/// s(1,1), s(2,1), s(2,2).
using SymmetricLower3 = std::array<double, 6>;

/// symmetric_eigen3 of `count` matrices, out[i] for matrices[i]: the same
/// bits, in less time per matrix. The finite ones are solved two at a time,
/// one in each lane of a SIMD vector (SSE2, WASM SIMD128): each lane does
/// Eigen's arithmetic, operation for operation, with branches as selects,
/// so a matrix's partner never changes its bits. The QR steps are chains of
/// divisions and square roots whose latency bounds them; two chains take
/// the time of one. A matrix whose block is down to 2×2 waits while its
/// partner takes 3×3 steps (Eigen takes 2 to 5 of those, then one 2×2
/// step): 2.3 vector steps a matrix where there were 4.3 to 4.5 steps.
/// Per matrix on the shape operators of the 1.1M-triangle bunny, the dragon
/// and the bunny (min of 9 alternated rounds, loaded machine): native 320 →
/// 205 ns, WASM 385 → 200 ns; instructions (callgrind, bunny) 1423 → 1348.
void symmetric_eigen3(const SymmetricLower3* matrices, size_t count, SymmetricEigen3* out);

}  // namespace crestline
