#include "crestline/numerics/sparse_solver.h"

#include <Eigen/IterativeLinearSolvers>

#include "crestline/error.h"

namespace crestline {

void SpdSolver::compute(SparseMatrix matrix) {
  matrix_ = std::move(matrix);
  matrix_.makeCompressed();
  for (Eigen::Index i = 0; i < matrix_.rows(); ++i) {
    const double d = matrix_.coeff(i, i);
    if (!(d > 0) || !std::isfinite(d))
      throw Error(ErrorKind::Numerical, "the smoothing system is not positive definite.");
  }
}

Eigen::VectorXd SpdSolver::solve(const Eigen::VectorXd& b, const Eigen::VectorXd& guess) const {
  // Full (Lower|Upper) storage lets the matrix-vector product run in one pass.
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg;
  cg.setTolerance(tolerance);
  cg.setMaxIterations(max_iterations);
  cg.compute(matrix_);
  if (cg.info() != Eigen::Success) throw Error(ErrorKind::Numerical, "the smoothing system could not be prepared.");
  Eigen::VectorXd x = cg.solveWithGuess(b, guess);
  if (cg.info() != Eigen::Success || !x.allFinite())
    throw Error(ErrorKind::Numerical, "the smoothing solver did not converge.");
  return x;
}

}  // namespace crestline
