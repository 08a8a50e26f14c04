#include "crestline/numerics/paired_cg.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "crestline/numerics/parallel.h"

namespace crestline {
namespace {

// Rows per block of the reductions: each block sums its rows in order, then
// the blocks are summed in order, so the dot products (and with them every
// iterate) are the same for any number of threads.
constexpr size_t kBlock = 1024;
// Blocks a thread takes at least; smaller systems stay on one thread.
constexpr size_t kMinBlocksPerThread = 4;

// Up to two sums per field: sums[k] and sums[2 + k] for field k.
using BlockSums = std::array<double, 4>;
using Sums = std::vector<BlockSums>;

// Calls body(begin, end, sums) for each block of rows, in parallel, and
// returns the totals of what the blocks added to their sums.
template <typename Body>
BlockSums sum_blocks(size_t rows, Sums& partial, const Body& body) {
  const size_t blocks = (rows + kBlock - 1) / kBlock;
  partial.assign(blocks, BlockSums{});
  parallel_for(
      blocks,
      [&](size_t first, size_t last) {
        for (size_t block = first; block < last; ++block)
          body(block * kBlock, std::min(rows, (block + 1) * kBlock), partial[block]);
      },
      kMinBlocksPerThread);
  BlockSums total{};
  for (const BlockSums& sums : partial)
    for (size_t k = 0; k < total.size(); ++k) total[k] += sums[k];
  return total;
}

// ±1 for both fields, by the entry's sign mask: multiplying by them is
// exact, and the pair of products is one SIMD multiplication.
alignas(16) constexpr double kSigns[4][2] = {{1, 1}, {-1, 1}, {1, -1}, {-1, -1}};

// y = A_k p for both k over rows [begin, end), interleaved; adds ⟨p_k, y_k⟩ to py[k].
void multiply(const SignedPairMatrix& a, const double* p, double* y, size_t begin, size_t end, BlockSums& py) {
  for (size_t i = begin; i < end; ++i) {
    double y0 = a.diagonal[i] * p[2 * i], y1 = a.diagonal[i] * p[2 * i + 1];
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
      const uint32_t c = a.columns[e];
      const double* sign = kSigns[c >> 30];
      const double* pj = p + 2 * size_t{c & SignedPairMatrix::kColumnMask};
      const double w = a.weights[e];
      y0 += w * sign[0] * pj[0];
      y1 += w * sign[1] * pj[1];
    }
    y[2 * i] = y0, y[2 * i + 1] = y1;
    py[0] += p[2 * i] * y0, py[1] += p[2 * i + 1] * y1;
  }
}

}  // namespace

SignedPairSolver::SignedPairSolver(SignedPairMatrix matrix) : a_(std::move(matrix)), inverse_diagonal_(a_.rows()) {
  for (size_t i = 0; i < a_.rows(); ++i) inverse_diagonal_[i] = 1.0 / a_.diagonal[i];
}

bool SignedPairSolver::solve(std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
                             const std::function<void(int)>& on_iteration) const {
  const SignedPairMatrix& a = a_;
  const std::vector<double>& inverse_diagonal = inverse_diagonal_;
  const size_t n = a.rows();
  // The preconditioned residual z = D⁻¹ r is never stored: each pass that
  // needs it recomputes it from r.
  std::vector<double>& r = b;  // b is read once, then holds the residual
  std::vector<double> p(2 * n), q(2 * n);
  Sums partial;
  sum_blocks(n, partial,
             [&](size_t begin, size_t end, BlockSums& sums) { multiply(a, x.data(), q.data(), begin, end, sums); });
  const BlockSums b2 = sum_blocks(n, partial, [&](size_t begin, size_t end, BlockSums& sums) {
    for (size_t j = 2 * begin; j < 2 * end; ++j) sums[j & 1] += b[j] * b[j];
  });
  // rr[k] = ⟨r_k, r_k⟩, rr[2 + k] = ⟨r_k, z_k⟩.
  BlockSums rr = sum_blocks(n, partial, [&](size_t begin, size_t end, BlockSums& sums) {
    for (size_t j = 2 * begin; j < 2 * end; ++j) {
      r[j] = b[j] - q[j];
      p[j] = r[j] * inverse_diagonal[j / 2];
      sums[j & 1] += r[j] * r[j];
      sums[2 + (j & 1)] += r[j] * p[j];
    }
  });
  double rz[2] = {rr[2], rr[3]};
  bool active[2];
  for (int k = 0; k < 2; ++k) {
    // As Eigen: a zero right-hand side has the solution 0.
    if (b2[k] == 0) {
      for (size_t i = 0; i < n; ++i) x[2 * i + k] = 0;
      active[k] = false;
    } else {
      active[k] = rr[k] > tolerance * tolerance * b2[k];
    }
  }
  for (int it = 0; it < max_iterations && (active[0] || active[1]); ++it) {
    const BlockSums pq = sum_blocks(n, partial, [&](size_t begin, size_t end, BlockSums& sums) {
      multiply(a, p.data(), q.data(), begin, end, sums);
    });
    double alpha[2];
    for (int k = 0; k < 2; ++k) alpha[k] = active[k] ? rz[k] / pq[k] : 0.0;
    // One pass for x, r and both sums; its blocks write only their own rows.
    rr = sum_blocks(n, partial, [&](size_t begin, size_t end, BlockSums& sums) {
      double r0 = 0, r1 = 0, z0 = 0, z1 = 0;  // locals: the loop stays in registers
      for (size_t i = begin; i < end; ++i) {
        const size_t j = 2 * i;
        x[j] += alpha[0] * p[j], x[j + 1] += alpha[1] * p[j + 1];
        r[j] -= alpha[0] * q[j], r[j + 1] -= alpha[1] * q[j + 1];
        const double s0 = r[j] * r[j], s1 = r[j + 1] * r[j + 1];
        r0 += s0, r1 += s1;
        z0 += s0 * inverse_diagonal[i], z1 += s1 * inverse_diagonal[i];
      }
      sums = {r0, r1, z0, z1};
    });
    const double rz_new[2] = {rr[2], rr[3]};
    double beta[2];
    for (int k = 0; k < 2; ++k) {
      if (active[k] && !(rr[k] > tolerance * tolerance * b2[k])) active[k] = false;
      beta[k] = active[k] ? rz_new[k] / rz[k] : 0.0;
      rz[k] = rz_new[k];
    }
    const double keep[2] = {active[0] ? 1.0 : 0.0, active[1] ? 1.0 : 0.0};
    parallel_for(
        n,
        [&](size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i)
            for (size_t k = 0; k < 2; ++k)
              p[2 * i + k] = keep[k] * (r[2 * i + k] * inverse_diagonal[i] + beta[k] * p[2 * i + k]);
        },
        kBlock * kMinBlocksPerThread);
    if (on_iteration) on_iteration(it + 1);
  }
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return !active[0] && !active[1];
}

}  // namespace crestline
