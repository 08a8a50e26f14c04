// The paired solver of extremality smoothing (numerics/paired_cg.h) on a
// system large enough that every Gauss–Seidel sweep splits its colours over
// two threads: both solutions meet the tolerance on the true residual, and
// the iterates are the same bits for 1 and 2 threads.
#include "crestline/numerics/paired_cg.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "crestline/numerics/parallel.h"

using namespace crestline;

namespace {

// A triangulated n×n grid (6 neighbours per inner row), weights in [0.5, 3],
// masses in [0.5, 1.5] (times mass_scale(i, j) if given) and random signs σ
// per edge and field, as M − t L_σ. With consistent_signs, σ_pq = g_p g_q
// for random g = ±1 per row and field, as the smoothing's σ are away from
// umbilics: then the modes smooth up to σ are not frustrated, and where the
// masses are small the sweeps reduce them slowly.
SignedPairMatrix grid_system(uint32_t n, const std::function<double(uint32_t, uint32_t)>& mass_scale = {},
                             bool consistent_signs = false) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> weight(0.5, 3.0), mass(0.5, 1.5);
  std::uniform_int_distribution<uint32_t> mask(0, 3);
  const uint32_t rows = n * n;
  std::vector<std::array<uint32_t, 3>> edges;  // p, q, sign mask
  std::vector<double> w;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = 0; j < n; ++j) {
      const uint32_t p = i * n + j;
      if (j + 1 < n) edges.push_back({p, p + 1, mask(random)}), w.push_back(weight(random));
      if (i + 1 < n) edges.push_back({p, p + n, mask(random)}), w.push_back(weight(random));
      if (i + 1 < n && j + 1 < n) edges.push_back({p, p + n + 1, mask(random)}), w.push_back(weight(random));
    }
  if (consistent_signs) {
    std::vector<uint32_t> gauge(rows);
    for (uint32_t& g : gauge) g = mask(random);
    for (auto& e : edges) e[2] = gauge[e[0]] ^ gauge[e[1]];
  }
  SignedPairMatrix a;
  a.diagonal.resize(rows);
  for (double& d : a.diagonal) d = mass(random);
  if (mass_scale)
    for (uint32_t r = 0; r < rows; ++r) a.diagonal[r] *= mass_scale(r / n, r % n);
  a.offsets.assign(rows + 1, 0);
  for (const auto& e : edges) ++a.offsets[e[0] + 1], ++a.offsets[e[1] + 1];
  for (uint32_t r = 0; r < rows; ++r) a.offsets[r + 1] += a.offsets[r];
  a.columns.resize(a.offsets[rows]);
  a.weights.resize(a.offsets[rows]);
  std::vector<uint32_t> fill(a.offsets.begin(), a.offsets.end() - 1);
  for (size_t k = 0; k < edges.size(); ++k) {
    const uint32_t p = edges[k][0], q = edges[k][1], m = edges[k][2];
    a.diagonal[p] += w[k], a.diagonal[q] += w[k];
    a.columns[fill[p]] = q | m << 30, a.weights[fill[p]++] = -w[k];
    a.columns[fill[q]] = p | m << 30, a.weights[fill[q]++] = -w[k];
  }
  return a;
}

// Both fields' right-hand sides, uniform in [−1, 1].
std::vector<double> random_pairs(size_t rows, unsigned seed) {
  std::vector<double> b(2 * rows);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (double& v : b) v = value(random);
  return b;
}

// ‖b_k − A_k x_k‖ / ‖b_k‖ for field k, summed directly; with `rounded`, the
// off-diagonal entries as the solver stores them: σw / √(a_ii a_jj) rounded
// to float (the system scaled to a unit diagonal), scaled back.
double relative_residual(const SignedPairMatrix& a, const std::vector<double>& b, const std::vector<double>& x, int k,
                         bool rounded = true) {
  double rr = 0, bb = 0;
  for (size_t i = 0; i < a.rows(); ++i) {
    double y = a.diagonal[i] * x[2 * i + k];
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
      const uint32_t c = a.columns[e];
      const double sign = (c >> (30 + k)) & 1 ? -1.0 : 1.0;
      const double scale = std::sqrt(a.diagonal[i]) * std::sqrt(a.diagonal[c & SignedPairMatrix::kColumnMask]);
      const double w = rounded ? double{static_cast<float>(sign * a.weights[e] / scale)} * scale : sign * a.weights[e];
      y += w * x[2 * size_t{c & SignedPairMatrix::kColumnMask} + k];
    }
    rr += (b[2 * i + k] - y) * (b[2 * i + k] - y);
    bb += b[2 * i + k] * b[2 * i + k];
  }
  return std::sqrt(rr / bb);
}

}  // namespace

TEST_CASE("the paired Gauss-Seidel CG meets its tolerance and gives the same bits on 1 and 2 threads",
          "[numerics][threads]") {
  const SignedPairMatrix a = grid_system(300);  // 90,000 rows: every colour holds many 1,024-row chunks
  const std::vector<double> b = random_pairs(a.rows(), 5);
  const SignedPairSolver solver(a);
  CHECK(solver.colours() >= 3);
  CHECK(solver.colours() <= 8);
  // Masses ≈ a tenth of the weights' sums: most rows are slow, and the
  // restriction and the prolongation run on both threads as well. A grid's
  // aggregates form a grid, whose factor fills in: Ac is swept.
  CHECK(solver.coarse_rows() > 1000);
  CHECK_FALSE(solver.coarse_factored());

  const int before = max_threads();
  std::vector<double> x[2];
  int iterations[2] = {0, 0};
  for (int threads : {1, 2}) {
    set_max_threads(threads);
    std::vector<double> scratch = b;
    x[threads - 1].assign(2 * a.rows(), 0.0);
    REQUIRE(solver.solve(scratch, x[threads - 1], 1e-6, 500, [&](int it) { iterations[threads - 1] = it; }));
  }
  set_max_threads(before);
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    CHECK(relative_residual(a, b, x[0], k) <= 1.01e-6);
  }
  CHECK(iterations[0] == iterations[1]);
  CHECK(iterations[0] > 1);
  CHECK(x[0] == x[1]);
}

TEST_CASE("the paired solver's float weights leave its solution within the tolerance of the exact system's",
          "[numerics]") {
  const SignedPairMatrix a = grid_system(60);
  const std::vector<double> b = random_pairs(a.rows(), 7);
  const SignedPairSolver solver(a);
  std::vector<double> scratch = b, tight(2 * a.rows(), 0.0), loose(2 * a.rows(), 0.0);
  REQUIRE(solver.solve(scratch, tight, 1e-13, 500));
  scratch = b;
  int iterations = 0;
  REQUIRE(solver.solve(scratch, loose, 1e-6, 500, [&](int it) { iterations = it; }));
  // A work count, not a time: 9 iterations here.
  CHECK(iterations <= 10);
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    // The system the solver stores is solved exactly ...
    CHECK(relative_residual(a, b, tight, k) <= 1e-12);
    // ... and differs from the double one by float rounding (2⁻²⁴ relative
    // per entry): a residual far below the smoothing tolerance of 1e-6.
    CHECK(relative_residual(a, b, tight, k, false) <= 1e-7);
    CHECK(relative_residual(a, b, loose, k, false) <= 1.1e-6);
  }
}

TEST_CASE("the paired solver stops at the first iterate whose true residual meets the tolerance", "[numerics]") {
  // The true residual is formed (in the sweep that updates x) from the
  // iteration that a prediction from ⟨r̃, D r̃⟩ puts near the tolerance: one
  // iteration fewer leaves a field above it, the iterate the solver returns
  // meets it. Loose tolerances check the prediction from the first
  // iteration, tight ones that it starts the check early enough.
  const SignedPairMatrix a = grid_system(60);
  const std::vector<double> b = random_pairs(a.rows(), 9);
  const SignedPairSolver solver(a);
  for (const double tolerance : {0.3, 1e-2, 1e-4, 1e-6, 1e-8, 1e-10}) {
    INFO("tolerance " << tolerance);
    int iterations = 0;
    std::vector<double> scratch = b, x(2 * a.rows(), 0.0), early(2 * a.rows(), 0.0);
    REQUIRE(solver.solve(scratch, x, tolerance, 500, [&](int it) { iterations = it; }));
    REQUIRE(iterations >= 1);
    scratch = b;
    CHECK_FALSE(solver.solve(scratch, early, tolerance, iterations - 1));
    CHECK(std::max(relative_residual(a, b, early, 0), relative_residual(a, b, early, 1)) > tolerance);
    for (int k = 0; k < 2; ++k) {
      INFO("field " << k);
      CHECK(relative_residual(a, b, x, k) <= tolerance);
    }
  }
}

TEST_CASE("the paired solver reorders rows by breadth-first search over every component, isolated rows included",
          "[numerics]") {
  // Two grids and ten rows without neighbours (as the frozen boundary band
  // of the smoothing gives), the rows shuffled: the solver's locality order
  // must reach every row exactly once, whatever the input order.
  const SignedPairMatrix g = grid_system(40);
  const uint32_t grid_rows = static_cast<uint32_t>(g.rows()), rows = 2 * grid_rows + 10;
  std::vector<uint32_t> shuffled(rows);
  for (uint32_t i = 0; i < rows; ++i) shuffled[i] = i;
  std::mt19937 random(3);
  std::shuffle(shuffled.begin(), shuffled.end(), random);
  std::vector<uint32_t> input_of(rows);  // the unshuffled row each shuffled row holds
  for (uint32_t i = 0; i < rows; ++i) input_of[shuffled[i]] = i;
  SignedPairMatrix a;
  a.diagonal.resize(rows);
  a.offsets.assign(rows + 1, 0);
  for (uint32_t r = 0; r < rows; ++r) {
    const uint32_t i = input_of[r], row = i % grid_rows;
    const bool grid = i < 2 * grid_rows;
    a.diagonal[r] = grid ? g.diagonal[row] : 1.0 + i;
    a.offsets[r + 1] = a.offsets[r] + (grid ? g.offsets[row + 1] - g.offsets[row] : 0);
    for (uint32_t e = grid ? g.offsets[row] : 0; grid && e < g.offsets[row + 1]; ++e) {
      const uint32_t c = g.columns[e], column = (c & SignedPairMatrix::kColumnMask) + (i / grid_rows) * grid_rows;
      a.columns.push_back(shuffled[column] | (c & ~SignedPairMatrix::kColumnMask));
      a.weights.push_back(g.weights[e]);
    }
  }
  std::vector<double> b(2 * rows);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (double& v : b) v = value(random);
  const SignedPairSolver solver(a);
  std::vector<double> scratch = b, x(2 * rows, 0.0);
  REQUIRE(solver.solve(scratch, x, 1e-6, 500));
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    CHECK(relative_residual(a, b, x, k) <= 1.01e-6);
  }
  // An isolated row's residual is at most the whole one: |b − d x| ≤ 1e-6 ‖b‖.
  double bb[2] = {0, 0};
  for (size_t i = 0; i < b.size(); ++i) bb[i & 1] += b[i] * b[i];
  for (uint32_t r = 0; r < rows; ++r)
    if (input_of[r] >= 2 * grid_rows)
      for (int k = 0; k < 2; ++k)
        CHECK(std::abs(b[2 * r + k] - a.diagonal[r] * x[2 * r + k]) <= 1.01e-6 * std::sqrt(bb[k]));
}

// The solver iterates on field 1 negated at the rows of one handedness
// (paired_cg.cpp), field 0 as given: with the fields swapped, each field's
// solution must be the same bits as before, or the negation was not exact.
TEST_CASE("the paired solver gives each field the same bits with the fields swapped", "[numerics]") {
  for (const bool consistent : {false, true}) {
    INFO("consistent signs " << consistent);
    // Small masses where consistent: a coarse level, whose transfer follows the handedness too.
    const SignedPairMatrix a = grid_system(
        60, consistent ? [](uint32_t, uint32_t) { return 0.05; } : std::function<double(uint32_t, uint32_t)>{},
        consistent);
    SignedPairMatrix swapped = a;
    for (uint32_t& c : swapped.columns) c = (c & SignedPairMatrix::kColumnMask) | (c >> 30 & 1) << 31 | (c >> 31) << 30;
    const std::vector<double> b = random_pairs(a.rows(), 7), x0 = random_pairs(a.rows(), 8);
    const auto swap_pairs = [](std::vector<double> v) {
      for (size_t i = 0; i < v.size(); i += 2) std::swap(v[i], v[i + 1]);
      return v;
    };
    const SignedPairSolver solver(a), solver_swapped(swapped);
    CHECK(solver.coarse_rows() == solver_swapped.coarse_rows());
    if (consistent) CHECK(solver.coarse_rows() > 0);
    std::vector<double> scratch = b, x = x0, scratch_swapped = swap_pairs(b), x_swapped = swap_pairs(x0);
    int iterations = 0, iterations_swapped = 0;
    REQUIRE(solver.solve(scratch, x, 1e-8, 500, [&](int it) { iterations = it; }));
    REQUIRE(solver_swapped.solve(scratch_swapped, x_swapped, 1e-8, 500, [&](int it) { iterations_swapped = it; }));
    CHECK(iterations == iterations_swapped);
    const std::vector<double> back = swap_pairs(x_swapped);
    REQUIRE(back.size() == x.size());
    CHECK(std::memcmp(back.data(), x.data(), x.size() * sizeof(double)) == 0);  // the bits, signs of zeros too
  }
}

TEST_CASE("rows without entries whose start already solves them keep it to the bit", "[numerics]") {
  // The smoothing's frozen band: weight 0 leaves a vertex without entries,
  // and b = M x₀ there. The solver scales rows by √a_ii; it must not round
  // such a row's x₀ through the scaling (x₀ √d / √d).
  SignedPairMatrix a = grid_system(40);
  const uint32_t grid_rows = static_cast<uint32_t>(a.rows()), rows = grid_rows + 50;
  std::mt19937 random(13);
  std::uniform_real_distribution<double> value(-1.0, 1.0), mass(0.1, 3.0);
  for (uint32_t r = grid_rows; r < rows; ++r) a.diagonal.push_back(mass(random)), a.offsets.push_back(a.offsets.back());
  std::vector<double> x0(2 * rows), b = random_pairs(rows, 17);
  for (double& v : x0) v = value(random);
  for (uint32_t r = grid_rows; r < rows; ++r)
    for (int k = 0; k < 2; ++k) b[2 * r + k] = a.diagonal[r] * x0[2 * r + k];
  const SignedPairSolver solver(a);
  std::vector<double> scratch = b, x = x0;
  REQUIRE(solver.solve(scratch, x, 1e-6, 500));
  size_t kept = 0;
  for (uint32_t r = grid_rows; r < rows; ++r)
    for (int k = 0; k < 2; ++k) kept += x[2 * r + k] == x0[2 * r + k];
  CHECK(kept == 2 * size_t{rows - grid_rows});
  CHECK(relative_residual(a, b, x, 0) <= 1.01e-6);
}

TEST_CASE("greedy colouring gives each row the least colour its earlier neighbours lack, beyond 64 too", "[numerics]") {
  // Rows 0–69 all joined (a vertex of valence 69 and more: colours 0–69,
  // those from 64 on found past the 64 bits); row 70 joined to rows 64–69
  // (colours 64–69 only: 0), row 71 to rows 0–69 but 3 (3), row 72 to rows
  // 0–68 (all 64 bits taken, then 64–68: 69) and row 73 to rows 72 and 70,
  // listed in that order (colours 69 and 0: 1).
  std::vector<std::vector<uint32_t>> neighbours(74);
  const auto join = [&](uint32_t p, uint32_t q) { neighbours[p].push_back(q), neighbours[q].push_back(p); };
  for (uint32_t p = 0; p < 70; ++p)
    for (uint32_t q = p + 1; q < 70; ++q) join(p, q);
  for (uint32_t q = 64; q < 70; ++q) join(70, q);
  for (uint32_t q = 0; q < 70; ++q)
    if (q != 3) join(71, q);
  for (uint32_t q = 0; q < 69; ++q) join(72, q);
  join(73, 72), join(73, 70);
  SignedPairMatrix a;
  a.offsets.push_back(0);
  for (const std::vector<uint32_t>& row : neighbours) {
    for (const uint32_t q : row) a.columns.push_back(q | 2u << 30), a.weights.push_back(-1.0);
    a.offsets.push_back(static_cast<uint32_t>(a.columns.size()));
    a.diagonal.push_back(1.0 + static_cast<double>(row.size()));
  }
  const std::vector<uint32_t> colour = detail::greedy_colours(a);
  REQUIRE(colour.size() == 74);
  for (uint32_t p = 0; p < 70; ++p) CHECK(colour[p] == p);
  CHECK(colour[70] == 0);
  CHECK(colour[71] == 3);
  CHECK(colour[72] == 69);
  CHECK(colour[73] == 1);
  const SignedPairSolver solver(a);
  CHECK(solver.colours() == 70);
  const std::vector<double> b = random_pairs(a.rows(), 19);
  std::vector<double> scratch = b, x(2 * a.rows(), 0.0);
  REQUIRE(solver.solve(scratch, x, 1e-6, 500));
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    CHECK(relative_residual(a, b, x, k) <= 1.01e-6);
  }
}

namespace {

// ‖x − y‖ / ‖y‖ over field k.
double relative_difference(const std::vector<double>& x, const std::vector<double>& y, int k) {
  double dd = 0, yy = 0;
  for (size_t i = k; i < x.size(); i += 2) dd += (x[i] - y[i]) * (x[i] - y[i]), yy += y[i] * y[i];
  return std::sqrt(dd / yy);
}

// The grid with masses 10⁻³ of the weights' sums (R ≈ 10⁴, as on the
// dragon's finest regions) in a disc over a third of it: the slow rows.
SignedPairMatrix grid_with_fine_region(uint32_t n) {
  return grid_system(
      n,
      [n](uint32_t i, uint32_t j) {
        const double di = i - 0.5 * n, dj = j - 0.5 * n;
        return di * di + dj * dj < 0.1 * n * n ? 1e-3 : 1.0;
      },
      true);
}

}  // namespace

TEST_CASE("the two-level solve agrees with a tight one-level solve where rows are aggregated", "[numerics]") {
  const SignedPairMatrix a = grid_with_fine_region(80);
  const std::vector<double> b = random_pairs(a.rows(), 23);
  const SignedPairSolver two_level(a), one_level(a, false);
  REQUIRE(two_level.coarse_rows() > 0);
  CHECK(one_level.coarse_rows() == 0);
  // The disc (≈ 31 % of the rows) and slow rows outside it.
  CHECK(two_level.aggregated_rows() >= a.rows() / 4);
  CHECK(two_level.aggregated_rows() <= a.rows());
  std::vector<double> scratch = b, reference(2 * a.rows(), 0.0), x(2 * a.rows(), 0.0);
  REQUIRE(one_level.solve(scratch, reference, 1e-13, 2000));
  scratch = b;
  REQUIRE(two_level.solve(scratch, x, 1e-10, 500));
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    CHECK(relative_residual(a, b, reference, k) <= 1e-12);
    CHECK(relative_residual(a, b, x, k) <= 1e-10);
    // The error is at most κ times the residual (measured: 1.1e-10 and 2.1e-10).
    CHECK(relative_difference(x, reference, k) <= 1e-8);
  }
}

TEST_CASE("the coarse level cuts the iterations where rows are aggregated, to the same tolerance", "[numerics]") {
  // A work count, not a time: one-level 55, two-level 12 (measured; 19 with
  // four Gauss–Seidel sweeps for the coarse solve instead of the factor).
  const SignedPairMatrix a = grid_with_fine_region(80);
  const std::vector<double> b = random_pairs(a.rows(), 29);
  int iterations[2] = {0, 0};
  std::vector<double> x[2];
  for (const bool two_level : {false, true}) {
    const SignedPairSolver solver(a, two_level);
    std::vector<double> scratch = b;
    x[two_level].assign(2 * a.rows(), 0.0);
    REQUIRE(solver.solve(scratch, x[two_level], 1e-6, 1000, [&](int it) { iterations[two_level] = it; }));
  }
  CHECK(iterations[1] < iterations[0] / 2);
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    CHECK(relative_residual(a, b, x[1], k) <= 1e-6);
  }
}

TEST_CASE("no coarse level where under 1 % of the rows are slow: the one-level iterates to the bit", "[numerics]") {
  // A 100×100 grid with masses large enough (R ≈ 1) that no row is slow but
  // in a square of s×s rows with R ≈ 10⁴: 81 rows are under 1 % of 10,000,
  // 144 are not.
  for (const uint32_t side : {9u, 12u}) {
    INFO("square of " << side << " rows a side");
    const SignedPairMatrix a = grid_system(
        100,
        [side](uint32_t i, uint32_t j) { return i >= 40 && i < 40 + side && j >= 40 && j < 40 + side ? 1e-3 : 10.0; },
        true);
    const SignedPairSolver two_level(a), one_level(a, false);
    const std::vector<double> b = random_pairs(a.rows(), 31);
    std::vector<double> scratch = b, x(2 * a.rows(), 0.0), y(2 * a.rows(), 0.0);
    REQUIRE(two_level.solve(scratch, x, 1e-6, 500));
    scratch = b;
    REQUIRE(one_level.solve(scratch, y, 1e-6, 500));
    if (side == 9) {
      CHECK(two_level.coarse_rows() == 0);
      CHECK(two_level.aggregated_rows() == 0);
      CHECK(x == y);
    } else {
      CHECK(two_level.coarse_rows() > 0);
      CHECK(two_level.aggregated_rows() >= 100);
      CHECK(two_level.aggregated_rows() <= 144);
      CHECK(x != y);
    }
  }
}

TEST_CASE("the coarse level follows the signs: negating a row's unknown negates exactly its value", "[numerics]") {
  // The smoothing flips e(p) with the direction at p (its signs σ_pq in the
  // entries at p); aggregates take their signs from the entries, so every
  // iterate flips exactly there and nowhere else.
  const SignedPairMatrix a = grid_with_fine_region(40);
  SignedPairMatrix flipped = a;
  const std::vector<double> b = random_pairs(a.rows(), 37);
  std::vector<double> fb = b;
  std::vector<uint32_t> flip(a.rows());  // bit k: negate the row's unknown in field k
  std::mt19937 random(41);
  for (uint32_t& f : flip) f = random() % 4;
  for (uint32_t i = 0; i < a.rows(); ++i) {
    for (int k = 0; k < 2; ++k)
      if (flip[i] >> k & 1) fb[2 * i + k] = -fb[2 * i + k];
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
      const uint32_t j = a.columns[e] & SignedPairMatrix::kColumnMask;
      flipped.columns[e] ^= (flip[i] ^ flip[j]) << 30;
    }
  }
  const SignedPairSolver solver(a), flipped_solver(flipped);
  REQUIRE(solver.coarse_rows() > 0);
  CHECK(flipped_solver.coarse_rows() == solver.coarse_rows());
  std::vector<double> scratch = b, x(2 * a.rows(), 0.0), fx(2 * a.rows(), 0.0);
  int iterations = 0, flipped_iterations = 0;
  REQUIRE(solver.solve(scratch, x, 1e-6, 500, [&](int it) { iterations = it; }));
  scratch = fb;
  REQUIRE(flipped_solver.solve(scratch, fx, 1e-6, 500, [&](int it) { flipped_iterations = it; }));
  CHECK(flipped_iterations == iterations);
  size_t same = 0;
  for (uint32_t i = 0; i < a.rows(); ++i)
    for (int k = 0; k < 2; ++k) same += fx[2 * i + k] == (flip[i] >> k & 1 ? -x[2 * i + k] : x[2 * i + k]);
  CHECK(same == 2 * size_t{a.rows()});
}

namespace {

// A pair of symmetric matrices with a unit diagonal and one random sparse
// pattern (≈ `neighbours` entries a row to earlier rows, some far apart, so
// that the factor fills in; with `components`, rows i and j are joined only
// where i ≡ j modulo it), each entry's pair of values in ±[0.05, 1] /
// (2·neighbours + 1): diagonally dominant, so positive definite. Returns the
// entries below the diagonal by row, as detail::PairFactor::factor takes
// them, and both fields dense (dense[k][i·rows + j]).
struct PairSystem {
  std::vector<uint32_t> begin, columns;
  std::vector<double> values;
  std::vector<double> dense[2];
};

PairSystem random_pair_system(uint32_t rows, uint32_t neighbours, unsigned seed, uint32_t components = 1) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> magnitude(0.05, 1.0);
  std::uniform_int_distribution<uint32_t> coin(0, 1);
  PairSystem s;
  s.begin.push_back(0);
  for (int k = 0; k < 2; ++k) s.dense[k].assign(size_t{rows} * rows, 0.0);
  for (uint32_t i = 0; i < rows; ++i) {
    for (int k = 0; k < 2; ++k) s.dense[k][size_t{i} * rows + i] = 1.0;
    std::vector<uint32_t> earlier;
    for (uint32_t n = 0; n < neighbours && i >= components; ++n) {
      // The earlier rows of its component (row i's is i mod components).
      const uint32_t j =
          n == 0 ? i - components
                 : i % components + components * std::uniform_int_distribution<uint32_t>(0, i / components - 1)(random);
      if (std::find(earlier.begin(), earlier.end(), j) == earlier.end()) earlier.push_back(j);
    }
    for (const uint32_t j : earlier) {
      s.columns.push_back(j);
      for (int k = 0; k < 2; ++k) {
        const double v = (coin(random) ? 1.0 : -1.0) * magnitude(random) / (2 * neighbours + 1);
        s.values.push_back(v);
        s.dense[k][size_t{i} * rows + j] = s.dense[k][size_t{j} * rows + i] = v;
      }
    }
    s.begin.push_back(static_cast<uint32_t>(s.columns.size()));
  }
  return s;
}

// x = A⁻¹ b by Gaussian elimination with partial pivoting (A dense, n×n).
std::vector<double> dense_solve(std::vector<double> a, std::vector<double> b) {
  const size_t n = b.size();
  for (size_t c = 0; c < n; ++c) {
    size_t p = c;
    for (size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r * n + c]) > std::abs(a[p * n + c])) p = r;
    for (size_t k = 0; k < n; ++k) std::swap(a[c * n + k], a[p * n + k]);
    std::swap(b[c], b[p]);
    for (size_t r = c + 1; r < n; ++r) {
      const double f = a[r * n + c] / a[c * n + c];
      for (size_t k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
      b[r] -= f * b[c];
    }
  }
  std::vector<double> x(n);
  for (size_t c = n; c-- > 0;) {
    double s = b[c];
    for (size_t k = c + 1; k < n; ++k) s -= a[c * n + k] * x[k];
    x[c] = s / a[c * n + c];
  }
  return x;
}

}  // namespace

TEST_CASE("the coarse factor is L D Lᵀ of both fields' matrices, and its solve their inverse", "[numerics]") {
  const uint32_t rows = 150;
  const PairSystem s = random_pair_system(rows, 3, 43);
  detail::PairFactor factor;
  // Random couplings fill L in densely: refused by default, factored without the limit.
  CHECK_FALSE(factor.factor(s.begin, s.columns, s.values));
  CHECK(factor.refused_for_fill);
  CHECK(factor.rows() == 0);
  REQUIRE(factor.factor(s.begin, s.columns, s.values, 0));
  CHECK_FALSE(factor.refused_for_fill);
  REQUIRE(factor.rows() == rows);
  // Fill-in: L has more entries below the diagonal than A.
  CHECK(factor.columns.size() > s.columns.size());
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    // L D Lᵀ, formed densely from the factor's rows, is A.
    std::vector<double> l(size_t{rows} * rows, 0.0);
    for (uint32_t i = 0; i < rows; ++i) {
      l[size_t{i} * rows + i] = 1.0;
      for (uint32_t e = factor.begin[i]; e < factor.begin[i + 1]; ++e) {
        REQUIRE(factor.columns[e] < i);
        l[size_t{i} * rows + factor.columns[e]] = factor.values[2 * size_t{e} + k];
      }
    }
    double largest = 0;
    for (uint32_t i = 0; i < rows; ++i)
      for (uint32_t j = 0; j < rows; ++j) {
        double ldl = 0;
        for (uint32_t m = 0; m < rows; ++m)
          ldl += l[size_t{i} * rows + m] * l[size_t{j} * rows + m] / factor.inverse_pivot[2 * size_t{m} + k];
        largest = std::max(largest, std::abs(ldl - s.dense[k][size_t{i} * rows + j]));
      }
    CHECK(largest <= 1e-14);
  }
  // The solve against dense elimination, both fields at once.
  const std::vector<double> g = random_pairs(rows, 47);
  std::vector<double> y(2 * rows);
  factor.solve(g.data(), y.data());
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    std::vector<double> gk(rows);
    for (uint32_t i = 0; i < rows; ++i) gk[i] = g[2 * i + k];
    const std::vector<double> reference = dense_solve(s.dense[k], gk);
    double dd = 0, rr = 0;
    for (uint32_t i = 0; i < rows; ++i)
      dd += (y[2 * i + k] - reference[i]) * (y[2 * i + k] - reference[i]), rr += reference[i] * reference[i];
    CHECK(std::sqrt(dd / rr) <= 1e-14);
  }
}

TEST_CASE("the coarse solve is a symmetric positive definite operator, to rounding", "[numerics]") {
  // What keeps the two-level preconditioner symmetric positive definite:
  // ⟨u, S v⟩ = ⟨S u, v⟩ and ⟨v, S v⟩ > 0 for the solve S ≈ A⁻¹.
  const uint32_t rows = 400;
  const PairSystem s = random_pair_system(rows, 4, 53);
  detail::PairFactor factor;
  REQUIRE(factor.factor(s.begin, s.columns, s.values, 0));
  for (const unsigned seed : {59u, 61u, 67u}) {
    const std::vector<double> u = random_pairs(rows, seed), v = random_pairs(rows, seed + 100);
    std::vector<double> su(2 * rows), sv(2 * rows);
    factor.solve(u.data(), su.data());
    factor.solve(v.data(), sv.data());
    for (int k = 0; k < 2; ++k) {
      double usv = 0, suv = 0, vsv = 0, vv = 0;
      for (uint32_t i = 0; i < rows; ++i) {
        usv += u[2 * i + k] * sv[2 * i + k], suv += su[2 * i + k] * v[2 * i + k];
        vsv += v[2 * i + k] * sv[2 * i + k], vv += v[2 * i + k] * v[2 * i + k];
      }
      CHECK(std::abs(usv - suv) <= 1e-13 * vv);
      // A's eigenvalues lie in (0, 2) (Gershgorin): ⟨v, A⁻¹ v⟩ > ⟨v, v⟩ / 2.
      CHECK(vsv > 0.5 * vv);
    }
  }
}

TEST_CASE("the coarse factor refuses a matrix that is not positive definite and keeps nothing", "[numerics]") {
  // Unit diagonal, off-diagonal 0.9 in field 0 and 1.5 in field 1: the
  // second pivots 1 − 0.81 and 1 − 2.25 < 0. With −0.5 in field 1 instead:
  // 1 − 0.25, and L's entry is the off-diagonal one.
  detail::PairFactor factor;
  CHECK_FALSE(factor.factor({0, 0, 1}, {0}, {0.9, 1.5}));
  CHECK(factor.rows() == 0);
  CHECK(factor.begin.empty());
  REQUIRE(factor.factor({0, 0, 1}, {0}, {0.9, -0.5}));
  CHECK(factor.inverse_pivot[0] == 1.0);
  CHECK(factor.inverse_pivot[1] == 1.0);
  CHECK(factor.inverse_pivot[2] == Approx(1 / (1 - 0.81)).epsilon(1e-15));
  CHECK(factor.inverse_pivot[3] == Approx(1 / (1 - 0.25)).epsilon(1e-15));
  CHECK(factor.values[0] == 0.9);
  CHECK(factor.values[1] == -0.5);
}

TEST_CASE("the coarse solve splits into whole trees of the factor, the same bits on 1 and 2 threads",
          "[numerics][threads]") {
  // 60 components of 40 rows, interleaved: each group of the parallel solve
  // holds rows from all over.
  const uint32_t rows = 2400, components = 60;
  const PairSystem s = random_pair_system(rows, 3, 71, components);
  detail::PairFactor factor;
  REQUIRE(factor.factor(s.begin, s.columns, s.values));
  REQUIRE(factor.group_begin.size() == detail::PairFactor::kGroups + 1);
  REQUIRE(factor.group_begin.back() == rows);
  std::vector<uint32_t> group(rows);
  size_t filled = 0;
  for (uint32_t k = 0; k < detail::PairFactor::kGroups; ++k) {
    filled += factor.group_begin[k + 1] > factor.group_begin[k];
    for (uint32_t i = factor.group_begin[k]; i < factor.group_begin[k + 1]; ++i) {
      group[factor.order[i]] = k;
      if (i > factor.group_begin[k]) CHECK(factor.order[i] > factor.order[i - 1]);
    }
  }
  CHECK(filled == detail::PairFactor::kGroups);
  // Whole components in one group, and so every entry of L.
  for (uint32_t i = 0; i < rows; ++i) CHECK(group[i] == group[i % components]);
  size_t across = 0;
  for (uint32_t i = 0; i < rows; ++i)
    for (uint32_t e = factor.begin[i]; e < factor.begin[i + 1]; ++e) across += group[factor.columns[e]] != group[i];
  CHECK(across == 0);
  // Equal work (rows and entries) to within a component's.
  const size_t work = rows + factor.columns.size();
  for (uint32_t k = 0; k < detail::PairFactor::kGroups; ++k) {
    size_t mine = 0;
    for (uint32_t i = factor.group_begin[k]; i < factor.group_begin[k + 1]; ++i)
      mine += 1 + factor.begin[factor.order[i] + 1] - factor.begin[factor.order[i]];
    CHECK(std::abs(double(mine) - double(work) / detail::PairFactor::kGroups) <= 2.0 * work / components);
  }
  const std::vector<double> g = random_pairs(rows, 73);
  const int before = max_threads();
  std::vector<double> y[2];
  for (const int threads : {1, 2}) {
    set_max_threads(threads);
    y[threads - 1].assign(2 * rows, 0.0);
    factor.solve(g.data(), y[threads - 1].data());
  }
  set_max_threads(before);
  CHECK(y[0] == y[1]);
  // And the inverse of each field's matrix: A y = g.
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    double rr = 0, gg = 0;
    for (uint32_t i = 0; i < rows; ++i) {
      double ay = 0;
      for (uint32_t j = i % components; j < rows; j += components)
        ay += s.dense[k][size_t{i} * rows + j] * y[0][2 * j + k];
      rr += (ay - g[2 * i + k]) * (ay - g[2 * i + k]), gg += g[2 * i + k] * g[2 * i + k];
    }
    CHECK(std::sqrt(rr / gg) <= 1e-14);
  }
}

TEST_CASE("the coarse transfer built on 1 or 2 threads gives the same bits", "[numerics][threads]") {
  // Q's rows are counted and filled on every thread (paired_cg_coarse.cpp).
  const SignedPairMatrix a = grid_system(
      200, [](uint32_t i, uint32_t j) { return i % 12 < 6 && j % 12 < 6 ? 1e-3 : 10.0; }, true);
  const std::vector<double> b = random_pairs(a.rows(), 83);
  const int before = max_threads();
  std::vector<double> x[2];
  for (const int threads : {1, 2}) {
    set_max_threads(threads);
    const SignedPairSolver solver(a);
    REQUIRE(solver.coarse_rows() > 500);
    set_max_threads(1);
    std::vector<double> scratch = b;
    x[threads - 1].assign(2 * a.rows(), 0.0);
    REQUIRE(solver.solve(scratch, x[threads - 1], 1e-8, 500));
  }
  set_max_threads(before);
  CHECK(x[0] == x[1]);
}

TEST_CASE("the two-level solve gives the same bits on 1 and 2 threads where the coarse level has many components",
          "[numerics][threads]") {
  // Islands of 6×6 slow rows (R ≈ 10⁴) 12 rows apart: ≈ 280 coarse
  // components, the coarse solve's groups all filled.
  const SignedPairMatrix a = grid_system(
      200, [](uint32_t i, uint32_t j) { return i % 12 < 6 && j % 12 < 6 ? 1e-3 : 10.0; }, true);
  const SignedPairSolver solver(a);
  REQUIRE(solver.coarse_rows() > 500);
  CHECK(solver.coarse_factored());  // many small components: little fill
  const std::vector<double> b = random_pairs(a.rows(), 79);
  const int before = max_threads();
  std::vector<double> x[2];
  int iterations[2] = {0, 0};
  for (const int threads : {1, 2}) {
    set_max_threads(threads);
    std::vector<double> scratch = b;
    x[threads - 1].assign(2 * a.rows(), 0.0);
    REQUIRE(solver.solve(scratch, x[threads - 1], 1e-8, 500, [&](int it) { iterations[threads - 1] = it; }));
  }
  set_max_threads(before);
  CHECK(iterations[0] == iterations[1]);
  CHECK(x[0] == x[1]);
  for (int k = 0; k < 2; ++k) {
    INFO("field " << k);
    CHECK(relative_residual(a, b, x[0], k) <= 1.01e-8);
  }
}

TEST_CASE("the paired solver by its own rows gives solve()'s bits, step after step", "[numerics]") {
  const SignedPairMatrix a = grid_system(120);
  const std::vector<double> b = random_pairs(a.rows(), 7), x0 = random_pairs(a.rows(), 8);
  const SignedPairSolver solver(a);
  REQUIRE(solver.coarse_rows() > 0);
  const auto& input_row = solver.input_rows();
  REQUIRE(input_row.size() == a.rows());
  size_t moved = 0;  // rows the solver's order moves (by colour, then breadth first)
  for (size_t k = 0; k < a.rows(); ++k) moved += input_row[k] != k;
  CHECK(moved > a.rows() / 2);
  // Two steps as the smoothing takes them: the second from the first's result.
  std::vector<double> x = x0, ordered(2 * a.rows()), ordered_b(2 * a.rows());
  for (size_t k = 0; k < a.rows(); ++k)
    for (int f = 0; f < 2; ++f) ordered[2 * k + f] = x0[2 * size_t{input_row[k]} + f];
  for (int step = 0; step < 2; ++step) {
    std::vector<double> scratch = b;
    REQUIRE(solver.solve(scratch, x, 1e-8, 500));
    for (size_t k = 0; k < a.rows(); ++k)
      for (int f = 0; f < 2; ++f) ordered_b[2 * k + f] = b[2 * size_t{input_row[k]} + f];
    REQUIRE(solver.solve_in_solver_order(ordered_b, ordered, 1e-8, 500));
    size_t differing = 0;
    for (size_t k = 0; k < a.rows(); ++k)
      for (int f = 0; f < 2; ++f)
        differing += std::memcmp(&ordered[2 * k + f], &x[2 * size_t{input_row[k]} + f], sizeof(double)) != 0;
    CHECK(differing == 0);
  }
}

TEST_CASE("a coarse level whose factor loses a pivot is dropped whole", "[numerics]") {
  // A path of 6 rows without mass (a_ii = Σ|a_ij|, weights 4, signs that a
  // smooth mode follows): every row is slow, the aggregates are {0, 1} and
  // {2, 3, 4, 5}, and Ac, scaled, is [[1, −1], [−1, 1]] exactly (√4 = 2):
  // its second pivot is 0. The solver keeps no coarse level, as without one.
  SignedPairMatrix a;
  const uint32_t rows = 6;
  a.diagonal.assign(rows, 0.0);
  a.offsets.assign(rows + 1, 0);
  for (uint32_t r = 0; r + 1 < rows; ++r) ++a.offsets[r + 1], ++a.offsets[r + 2];
  for (uint32_t r = 0; r < rows; ++r) a.offsets[r + 1] += a.offsets[r];
  a.columns.resize(a.offsets[rows]);
  a.weights.resize(a.offsets[rows]);
  std::vector<uint32_t> fill(a.offsets.begin(), a.offsets.end() - 1);
  for (uint32_t r = 0; r + 1 < rows; ++r) {
    a.diagonal[r] += 4, a.diagonal[r + 1] += 4;
    a.columns[fill[r]] = r + 1, a.weights[fill[r]++] = -4;
    a.columns[fill[r + 1]] = r, a.weights[fill[r + 1]++] = -4;
  }
  const SignedPairSolver solver(a);
  CHECK(solver.coarse_rows() == 0);
  CHECK(solver.aggregated_rows() == 0);
  CHECK_FALSE(solver.coarse_factored());
}
