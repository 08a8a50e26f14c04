#pragma once
// The general solver for Crestline's systems, M + t·L with a lumped mass
// matrix M and a (sign-corrected) cotan Laplacian with non-negative
// weights, hence symmetric positive definite: Eigen's CG, then a
// factorization. The large solves, extremality smoothing and pre-smoothing,
// run on SignedPairSolver (numerics/paired_cg.h) and come here only where
// it does not converge; the boundary curves of pre-smoothing (1-D, small)
// come here always. Well conditioned for time steps of a few squared edge
// lengths, CG beats a factorization in time and memory. Sliver triangles
// (marching-cubes scans) break that: a vertex whose cotan weights dwarf its
// mass makes the condition number huge, and CG needs thousands of
// iterations. The solver then factorizes once (sparse LDLᵀ) and reuses it.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace crestline {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Triplets = std::vector<Eigen::Triplet<double>>;

class SpdSolver {
 public:
  /// Takes the matrix (swapped in: Eigen's SparseMatrix has no move
  /// constructor, so a by-value parameter would copy it); throws
  /// Error(Numerical) unless its diagonal is positive and finite.
  void compute(SparseMatrix&& matrix);
  /// Solves matrix · x = b starting from `guess`; throws Error(Numerical)
  /// when neither the iteration nor the factorization converges. The first
  /// solve gives CG a budget of about what a factorization costs; beyond it,
  /// this and every later solve use the factorization.
  Eigen::VectorXd solve(const Eigen::VectorXd& b, const Eigen::VectorXd& guess) const;

  double tolerance = 1e-10;  // relative residual
  int max_iterations = 2000;

 private:
  struct Factorization;
  SparseMatrix matrix_;
  mutable std::shared_ptr<Factorization> factorization_;
  mutable bool iterative_ok_ = false;  // CG has converged here before
};

}  // namespace crestline
