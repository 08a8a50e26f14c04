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
// The true residual is computed once ‖D r̃‖² (which tracks ‖r‖²) is within
// this factor of the limit.
constexpr double kCheckMargin = 4;
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

// Σ a_ij v_j over entries [begin, end) of a row, both fields.
inline void accumulate(const SignedPairMatrix& a, const double* v, uint32_t begin, uint32_t end, double& s0,
                       double& s1) {
  for (uint32_t e = begin; e < end; ++e) {
    const uint32_t c = a.columns[e];
    const double* sign = kSigns[c >> 30];
    const double* vj = v + 2 * size_t{c & SignedPairMatrix::kColumnMask};
    const double w = a.weights[e];
    s0 += w * sign[0] * vj[0];
    s1 += w * sign[1] * vj[1];
  }
}

// Calls body(begin, end, sums) over the rows of each colour in turn (last
// colour first if backward), in parallel within a colour: its rows are not
// neighbours. Chunks end at multiples of kBlock, each sums its rows in order
// and the chunks are summed in order: the same for any number of threads.
template <typename Body>
BlockSums sweep(const std::vector<uint32_t>& colour_begin_, bool backward, Sums& partial, const Body& body) {
  const size_t colours = colour_begin_.size() - 1;
  partial.clear();
  for (size_t step = 0; step < colours; ++step) {
    const size_t c = backward ? colours - 1 - step : step;
    const size_t begin = colour_begin_[c], end = colour_begin_[c + 1];
    if (begin == end) continue;
    const size_t first_chunk = begin / kBlock, chunks = (end - 1) / kBlock + 1 - first_chunk;
    const size_t base = partial.size();
    partial.resize(base + chunks, BlockSums{});
    parallel_for(
        chunks,
        [&](size_t from, size_t to) {
          for (size_t k = from; k < to; ++k) {
            const size_t chunk = first_chunk + k;
            body(std::max(begin, chunk * kBlock), std::min(end, (chunk + 1) * kBlock), partial[base + k]);
          }
        },
        kMinBlocksPerThread);
  }
  BlockSums total{};
  for (const BlockSums& sums : partial)
    for (size_t k = 0; k < total.size(); ++k) total[k] += sums[k];
  return total;
}

}  // namespace

SignedPairSolver::SignedPairSolver(SignedPairMatrix matrix) {
  const size_t n = matrix.rows();
  // Greedy colouring in row order: no two neighbours share a colour.
  std::vector<uint32_t> colour(n, 0), stamp;
  uint32_t colours = 0;
  for (size_t i = 0; i < n; ++i) {
    stamp.assign(colours + 1, 0);
    for (uint32_t e = matrix.offsets[i]; e < matrix.offsets[i + 1]; ++e) {
      const size_t j = matrix.columns[e] & SignedPairMatrix::kColumnMask;
      if (j < i) stamp[colour[j]] = 1;
    }
    uint32_t c = 0;
    while (stamp[c]) ++c;
    colour[i] = c;
    colours = std::max(colours, c + 1);
  }
  // Rows ordered by colour (a counting sort keeps row order within one).
  colour_begin_.assign(colours + 1, 0);
  for (size_t i = 0; i < n; ++i) ++colour_begin_[colour[i] + 1];
  for (uint32_t c = 0; c < colours; ++c) colour_begin_[c + 1] += colour_begin_[c];
  order_.resize(n);
  std::vector<uint32_t> position(n), fill(colour_begin_.begin(), colour_begin_.end() - 1);
  for (size_t i = 0; i < n; ++i) position[i] = fill[colour[i]]++, order_[position[i]] = static_cast<uint32_t>(i);
  // The permuted matrix, each row's entries as upper (later colours) | lower.
  // Weights first, then columns, each input array released once copied: at
  // most one and a half matrices are held, not two.
  a_.diagonal.resize(n);
  inverse_diagonal_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    a_.diagonal[k] = matrix.diagonal[order_[k]];
    inverse_diagonal_[k] = 1.0 / a_.diagonal[k];
  }
  std::vector<double>().swap(matrix.diagonal);
  // Calls entry(input entry, output entry) in the output's order.
  auto permute = [&](const auto& entry) {
    uint32_t next = 0;
    for (size_t k = 0; k < n; ++k) {
      const size_t i = order_[k];
      for (int lower = 0; lower < 2; ++lower)
        for (uint32_t e = matrix.offsets[i]; e < matrix.offsets[i + 1]; ++e) {
          const size_t j = matrix.columns[e] & SignedPairMatrix::kColumnMask;
          if ((colour[j] < colour[i]) == bool(lower)) entry(e, next++);
        }
    }
  };
  a_.weights.resize(matrix.weights.size());
  permute([&](uint32_t from, uint32_t to) { a_.weights[to] = matrix.weights[from]; });
  std::vector<double>().swap(matrix.weights);
  a_.columns.resize(matrix.columns.size());
  permute([&](uint32_t from, uint32_t to) {
    const uint32_t c = matrix.columns[from];
    a_.columns[to] = position[c & SignedPairMatrix::kColumnMask] | (c & ~SignedPairMatrix::kColumnMask);
  });
  a_.offsets.assign(n + 1, 0);
  lower_begin_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const size_t i = order_[k];
    uint32_t upper = 0;
    for (uint32_t e = matrix.offsets[i]; e < matrix.offsets[i + 1]; ++e)
      upper += colour[matrix.columns[e] & SignedPairMatrix::kColumnMask] > colour[i];
    lower_begin_[k] = a_.offsets[k] + upper;
    a_.offsets[k + 1] = a_.offsets[k] + (matrix.offsets[i + 1] - matrix.offsets[i]);
  }
}

// Conjugate gradients preconditioned by multicolour symmetric Gauss–Seidel,
// M = (D + L) D⁻¹ (D + U), with the rows ordered by colour (L: entries to
// earlier colours, U = Lᵀ). Eisenstat's trick: CG on Ã = (D + L)⁻¹ A (D +
// U)⁻¹, preconditioned by D (Ã ≈ D⁻¹), is PCG on A with M, and Ã v = t + (D
// + L)⁻¹ (v − D t) with t = (D + U)⁻¹ v: an iteration reads U once and L
// twice (the second time for the true residual r = (D + L) r̃, which the
// stopping rule uses), against A once for Jacobi, and needs about half the
// iterations. x is updated with t: x̃ = (D + U) x is never formed.
bool SignedPairSolver::solve(std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
                             const std::function<void(int)>& on_iteration) const {
  const SignedPairMatrix& a = a_;
  const std::vector<double>& inverse_diagonal = inverse_diagonal_;
  const size_t n = a.rows();
  std::vector<double> xp(2 * n), rt(2 * n), p(2 * n);
  for (size_t k = 0; k < n; ++k)
    for (int f = 0; f < 2; ++f)
      xp[2 * k + f] = x[2 * size_t{order_[k]} + f], rt[2 * k + f] = b[2 * size_t{order_[k]} + f];
  std::vector<double>& t = x;  // the caller's vectors serve as scratch
  std::vector<double>& u = b;
  Sums partial;
  const BlockSums b2 = sum_blocks(n, partial, [&](size_t begin, size_t end, BlockSums& sums) {
    for (size_t j = 2 * begin; j < 2 * end; ++j) sums[j & 1] += rt[j] * rt[j];
  });
  // r = b − A x, then r̃ = (D + L)⁻¹ r in place, colour by colour.
  BlockSums rr = sweep(colour_begin_, false, partial, [&](size_t begin, size_t end, BlockSums& sums) {
    for (size_t i = begin; i < end; ++i) {
      double r0 = rt[2 * i] - a.diagonal[i] * xp[2 * i], r1 = rt[2 * i + 1] - a.diagonal[i] * xp[2 * i + 1];
      double s0 = 0, s1 = 0;
      accumulate(a, xp.data(), a.offsets[i], a.offsets[i + 1], s0, s1);
      r0 -= s0, r1 -= s1;
      sums[0] += r0 * r0, sums[1] += r1 * r1;
      double l0 = 0, l1 = 0;
      accumulate(a, rt.data(), lower_begin_[i], a.offsets[i + 1], l0, l1);
      rt[2 * i] = (r0 - l0) * inverse_diagonal[i], rt[2 * i + 1] = (r1 - l1) * inverse_diagonal[i];
      sums[2] += rt[2 * i] * rt[2 * i] * a.diagonal[i], sums[3] += rt[2 * i + 1] * rt[2 * i + 1] * a.diagonal[i];
    }
  });
  double rz[2] = {rr[2], rr[3]};  // ⟨r̃, D r̃⟩ per field
  bool active[2];
  const double limit[2] = {tolerance * tolerance * b2[0], tolerance * tolerance * b2[1]};
  for (int k = 0; k < 2; ++k) {
    // As Eigen: a zero right-hand side has the solution 0.
    if (b2[k] == 0) {
      for (size_t i = 0; i < n; ++i) xp[2 * i + k] = 0;
      active[k] = false;
    } else {
      active[k] = rr[k] > limit[k];
    }
  }
  double beta[2] = {0, 0};
  for (int it = 0; it < max_iterations && (active[0] || active[1]); ++it) {
    const double keep[2] = {active[0] ? 1.0 : 0.0, active[1] ? 1.0 : 0.0};
    // Last colour first: p = D r̃ + β p, t = (D + U)⁻¹ p.
    sweep(colour_begin_, true, partial, [&](size_t begin, size_t end, BlockSums&) {
      for (size_t i = begin; i < end; ++i) {
        const double p0 = keep[0] * (rt[2 * i] * a.diagonal[i] + beta[0] * p[2 * i]);
        const double p1 = keep[1] * (rt[2 * i + 1] * a.diagonal[i] + beta[1] * p[2 * i + 1]);
        p[2 * i] = p0, p[2 * i + 1] = p1;
        double s0 = 0, s1 = 0;
        accumulate(a, t.data(), a.offsets[i], lower_begin_[i], s0, s1);
        t[2 * i] = (p0 - s0) * inverse_diagonal[i], t[2 * i + 1] = (p1 - s1) * inverse_diagonal[i];
      }
    });
    // First colour first: u = (D + L)⁻¹ (p − D t); Ã p = t + u.
    const BlockSums pq = sweep(colour_begin_, false, partial, [&](size_t begin, size_t end, BlockSums& sums) {
      for (size_t i = begin; i < end; ++i) {
        double l0 = 0, l1 = 0;
        accumulate(a, u.data(), lower_begin_[i], a.offsets[i + 1], l0, l1);
        const double d = a.diagonal[i];
        const double u0 = (p[2 * i] - d * t[2 * i] - l0) * inverse_diagonal[i];
        const double u1 = (p[2 * i + 1] - d * t[2 * i + 1] - l1) * inverse_diagonal[i];
        u[2 * i] = u0, u[2 * i + 1] = u1;
        sums[0] += p[2 * i] * (t[2 * i] + u0), sums[1] += p[2 * i + 1] * (t[2 * i + 1] + u1);
      }
    });
    double alpha[2];
    for (int k = 0; k < 2; ++k) alpha[k] = active[k] ? rz[k] / pq[k] : 0.0;
    // x += α t, r̃ −= α Ã p; sums: ‖D r̃‖², an estimate of ‖r‖², and ⟨r̃, D r̃⟩.
    const BlockSums estimate = sum_blocks(n, partial, [&](size_t begin, size_t end, BlockSums& sums) {
      for (size_t i = begin; i < end; ++i) {
        const size_t j = 2 * i;
        xp[j] += alpha[0] * t[j], xp[j + 1] += alpha[1] * t[j + 1];
        rt[j] -= alpha[0] * (t[j] + u[j]), rt[j + 1] -= alpha[1] * (t[j + 1] + u[j + 1]);
        const double d0 = a.diagonal[i] * rt[j], d1 = a.diagonal[i] * rt[j + 1];
        sums[0] += d0 * d0, sums[1] += d1 * d1;
        sums[2] += d0 * rt[j], sums[3] += d1 * rt[j + 1];
      }
    });
    // The stopping rule is on the true residual r = (D + L) r̃, one more
    // read of L, computed only once the estimate is near the tolerance.
    bool check = false;
    for (int k = 0; k < 2; ++k) check = check || (active[k] && estimate[k] <= kCheckMargin * limit[k]);
    if (check) {
      rr = sweep(colour_begin_, false, partial, [&](size_t begin, size_t end, BlockSums& sums) {
        for (size_t i = begin; i < end; ++i) {
          double l0 = 0, l1 = 0;
          accumulate(a, rt.data(), lower_begin_[i], a.offsets[i + 1], l0, l1);
          const double r0 = a.diagonal[i] * rt[2 * i] + l0, r1 = a.diagonal[i] * rt[2 * i + 1] + l1;
          sums[0] += r0 * r0, sums[1] += r1 * r1;
        }
      });
    }
    for (int k = 0; k < 2; ++k) {
      if (active[k] && check && !(rr[k] > limit[k])) active[k] = false;
      beta[k] = active[k] ? estimate[2 + k] / rz[k] : 0.0;
      rz[k] = estimate[2 + k];
    }
    if (on_iteration) on_iteration(it + 1);
  }
  for (size_t k = 0; k < n; ++k) x[2 * size_t{order_[k]}] = xp[2 * k], x[2 * size_t{order_[k]} + 1] = xp[2 * k + 1];
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return !active[0] && !active[1];
}

}  // namespace crestline
