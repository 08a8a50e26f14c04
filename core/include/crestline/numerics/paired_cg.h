#pragma once
// Two symmetric positive definite systems solved together, for extremality
// smoothing (paper §5.1): the κ_max and κ_min fields share the mass matrix
// and the cotan weights, and their matrices differ only in the signs σ_pq of
// off-diagonal entries. Conjugate gradients on both in lockstep read each
// matrix entry once for both fields (12 bytes per entry instead of 24), which
// is what a sparse matrix-vector product is limited by.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace crestline {

/// A_k(i,i) = diagonal[i]; A_k(i,j) = ±weight for the off-diagonal entries of
/// a CSR pattern with both triangles stored, negated in A_k where bit k of
/// the entry's sign mask is set (k = 0, 1).
struct SignedPairMatrix {
  std::vector<uint32_t> offsets;  // rows + 1
  std::vector<uint32_t> columns;  // column | sign mask << 30
  std::vector<double> weights;
  std::vector<double> diagonal;

  static constexpr uint32_t kColumnMask = (1u << 30) - 1;
  size_t rows() const { return diagonal.size(); }
};

/// Jacobi-preconditioned CG on both systems; x (2 values per row,
/// interleaved: x[2i+k]) holds the guess on entry. Each system stops at
/// relative residual `tolerance` (as Eigen's CG). Returns false if either has
/// not converged within max_iterations; x then holds the last iterates.
bool solve_signed_pair(const SignedPairMatrix& matrix, const std::vector<double>& b, std::vector<double>& x,
                       double tolerance, int max_iterations);

}  // namespace crestline
