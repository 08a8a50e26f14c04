#pragma once
// Two symmetric positive definite systems solved together, for extremality
// smoothing (paper §5.1): the κ_max and κ_min fields share the mass matrix
// and the cotan weights, and their matrices differ only in the signs σ_pq of
// off-diagonal entries. Conjugate gradients on both in lockstep read each
// matrix entry once for both fields, which is what a sparse matrix-vector
// product is limited by. The solver stores an entry as its column and
// σ_0 w / √(a_ii a_jj) in float, 8 bytes: with field 1's unknown negated at
// the rows of one handedness (found by a breadth-first search, so that
// σ_0 = σ_1 along its tree), both fields' entries are equal but for 0.2–2 %
// of them (the 1.1M bunny, the dragon, the bunny), whose rows are marked and
// whose floats carry a flip bit; negation is exact, so the iterates are the
// same bits (all shared meshes). Before: the pair (σ_0 w, σ_1 w) in float,
// 12 bytes (CLI at 1.1M, 1 thread, callgrind: smoothing 4.56 → 5.04 G
// instructions, last-level read misses 62.2 M → 52.8 M with a 32 MB cache;
// massif peak 260.9 → 250.4 MB). The system is scaled to a unit diagonal,
// so that no sweep reads a diagonal or its inverse: 32 of ≈ 340 bytes per
// row and iteration, and bunny 397 M → 379 M instructions, last-level
// misses −18 %, the same iterations on the bunny, 1.1M and the dragon. The
// system it solves differs from the double one by 2⁻²⁴ relative per entry,
// a residual below 10⁻⁷ where the smoothing stops at 10⁻⁶ (measured on the
// bunny, its 1.1M subdivision and the dragon: zero crossings against a 10⁻¹²
// double solve as with double weights, the same iterations).
//
// Why the iteration count grows under refinement although t ≈ h²: with
// Jacobi, a mode that is smooth (up to the signs σ) over a region gets the
// eigenvalue ≈ 1/(1 + R), R = t·Σ_q w_pq / m_p there, while rough modes
// reach 2; the condition number is ≈ 2(1 + R) for the largest R over any
// region big enough to carry such a mode. t is scaled by the *mean* edge
// length, R is ≈ 4 on an even mesh but larger where triangles are smaller
// than the mean, and refinement lets ever smaller such regions carry a mode:
// Lanczos estimates from the CG coefficients give κ ≈ 12.5 on the bunny (69k
// triangles, 22–25 iterations at 1e-6) and κ ≈ 33 on its 1-to-4 subdivision
// twice (1.1M, 34–46), bounded by the mesh's most refined region. The modes
// are small (2–4 vertices across): an additive coarse correction over signed
// aggregates of 32 vertices left κ unchanged; aggregates of 4 reach κ ≈ 8.8,
// at a coarse matrix a quarter of the fine one. Symmetric Gauss–Seidel
// over the whole mesh (rows in colour order, paired_cg.cpp) halves the
// iterations (bunny 23–25 → 11–12 per solve); block Gauss–Seidel in blocks
// of 1,024 rows (block Jacobi between them, 43 % of the entries) saved 8 %.
// Each colour's rows are in breadth-first order (6 % fewer cache misses at
// 1.1M); an iteration is two passes over the rows, one per sweep, that
// stream the matrix once and five vectors of the pair, so the iteration
// count is what is left to cut. What an iteration still cost was cut in
// three ways (paired_cg.cpp; callgrind of the 5 smoothing steps with a
// 4 MB last-level cache, bunny and 1.1M; the same iterations, 57 and 94,
// and 248 on the dragon): the true residual (the stopping rule's: one more
// gather of r̃ per entry of L) is formed only from the iteration whose
// residual, predicted from ⟨r̃, r̃⟩, its last reduction and its ratio to ‖r‖²
// at the last check (4.6–5.7 over the bunny's solves), is within 4× (in
// norm) of the limit: the same iterates, bunny 416.9 M → 397.5 M
// instructions; the unit diagonal (above): 379.2 M, and the two together
// at 1.1M 9.73 G → 8.65 G instructions, last-level misses 371 M → 320 M; t
// in float: misses 320 M → 296 M (bunny 4.53 M → 3.85 M) for 2 % more
// instructions. As landed (with the correction form that keeps the frozen
// band exact): 1.1M 9.73 G → 8.94 G instructions (−8 %), misses 371 M →
// 297 M (−20 %); bunny 416.9 M → 393.1 M (−6 %), 5.53 M → 4.08 M (−26 %);
// dragon 17.30 G → 15.35 G (−11 %), 657 M → 513 M (−22 %). Measured at
// 1.1M and dropped: SSOR with
// ω = 1.3 or 1.6 instead of 1 (the bench's two smoothings: 221 and 288
// iterations against 199); starting each step from the A-optimal
// combination of x_k and its last two differences (94 → 90: the first
// residual is ≈ 10⁻² of b, and four orders of magnitude remain to cut).
//
// Left to cut: the dragon (871k) takes 44–57 iterations per solve against
// 17–23 at 1.1M. R = t·Σ_q w_pq / m_p there has its 90th and 99th
// percentiles and maximum at 47, 128 and 3.3·10⁵ (1.1M: 6.6, 14, 3.2·10³;
// bunny: 7.1, 10, 144). Block symmetric Gauss–Seidel, measured outside
// this solver (2ff2dda's systems, each field alone in double, blocks
// solved exactly by Cholesky; iterations of the 5 bench steps, the larger
// field's per step, summed: bunny, 1.1M, dragon 57, 94, 248 with the point
// sweeps here): blocks grown from the strongest couplings |w_pq| / √(a_pp
// a_qq) above θ up to a cap of vertices, then coloured. Strongly coupled
// clusters alone do not carry the slow modes: θ = 0.45 puts 16 % of the
// dragon's vertices in blocks of ≤ 5 and gives 248 → 246. θ = 0.2 (90–97 %
// of the vertices in blocks) with caps 4, 8, 16, 32: bunny 41, 40, 39, 37;
// 1.1M 65, 58, 45, 46; dragon 180, 155, 127, 103. The same order with point
// sweeps (θ = 0.2, cap 8; a block's rows consecutive, in turn): 54, 85,
// 226. Exact blocks cost two triangular solves per sweep: at cap 32, 1.3–1.5
// strictly lower factor entries a row (vertex order in the block) besides
// 3.5–3.8 off-block entries, against 5.4–5.8 entries now, and a gather is
// 11 instructions an entry, about a third of an iteration's: an iteration
// would cost ≈ 1.5× (estimated), so ≈ −40 % on the dragon, −25 % at 1.1M
// and nothing on the bunny, before memory traffic. Built in this solver
// on 294cb6c and not kept: Eisenstat's trick in the variables scaled by
// each block's Cholesky factor C (Ĉ⁻¹ Â Ĉ⁻ᵀ has a unit block diagonal, so
// the recurrences here carry over; two triangular solves a block and
// sweep), θ = 0.2, cap 32, a block's rows consecutive, chunks of whole
// blocks. CLI defaults (3 steps), 1 thread, callgrind: iterations bunny
// 35 → 23, 1.1M 60 → 28, dragon 159 → 64, but an iteration costs 2.2–2.3×
// the point one (a row's fixed work, not its gathers, is most of an
// iteration, and the block solves add as much again) and the set-up grows
// by 0.8–1.2 times the old one: smoothing bunny 269 M → 393 M
// instructions, 1.1M 6.09 G → 6.91 G, dragon 10.12 G → 9.80 G. Blocks kept
// to trees of their couplings (no fill: one factor entry a column, no
// index loops) need 24, 39 and 119 iterations at 1.5× (bunny) to 1.9×
// (dragon, small blocks) an iteration: bunny 308 M, dragon 14.25 G. An
// iteration's cost, not the count, is what a block method must cut first.
//
// Two-level (multiplicative) preconditioner (paired_cg_coarse.cpp builds the
// coarse level; first built on 85d284e, branch solver-two-level, and rebuilt):
// the sweeps here as smoother around a coarse correction over aggregates of the
// slow rows. Forward sweep, coarse correction P Ac⁻¹ Pᵀ, backward sweep: in the
// Eisenstat variables the whole preconditioner is B̃⁻¹ = I + Q Ac⁻¹ Qᵀ with Q =
// L P (the other terms cancel: S + Sᵀ − Â = I), so an iteration keeps its two
// passes; the first gathers Q y into p, and after the second Qᵀ r̃ is gathered
// by coarse row and y = Ac⁻¹ Qᵀ r̃ formed, ⟨r̃, z⟩ = ⟨r̃, r̃⟩ + ⟨Qᵀ r̃, y⟩.
// Only rows with m < 0.1 d (R > 9; detail::is_slow, from the matrix: d −
// Σ|a_ij| < 0.1 d) are aggregated: roots and their strong slow neighbours
// (|â_ij| ≥ 0.08), then the rest joined to their strongest neighbour's
// aggregate; P = ±√d along each aggregate's tree, its sign following the
// entries σ (so flipping a row's sign flips exactly its value, as the smoothing
// promises). Ac from the double entries as a sum of terms ≥ 0 (positive
// definite however large R is), first solved by 4 serial symmetric
// Gauss–Seidel sweeps from 0 (2, 3 and 6 sweeps: dragon 70, 62 and 53
// iterations against 58, no fewer instructions), now factored (below). No coarse level where under 1 % of the rows are
// aggregated (the bunny): the iterates there are the one-level ones to the bit (CLI OBJ byte-identical with two_level =
// false and with main on the 1.1M, the dragon, feline and cessna). CLI defaults, 1 thread, callgrind of
// smooth_extremality against 2817f06: iterations 1.1M 23/19/18 → 15/12/12, dragon 57/55/47 → 23/19/16, bunny 12/12/11
// unchanged; instructions 1.1M 5.68 G → 4.69 G (−17 %), dragon 9.81 G → 6.51 G (−34 %; coarse solve 0.99 G, Qᵀ r̃ 0.31
// G, set-up 0.21 G), bunny 243.4 M → 247.4 M (+1.6 %: the test for slow rows, and aggregates too few for a coarse
// level). Line counts equal to main's on 54 meshes (classic, smooth, cad, glb, large and the 1.1M; 38 of them with
// other iterations, e.g. cad/crank 150 → 74, cgal-blade 105 → 31). Zero crossings against a 10⁻¹² solve (largest and
// mean move along the edge, in edge lengths, over both fields; crossings appearing or vanishing): 1.1M 0.0068 / 9·10⁻⁷,
// 6 → 0.0018 / 9·10⁻⁷, 0; dragon 0.036 / 2.3·10⁻⁶, 7 → 0.12 / 8.6·10⁻⁷, 4;
// moves above 0.01 edge 6 → 2 (0.12 where both ends are below 2·10⁻⁷ of the
// field's RMS, 0.019 below 1.2·10⁻³). Round-off and the discrete thresholds: no
// row of the 28 meshes with slow rows enough to aggregate (classic, cad, the
// dragon and the 1.1M) lies within 10⁻⁹ (relative) of either threshold, within
// 10⁻⁶ 1 row and 6 strength tests; so a margin would buy nothing. The iterates
// still depend on the preconditioner by tolerance amounts, as they do on the
// stopping iteration: where the lines are decided by round-off (cad/cessna)
// they differ under the invariance transforms, as main's do
// (tests/unit/pipeline/invariance_test.cpp). Also measured on the first branch:
// every row aggregated (1.1M 60 → 39 iterations but 5.68 → 6.60 G); smoothed
// aggregation (Q and Ac 2–4× denser; dragon 8.49 G); and here R > 4 (m <
// 0.2 d): bunny 35 → 28 iterations but 243 → 429 M.
//
// The coarse solve is exact: Ac = L D Lᵀ (detail::PairFactor), both fields
// in lockstep. Ac is sparse and far from connected (the dragon: 60,930 rows,
// 55 k entries below the diagonal, 19,334 components of up to 1,048 rows,
// 11,467 of one row); in the aggregates' breadth-first order L has 121 k
// (AMD would give 65 k: ≈ 1 % of the smoothing, not worth a permutation). A
// solve reads 242 k entries where the 4 sweeps read ≈ 825 k, and the
// preconditioner is the two-level one with an exact coarse solve (symmetric
// positive definite as before). Callgrind of smooth_extremality, CLI
// defaults, 1 thread, against 0ed13dc: dragon 6.51 G → 5.19 G (−20 %; coarse
// solve 0.99 G → 0.23 G, the factorisation 27 M), iterations 23/19/16 →
// 19/17/14; 1.1M 4.70 G → 4.65 G (15/12/12 both); bunny 248.2 M → 247.8 M
// (no coarse level). Line counts as before on all 121 outputs of the shared
// meshes and the 1.1M (iterations 2348 → 2238 in all, fewer on 19, more on
// glb/VertexColorTest, 56 vertices: 12 → 13). Zero crossings against a
// 10⁻¹² double solve (largest and mean move, crossings appearing/vanishing):
// dragon 0.118 → 0.035 edge lengths, 7.8·10⁻⁷ → 7.0·10⁻⁷, 2/2 → 2/2; 1.1M
// 0.00182 → 0.00183 (one edge, its ends at 2·10⁻⁴ and 9·10⁻⁴ of the field's
// RMS), 9·10⁻⁷, 0/0 both. The factor's trees (Ac's components, which L
// never joins) are dealt to groups of equal work that run on the threads,
// each row's sums as on one thread: the same bits for any thread count; at 2
// threads the calling thread's share on the dragon 4.26 G → 3.13 G (3.23 G
// with the factor solved on one thread). WASM CLI, dragon, 1 thread,
// smoothing seconds in 5 alternated rounds (loaded machine): 2.41, 2.89,
// 2.90, 2.55, 2.62 → 1.48, 2.10, 2.35, 2.17, 1.91; output identical to native.
// Not measured: float coarse values, or Ac's columns beside its values,
// multicolour sweeps (the groups need no colours).
// Where the factor fills in (a coarse level that is one large mesh-like
// component: even meshes at larger time steps, cad/crank at the default),
// the sweeps stay (PairFactor::kMaxFill; L over Ac's rows and entries below
// its diagonal). At 1.5× the default time step, L/Ac was 9.8 at 1.1M (1.35 M
// entries) and 19 at 4.4M (11.0 M), and the factor made smoothing slower and
// the run's peak higher: CLI, 1 thread, factor → sweeps, the same 43 and 44
// iterations: 1.1M 1.33 → 1.15 s, 311 → 288 MB; 4.4M 8.41 → 5.53 s, 1,374 →
// 1,129 MB (the bench's re-smooth column, and its peak). The dragon at 1.5×
// (5.9) keeps the factor (1.33 s against 1.71 with no coarse level); crank
// at the default is swept again: 74 iterations against the factor's 49.
//
// Vectors in float beyond t, measured on 2dd3268 and not kept: U t, u and
// r̃ in float (48 instead of 56 bytes a row of vectors), callgrind of the
// CLI's solves on the bunny: instructions 192 M → 207 M (+7.6 %, the
// conversions), last-level misses 2.12 M → 0.99 M; the same iterations on
// the bunny, feline, 1.1M and dragon, zero crossings against a 10⁻¹² solve
// as close as the double solve's. But rounding U t or u is an error of the
// operator, not of the direction (as t's is), so r̃ drifts from the true
// residual: ≈ 3·10⁻⁸ ‖b‖ from a zero start (this solver then cannot
// reach 10⁻⁸), and the first smoothing step at 1.1M and on the dragon
// returned iterates above 10⁻⁶. Checking the true residual in double at
// the end and restarting (iterative refinement) meets it, at 1.1M in 64
// iterations instead of 60, on the dragon 170 instead of 159, plus a
// residual pass a solve (r̃ kept in double: 62 and 165, misses −42 % on
// the bunny): an estimated +15–20 % instructions for the misses saved.
// Wall clock decides against it (CLI `--stats` smoothing seconds, 1 thread,
// three alternated rounds on an idle machine, load 0.9–1.0): 1.1M 1.39–1.58
// s as landed against 1.69–2.42 with the check and restarts, the dragon
// 2.99–3.30 against 3.18–3.58. The streams are prefetched; the conversions
// cost more than the misses saved. Instructions guide this solve here.
//
// Measured on c03287c and not kept (branch solve-float-x): the correction
// x̂ − x̂₀ accumulated in float. It feeds nothing back into the iteration (r̃
// has its own recurrence), so the iterates and their count are the double
// ones and only the result moves, by ≈ 2⁻²⁴ of the correction: against
// the double correction, 5 steps, zero crossings of the smoothed fields on
// edges (largest / mean move in edge lengths, edges changing sides): dragon
// 4.7·10⁻⁴ / 8·10⁻⁸, 0; 1.1M 1.3·10⁻⁴ / 9·10⁻⁸, 0; bunny and feline ≤
// 4.8·10⁻⁵, 0; ridge, valley and crease counts unchanged on the 143 shared
// files. callgrind of the CLI on the dragon, 1 thread, 32 MB last-level
// cache: smoothing 5,212 → 5,275 M instructions, last-level read misses
// 54.5 → 50.3 M. But the rounding is outside the stopping test (from 0 a
// 10⁻⁶ solve ends at a true residual of 1.21·10⁻⁶, and none gets below
// 1.2·10⁻⁷), the invariance test's torus ×10⁻³ moves its lines 1.05·10⁻⁶
// diagonals (its limit 10⁻⁶), and the heap it saves is capped by the
// curvature stage's peak: at 1.1M, massif of the CLI at its defaults peaks
// at 180.3 MB inside compute_curvature either way, and at 1.5× the time
// step heaptrack gives 183.7 → 180.3 MB. r̃ in float besides (with the
// first residual's b − D x₀ kept in double): the same iterations, but on
// the dragon zero crossings move up to 0.020 edge (11 edges above 0.01)
// and 6 edges change sides: r̃'s rounding drifts from the true residual.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <vector>

#include "crestline/numerics/uninitialised.h"

namespace crestline {

/// A_k(i,i) = diagonal[i]; A_k(i,j) = ±weight for the off-diagonal entries of
/// a CSR pattern with both triangles stored, negated in A_k where bit k of
/// the entry's sign mask is set (k = 0, 1).
struct SignedPairMatrix {
  std::vector<uint32_t> offsets;          // rows + 1
  UninitialisedVector<uint32_t> columns;  // column | sign mask << 30
  UninitialisedVector<double> weights;    // (sized, then written in full: not zero-filled first)
  std::vector<double> diagonal;

  static constexpr uint32_t kColumnMask = (1u << 30) - 1;
  size_t rows() const { return diagonal.size(); }
};

namespace detail {
/// A matrix entry of the solver's parts: one float, field 0's value, with
/// bit 30 set where field 1's is its negation (0 in any float of magnitude
/// below 2, and the entries of the unit-diagonal system are below 1).
constexpr uint32_t kFlipBit = uint32_t{1} << 30;
inline float stored_entry(float value, bool flip) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  bits |= flip ? kFlipBit : 0;
  float stored;
  std::memcpy(&stored, &bits, sizeof stored);
  return stored;
}
/// Field 0's value of a stored entry; `flip`: whether field 1's is its negation.
inline float entry_value(float stored, bool& flip) {
  uint32_t bits;
  std::memcpy(&bits, &stored, sizeof bits);
  flip = (bits & kFlipBit) != 0;
  bits &= ~kFlipBit;
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// Whether the sweeps smooth a row slowly, so that it takes part in the
/// coarse level: its diagonal exceeds the sum of its off-diagonal magnitudes
/// (`excess`) by less than a tenth of the diagonal (in the smoothing, m <
/// 0.1 d: R = t Σ_q w_pq / m_p > 9).
inline bool is_slow(double diagonal, double excess, bool has_entries) { return has_entries && excess < 0.1 * diagonal; }
/// The fewest aggregated rows of `rows` for which there is a coarse level (1 %).
inline size_t min_aggregated(size_t rows) { return (rows + 99) / 100; }

/// Greedy colouring in row order: each row takes the least colour that none
/// of its earlier neighbours (columns below its row) has.
std::vector<uint32_t> greedy_colours(const SignedPairMatrix& a);

/// A = L D Lᵀ for a pair of symmetric positive definite matrices with one
/// pattern and a unit diagonal (the coarse level's Ac, one per field), both
/// factored in lockstep. L's entries below the diagonal are kept by row,
/// (column, field 0, field 1), and D⁻¹ per field.
struct PairFactor {
  std::vector<uint32_t> begin, columns;
  std::vector<double> values, inverse_pivot;
  // The rows by group (group_begin: kGroups + 1 offsets), ascending within
  // one: each group whole trees of the elimination forest, which share no
  // entry of L, so the groups are solved on any threads in any order, each
  // row's arithmetic the same.
  static constexpr uint32_t kGroups = 16;
  std::vector<uint32_t> order, group_begin;

  size_t rows() const { return inverse_pivot.size() / 2; }
  /// The most entries L may have, per row and entry of A below the
  /// diagonal, by default (paired_cg_coarse.cpp says why).
  static constexpr size_t kMaxFill = 8;
  /// Factors A given by its entries below the diagonal by row (row_begin:
  /// rows + 1 offsets), each a pair (field 0, field 1). False, and nothing
  /// kept, if a pivot is not positive, or if L would have more than
  /// max_fill · (rows + A's entries below the diagonal) entries (then
  /// refused_for_fill is set).
  bool factor(const std::vector<uint32_t>& row_begin, const std::vector<uint32_t>& row_columns,
              const std::vector<double>& row_values, size_t max_fill = kMaxFill);
  bool refused_for_fill = false;
  /// y = A⁻¹ g for both fields (pairs interleaved as the solver's vectors);
  /// the groups in parallel where there are threads, the same bits.
  void solve(const double* g, double* y) const;
};
}  // namespace detail

/// Conjugate gradients on both systems, preconditioned by multicolour
/// symmetric Gauss–Seidel (paired_cg.cpp), with a coarse correction between
/// its two sweeps where enough rows qualify (see above).
class SignedPairSolver {
 public:
  /// two_level = false leaves the coarse level out (one-level sweeps only).
  /// checkpoint, if set, is called between the set-up's parts (a tenth of a
  /// second apart on the dragon's 437k rows) and may throw to abandon it.
  explicit SignedPairSolver(SignedPairMatrix matrix, bool two_level = true,
                            const std::function<void()>& checkpoint = {});

  /// x (2 values per row, interleaved: x[2i+k]) holds the guess on entry;
  /// b is overwritten (the solver uses it as scratch: one vector less).
  /// Each system stops at relative residual `tolerance` (‖b − Ax‖ ≤
  /// tolerance·‖b‖, as Eigen's CG). Returns false if either has not converged
  /// within max_iterations; x then holds the last iterates. on_iteration, if
  /// set, is called after every iteration with its number (from 1) and may
  /// throw to abandon the solve.
  bool solve(std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
             const std::function<void(int iteration)>& on_iteration = {}) const;
  /// solve() with b and x by the solver's rows (x[2k + f] is input row
  /// input_rows()[k]'s), for a caller that solves several times: the same
  /// arithmetic without the gather and scatter through the permutation that
  /// solve() does on each call (the rows' order is random to the input's).
  bool solve_in_solver_order(std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
                             const std::function<void(int iteration)>& on_iteration = {}) const;
  /// The input row of each of the solver's rows.
  const UninitialisedVector<uint32_t>& input_rows() const { return order_; }

  /// The colours of the Gauss–Seidel sweeps (no two neighbours share one).
  size_t colours() const { return colour_begin_.size() - 1; }
  /// Rows of the coarse level (one per aggregate); 0 without one.
  size_t coarse_rows() const {
    return coarse_factor_.rows() ? coarse_factor_.rows() : coarse_begin_.empty() ? 0 : coarse_begin_.size() - 1;
  }
  /// Whether the coarse level is solved exactly (its factor) rather than by sweeps.
  bool coarse_factored() const { return coarse_factor_.rows() > 0; }
  /// Rows of the fine level in some aggregate.
  size_t aggregated_rows() const { return aggregated_; }

 private:
  // The coarse level's aggregates, by the solver's rows, and the roots of
  // Ac's diagonal; empty without a coarse level.
  struct Aggregation {
    std::vector<uint32_t> aggregate;  // of each row, or none
    std::vector<uint8_t> flips;       // bit k: the row's value in field k's column of P is negative
    std::vector<double> coarse_root;  // √Ac_cc per field
    // Ac scaled to a unit diagonal, its entries below the diagonal by row
    // (rows + 1 offsets; pairs per field): factored once Q is built.
    std::vector<uint32_t> lower_begin, lower_columns;
    std::vector<double> lower_values;
  };
  // Aggregates the slow rows and builds Ac from the input matrix (by input
  // row), before the permuted matrix exists: the two are never held beside
  // the aggregation's work (paired_cg_coarse.cpp). `pause` is called between
  // its passes (a chance to cancel).
  Aggregation build_coarse_matrix(const SignedPairMatrix& matrix, const UninitialisedVector<double>& excess,
                                  const std::vector<uint32_t>& bfs_order, const UninitialisedVector<uint32_t>& position,
                                  const std::function<void()>& pause);
  // Q = L P and Qᵀ from the permuted float matrix, once the input is
  // released, and Ac factored (or kept for sweeps) beside Qᵀ's transpose;
  // false, and no coarse level, if a pivot is not positive.
  bool build_coarse_transfer(Aggregation& aggregation);

  // One part of the permuted matrix (rows in colour order) by row: row k's
  // entries are [begin[k], begin[k + 1]), each its column and σ_0 w /
  // √(a_ii a_jj) rounded to float, field 1's value the same in the rows'
  // handedness (handed_) or, where mixed[k] and bit 30 of the float is set,
  // its negation (paired_cg.cpp).
  struct Part {
    UninitialisedVector<uint32_t> begin, columns;
    UninitialisedVector<float> weights;
    UninitialisedVector<uint8_t> mixed;
  };
  Part upper_, lower_;  // the entries to later colours, to earlier ones
  // The arrays below and the parts above are written in full once sized:
  // not zero-filled first (at 1.1M, 64 MB that the set-up wrote twice).
  UninitialisedVector<double> diagonal_;  // A(i,i)
  UninitialisedVector<uint32_t> order_;   // the input row of each row of the solver's
  UninitialisedVector<uint8_t> handed_;   // 1 where the solver iterates on −x₁ (paired_cg.cpp)
  bool representable_ = true;             // every entry below 2 in magnitude
  std::vector<uint32_t> colour_begin_;
  // √A(i,i) by input row (the input's neighbours are near in memory): the
  // solver works on the system scaled to a unit diagonal. Kept until the
  // entries are scaled; the solves and Q take the roots of diagonal_.
  UninitialisedVector<double> roots_;
  // The coarse level (empty without one), scaled to a unit diagonal per field:
  // Q = L P by fine row (q_begin_, n + 1 offsets) and by coarse row
  // (qt_begin_), entries (column, field 0, field 1); Ac factored.
  std::vector<uint32_t> q_begin_, q_columns_, qt_begin_, qt_rows_;
  std::vector<float> q_values_, qt_values_;
  detail::PairFactor coarse_factor_;
  // Where the factor would fill in too much, Ac itself by row instead
  // (coarse_begin_: rows + 1 offsets; each row's entries to earlier rows
  // first, up to coarse_upper_begin_[c]), solved by kCoarseSweeps symmetric
  // Gauss–Seidel sweeps from 0: a fixed symmetric positive definite
  // approximation of Ac⁻¹.
  std::vector<uint32_t> coarse_begin_, coarse_upper_begin_, coarse_columns_;
  std::vector<double> coarse_values_;
  // Ac's full rows for the sweeps, from its entries below the diagonal.
  void keep_coarse_rows(const std::vector<uint32_t>& lower_begin, const std::vector<uint32_t>& lower_columns,
                        const std::vector<double>& lower_values);
  // y ≈ Ac⁻¹ g, both fields: the factor's solve or the sweeps.
  void coarse_solve(const double* g, double* y) const;
  // solve()'s body; x and b by input row if `permuted`, else by the solver's.
  bool solve_rows(std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
                  const std::function<void(int iteration)>& on_iteration, bool permuted) const;
  size_t aggregated_ = 0;
};

}  // namespace crestline
