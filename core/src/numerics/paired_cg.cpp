#include "crestline/numerics/paired_cg.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "crestline/numerics/parallel.h"
#include "crestline/numerics/uninitialised.h"

namespace crestline {
namespace {

// Rows per block of the reductions: each block sums its rows in order, then
// the blocks are summed in order, so the dot products (and with them every
// iterate) are the same for any number of threads.
constexpr size_t kBlock = 1024;
// Blocks a thread takes at least; smaller systems stay on one thread.
constexpr size_t kMinBlocksPerThread = 4;
// Symmetric Gauss–Seidel sweeps of the coarse solve where Ac is not factored.
constexpr int kCoarseSweeps = 4;
// The true residual is formed from the iteration whose predicted squared
// residual is at most this many times the limit.
constexpr double kNearFactor = 16;

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

// The two fields' values of a row as one pair (x[2i], x[2i + 1]). Every
// operation is lane by lane, so the SSE2 form and the scalar one (WASM
// without SIMD) round identically: the same bits natively and in WASM.
#if defined(__SSE2__)
struct Pair {
  __m128d v;
  static Pair load(const double* p) { return {_mm_loadu_pd(p)}; }
  static Pair both(double a) { return {_mm_set1_pd(a)}; }
  static Pair of(double a, double b) { return {_mm_set_pd(b, a)}; }
  // Two floats widened to doubles (exact).
  static Pair widen(const float* p) {
    return {_mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))))};
  }
  static Pair load(const float* p) { return widen(p); }
  // One float widened, in both lanes.
  static Pair dup(const float* p) {
    const __m128 f = _mm_load_ss(p);
    return {_mm_cvtps_pd(_mm_unpacklo_ps(f, f))};
  }
  // √a in both lanes (correctly rounded, as std::sqrt; no errno to set).
  static Pair root_both(double a) { return {_mm_sqrt_pd(_mm_set1_pd(a))}; }
  void store(double* p) const { _mm_storeu_pd(p, v); }
  // Rounded to the nearest floats, as static_cast<float> does.
  void store(float* p) const { _mm_storel_pi(reinterpret_cast<__m64*>(p), _mm_cvtpd_ps(v)); }
};
inline Pair operator+(Pair a, Pair b) { return {_mm_add_pd(a.v, b.v)}; }
inline Pair operator-(Pair a, Pair b) { return {_mm_sub_pd(a.v, b.v)}; }
inline Pair operator*(Pair a, Pair b) { return {_mm_mul_pd(a.v, b.v)}; }
inline Pair operator/(Pair a, Pair b) { return {_mm_div_pd(a.v, b.v)}; }
#else
struct Pair {
  double a, b;
  static Pair load(const double* p) { return {p[0], p[1]}; }
  static Pair both(double x) { return {x, x}; }
  static Pair of(double x, double y) { return {x, y}; }
  static Pair widen(const float* p) { return {double{p[0]}, double{p[1]}}; }
  static Pair load(const float* p) { return widen(p); }
  static Pair dup(const float* p) { return {double{p[0]}, double{p[0]}}; }
  static Pair root_both(double x) { return both(std::sqrt(x)); }
  void store(double* p) const { p[0] = a, p[1] = b; }
  void store(float* p) const { p[0] = static_cast<float>(a), p[1] = static_cast<float>(b); }
};
inline Pair operator+(Pair x, Pair y) { return {x.a + y.a, x.b + y.b}; }
inline Pair operator-(Pair x, Pair y) { return {x.a - y.a, x.b - y.b}; }
inline Pair operator*(Pair x, Pair y) { return {x.a * y.a, x.b * y.b}; }
inline Pair operator/(Pair x, Pair y) { return {x.a / y.a, x.b / y.b}; }
#endif

// Σ a_ij v_j over entries [begin, end) of a row, both fields: weights holds
// each entry's pair (σ_0 w, σ_1 w).
template <typename Value>
inline Pair accumulate(const uint32_t* columns, const float* weights, const Value* v, uint32_t begin, uint32_t end) {
  Pair s = Pair::both(0.0);
  const float* w = weights + 2 * size_t{begin};
  for (const uint32_t *c = columns + begin, *last = columns + end; c != last; ++c, w += 2)
    s = s + Pair::widen(w) * Pair::load(v + 2 * size_t{*c});
  return s;
}

// Both fields' values of a stored entry of the solver's parts (detail::stored_entry).
inline Pair flipped_entry(const float* p) {
  bool flip;
  const double d = detail::entry_value(*p, flip);
  return Pair::of(d, flip ? -d : d);
}

// Σ a_ij v_j over entries [begin, end) of a row of a part, both fields; s,
// if given, is the sum so far (of the row's other part).
template <typename Value>
inline Pair row_sum(const uint32_t* columns, const float* weights, bool mixed, const Value* v, uint32_t begin,
                    uint32_t end, Pair s = Pair::both(0.0)) {
  const uint32_t* const last = columns + end;
  const float* w = weights + begin;
  if (!mixed) {
    for (const uint32_t* c = columns + begin; c != last; ++c, ++w)
      s = s + Pair::dup(w) * Pair::load(v + 2 * size_t{*c});
  } else {
    for (const uint32_t* c = columns + begin; c != last; ++c, ++w)
      s = s + flipped_entry(w) * Pair::load(v + 2 * size_t{*c});
  }
  return s;
}

// Σ a_ij v_j and Σ a_ij w_j over the same entries of a row of a part: each
// entry read once.
inline void row_sum2(const uint32_t* columns, const float* weights, bool mixed, const double* v, const double* w,
                     uint32_t begin, uint32_t end, Pair& sv, Pair& sw) {
  sv = Pair::both(0.0), sw = Pair::both(0.0);
  const uint32_t* const last = columns + end;
  const float* e = weights + begin;
  if (!mixed) {
    for (const uint32_t* c = columns + begin; c != last; ++c, ++e) {
      const Pair a = Pair::dup(e);
      sv = sv + a * Pair::load(v + 2 * size_t{*c});
      sw = sw + a * Pair::load(w + 2 * size_t{*c});
    }
  } else {
    for (const uint32_t* c = columns + begin; c != last; ++c, ++e) {
      const Pair a = flipped_entry(e);
      sv = sv + a * Pair::load(v + 2 * size_t{*c});
      sw = sw + a * Pair::load(w + 2 * size_t{*c});
    }
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

// Rows in breadth-first order, component by component: rows close in this
// order are close on the mesh, so a sweep over one colour reads its
// neighbours from a narrow band of each vector. Each colour's rows are kept
// in this order; the colouring itself stays greedy in input order (coloured
// in this order, the 10⁻⁶ solutions moved by tolerance amounts and the
// occt-motor lost a valley). callgrind's cache simulation of 5 smoothing
// steps at 1.1M (4 MB last-level cache): read misses 361 M → 339 M (−6 %),
// instructions +0.8 %, the same 94 iterations, results equal but for the
// order of the dot products' sums (≤ 5·10⁻¹⁵). An iteration streams ≈ 340
// bytes per row (≈ 2.95 M cache lines there of the 3.84 M missed), so no
// order can save much more.
//
// The same search gives each row its handedness (handed, by input row): 1
// where field 1's unknown is negated in the system the solver iterates on,
// so that along the search's tree every entry's two fields have one sign:
// σ_max σ_min is +1 across most edges once the frames' arbitrary
// orientations are undone (1.1M: 0.19 % of the entries differ, against 39 %
// as given; the dragon 0.64 %, the bunny 2.2 %). Negating an unknown
// negates exactly what depends on it, so the solution is the same, bit for
// bit (paired_cg.h); an entry is then one float for both fields.
std::vector<uint32_t> locality_order(const SignedPairMatrix& a, UninitialisedVector<uint8_t>& handed) {
  const size_t n = a.rows();
  std::vector<uint32_t> order(n);
  std::vector<uint8_t> seen(n, 0);
  handed.resize(n);
  size_t end = 0;
  for (uint32_t start = 0; start < n; ++start) {
    if (seen[start]) continue;
    seen[start] = 1, handed[start] = 0, order[end++] = start;
    for (size_t k = end - 1; k < end; ++k) {
      const uint32_t i = order[k];
      for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
        const uint32_t column = a.columns[e], j = column & SignedPairMatrix::kColumnMask;
        if (!seen[j])
          seen[j] = 1, handed[j] = static_cast<uint8_t>(handed[i] ^ ((column >> 30 ^ column >> 31) & 1)),
          order[end++] = j;
      }
    }
  }
  return order;
}

}  // namespace

// The colours below 64 that a row's earlier neighbours hold are kept as the
// bits of a word (no list to clear per row, no search through one); a row
// that finds all 64 taken (valence 64 or more) looks further with a list.
std::vector<uint32_t> detail::greedy_colours(const SignedPairMatrix& a) {
  const size_t n = a.rows();
  std::vector<uint32_t> colour(n), stamp;
  uint32_t colours = 0;
  for (size_t i = 0; i < n; ++i) {
    uint64_t taken = 0;
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
      const size_t j = a.columns[e] & SignedPairMatrix::kColumnMask;
      if (j < i && colour[j] < 64) taken |= uint64_t{1} << colour[j];
    }
    uint32_t c = 0;
    while (c < 64 && (taken >> c & 1)) ++c;
    if (c == 64) {
      stamp.assign(colours + 1, 0);
      for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
        const size_t j = a.columns[e] & SignedPairMatrix::kColumnMask;
        if (j < i) stamp[colour[j]] = 1;
      }
      while (stamp[c]) ++c;
    }
    colour[i] = c;
    colours = std::max(colours, c + 1);
  }
  return colour;
}

SignedPairSolver::SignedPairSolver(SignedPairMatrix matrix, bool two_level, const std::function<void()>& checkpoint) {
  const auto pause = [&] {
    if (checkpoint) checkpoint();
  };
  const size_t n = matrix.rows();
  // The colouring and the breadth-first order read only the matrix: each
  // serial, the two side by side where there are threads (the dragon:
  // ≈ 44 M instructions each).
  std::vector<uint32_t> colour, bfs_order;
  UninitialisedVector<uint8_t> handed;  // by input row
  run_side_by_side([&] { colour = detail::greedy_colours(matrix); },
                   [&] { bfs_order = locality_order(matrix, handed); });
  const uint32_t colours = n == 0 ? 0 : *std::max_element(colour.begin(), colour.end()) + 1;
  // Rows ordered by colour (a counting sort keeps the locality order within one).
  colour_begin_.assign(colours + 1, 0);
  for (size_t i = 0; i < n; ++i) ++colour_begin_[colour[i] + 1];
  for (uint32_t c = 0; c < colours; ++c) colour_begin_[c + 1] += colour_begin_[c];
  order_.resize(n);
  UninitialisedVector<uint32_t> position(n);
  pause();
  {
    std::vector<uint32_t> fill(colour_begin_.begin(), colour_begin_.end() - 1);
    for (const uint32_t i : bfs_order) position[i] = fill[colour[i]]++, order_[position[i]] = i;
  }
  diagonal_.resize(n);
  roots_.resize(n);
  parallel_for(n, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) diagonal_[k] = matrix.diagonal[order_[k]];
    for (size_t i = begin; i < end; ++i) roots_[i] = std::sqrt(matrix.diagonal[i]);
  });
  // The coarse level's test, what each row's diagonal exceeds its
  // off-diagonal magnitudes by, and with it Ac, from the input matrix
  // before the permuted one is made: the two matrices are held together
  // only with none of the aggregation's work (at 1.1M, massif of the CLI:
  // the set-up's peak 289 -> 261 MB of heap, the solves' own level).
  // Each part of the set-up ends with a chance to cancel: the locality
  // order, the coarse matrix and the fill below each take 20-60 ms at 1.1M
  // (1 thread), and the page answers a cancel only at these calls.
  pause();
  Aggregation aggregation;
  if (two_level) {
    UninitialisedVector<double> excess(n);
    std::atomic<size_t> slow_rows{0};
    parallel_for(n, [&](size_t begin, size_t end) {
      size_t slow = 0;
      for (size_t i = begin; i < end; ++i) {
        double off = 0;
        for (uint32_t e = matrix.offsets[i]; e < matrix.offsets[i + 1]; ++e) off += std::abs(matrix.weights[e]);
        excess[i] = std::max(0.0, matrix.diagonal[i] - off);
        slow += detail::is_slow(matrix.diagonal[i], excess[i], matrix.offsets[i + 1] > matrix.offsets[i]);
      }
      slow_rows += slow;
    });
    if (slow_rows >= detail::min_aggregated(n))
      aggregation = build_coarse_matrix(matrix, excess, bfs_order, position, pause);
    pause();
  }
  std::vector<uint32_t>().swap(bfs_order);
  // The permuted matrix in two parts, each by row: the entries to later
  // colours (upper), read by the backward sweep, and those to earlier ones
  // (lower), read by the forward sweep, each part's in input order. A
  // neighbour's colour is earlier exactly when its row comes before the
  // first of this row's colour. Each part streams alone: with both in one
  // array a row's two halves shared cache lines, and each sweep brought in
  // the whole matrix to read half of it (callgrind of the CLI at 1.1M, 1
  // thread, a 32 MB last-level cache: the solves' last-level read misses
  // 71.2 M → 57.7 M, the same instructions and bits). Each input row's
  // lower entries are counted first, so the offsets are known and the rows
  // filled on every thread (the same bits for any number: each entry is
  // computed alone).
  {
    UninitialisedVector<uint32_t> lower_count(n);
    parallel_for(n, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        uint32_t count = 0;
        for (uint32_t e = matrix.offsets[i]; e < matrix.offsets[i + 1]; ++e)
          count += colour[matrix.columns[e] & SignedPairMatrix::kColumnMask] < colour[i] ? 1 : 0;
        lower_count[i] = count;
      }
    });
    upper_.begin.resize(n + 1);
    lower_.begin.resize(n + 1);
    upper_.begin[0] = lower_.begin[0] = 0;
    for (size_t k = 0; k < n; ++k) {
      const size_t i = order_[k];
      upper_.begin[k + 1] = upper_.begin[k] + (matrix.offsets[i + 1] - matrix.offsets[i] - lower_count[i]);
      lower_.begin[k + 1] = lower_.begin[k] + lower_count[i];
    }
  }
  // Each entry as the parts store it, in input order: σ_0 w / √(a_ii a_jj)
  // rounded to float, with field 1's flip bit (detail::stored_entry), and
  // its column as the solver's row; then the double weights are released
  // before the parts are made, so that the set-up never holds the doubles
  // beside the parts (1.1M, bench: RSS at the set-up's peak 198 -> 185 MB
  // above the soup, the set-up 174 -> 212 M instructions; the same bits:
  // each entry is computed as it was in the fill, which now copies). The
  // columns are rewritten in place (the sign mask is in the float now).
  handed_.resize(n);
  std::atomic<bool> representable{true};
  UninitialisedVector<float> stored(matrix.weights.size());
  parallel_for(n, [&](size_t begin, size_t end) {
    uint32_t* const columns = matrix.columns.data();
    const uint32_t *const offsets = matrix.offsets.data(), *const at_position = position.data();
    const double *const weights = matrix.weights.data(), *const root = roots_.data();
    const uint8_t* const hand = handed.data();
    float* const out = stored.data();
    bool part_representable = true;
    for (size_t i = begin; i < end; ++i) {
      const uint32_t hand_i = hand[i];
      for (uint32_t e = offsets[i]; e < offsets[i + 1]; ++e) {
        const uint32_t column = columns[e], j = column & SignedPairMatrix::kColumnMask, to = at_position[j];
        // The product of the roots is the same both ways: A stays symmetric.
        // Rounding to float commutes with the sign.
        const float w = static_cast<float>(weights[e] / (root[i] * root[j]));
        part_representable = part_representable && std::abs(w) < 2.0f;
        // Field 0's value, and whether field 1's, in the rows' handedness, is its negation.
        const float value = column >> 30 & 1 ? -w : w;
        const uint32_t flip = (column >> 30 ^ column >> 31 ^ hand_i ^ hand[j]) & 1;
        out[e] = detail::stored_entry(value, flip != 0);
        columns[e] = to;
      }
    }
    if (!part_representable) representable = false;
  });
  UninitialisedVector<double>().swap(matrix.weights);
  UninitialisedVector<double>().swap(roots_);
  pause();
  for (Part* part : {&upper_, &lower_}) {
    part->columns.resize(part->begin[n]);
    part->weights.resize(part->begin[n]);
    part->mixed.resize(n);
  }
  // Raw pointers in locals: a store through one may alias anything that
  // lives in memory, the vectors' own pointers too.
  uint32_t* const part_columns[2] = {upper_.columns.data(), lower_.columns.data()};
  float* const part_weights[2] = {upper_.weights.data(), lower_.weights.data()};
  // In slices of rows with a chance to cancel after each: the fill was the
  // set-up's longest part (0.13 s at 1.1M on 1 thread, bench/ `cancel wait`).
  constexpr size_t kFillSlices = 4;
  constexpr size_t kFillAhead = 16;
  for (size_t slice = 0; slice < kFillSlices; ++slice) {
    const size_t first_row = n * slice / kFillSlices;
    parallel_for(n * (slice + 1) / kFillSlices - first_row, [&](size_t begin, size_t end) {
      const uint32_t *const offsets = matrix.offsets.data(), *const columns = matrix.columns.data();
      const uint32_t* const input_row = order_.data();
      const float* const entries = stored.data();
      const uint8_t* const hand = handed.data();
      uint32_t* const cols[2] = {part_columns[0], part_columns[1]};
      float* const values[2] = {part_weights[0], part_weights[1]};
      for (size_t k = first_row + begin; k < first_row + end; ++k) {
        // The input rows are read in the solver's order, random to theirs:
        // their offsets, colours and hands fetched 16 rows ahead, their entries 8 ahead.
        if (k + kFillAhead < n) {
          const size_t ahead = input_row[k + kFillAhead];
          __builtin_prefetch(&offsets[ahead]);
          __builtin_prefetch(&colour[ahead]);
          __builtin_prefetch(&hand[ahead]);
        }
        if (k + kFillAhead / 2 < n) {
          const uint32_t ahead = offsets[input_row[k + kFillAhead / 2]];
          __builtin_prefetch(&columns[ahead]);
          __builtin_prefetch(&entries[ahead]);
        }
        const size_t i = input_row[k];
        const uint32_t earlier = colour_begin_[colour[i]];
        uint32_t next[2] = {upper_.begin[k], lower_.begin[k]}, mixed[2] = {0, 0};
        for (uint32_t e = offsets[i]; e < offsets[i + 1]; ++e) {
          const uint32_t to = columns[e];
          const int lower = to < earlier ? 1 : 0;
          const uint32_t at = next[lower]++;
          bool flip;
          detail::entry_value(entries[e], flip);
          cols[lower][at] = to;
          values[lower][at] = entries[e];
          mixed[lower] |= flip ? 1u : 0u;
        }
        handed_[k] = hand[i];
        upper_.mixed[k] = static_cast<uint8_t>(mixed[0]), lower_.mixed[k] = static_cast<uint8_t>(mixed[1]);
      }
    });
    pause();
  }
  // An entry of magnitude 2 or more (not from a symmetric positive definite
  // matrix) would not hold the flip bit: such a system is not solved.
  representable_ = representable;
  // Not read beyond here: Q is built without the input beside it.
  matrix = SignedPairMatrix();
  if (!aggregation.aggregate.empty()) build_coarse_transfer(aggregation);
  aggregation = Aggregation();
}

namespace {

// y = Lᵀ⁻¹ D⁻¹ L⁻¹ g over rows row(0), …, row(count − 1), ascending, that
// L joins to no other rows: a gather by row forward, D⁻¹, then the backward
// solve by the same rows, each row's y scattered to the earlier rows it
// reaches once final. Each row's sums are in the same order for any such
// set of rows that holds it.
template <typename Row>
void solve_rows(const detail::PairFactor& factor, const Row& row, size_t count, const double* g, double* y) {
  const uint32_t *const begin = factor.begin.data(), *const columns = factor.columns.data();
  const double *const values = factor.values.data(), *const inverse_pivot = factor.inverse_pivot.data();
  for (size_t i = 0; i < count; ++i) {
    const size_t c = row(i);
    Pair s = Pair::load(g + 2 * c);
    for (uint32_t e = begin[c]; e < begin[c + 1]; ++e)
      s = s - Pair::load(values + 2 * size_t{e}) * Pair::load(y + 2 * size_t{columns[e]});
    s.store(y + 2 * c);
  }
  for (size_t i = 0; i < count; ++i) {
    const size_t c = row(i);
    (Pair::load(y + 2 * c) * Pair::load(inverse_pivot + 2 * c)).store(y + 2 * c);
  }
  for (size_t i = count; i-- > 0;) {
    const size_t c = row(i);
    const Pair yc = Pair::load(y + 2 * c);
    for (uint32_t e = begin[c]; e < begin[c + 1]; ++e) {
      double* const to = y + 2 * size_t{columns[e]};
      (Pair::load(to) - Pair::load(values + 2 * size_t{e}) * yc).store(to);
    }
  }
}

}  // namespace

// All rows in order on one thread (no index to look up); else the groups of
// whole trees on the threads.
void detail::PairFactor::solve(const double* g, double* y) const {
  if (max_threads() <= 1) {
    solve_rows(
        *this, [](size_t i) { return i; }, rows(), g, y);
    return;
  }
  parallel_for(
      kGroups,
      [&](size_t first, size_t last) {
        for (size_t k = first; k < last; ++k) {
          const uint32_t* const rows_of = order.data() + group_begin[k];
          solve_rows(
              *this, [rows_of](size_t i) { return rows_of[i]; }, group_begin[k + 1] - group_begin[k], g, y);
        }
      },
      1);
}

// The factor's solve, or symmetric Gauss–Seidel sweeps on Ac (unit
// diagonal) from y = 0 where it filled in too much: a fixed number of them
// is a symmetric positive definite approximation of Ac⁻¹, so the
// preconditioner stays symmetric positive definite. Serial.
void SignedPairSolver::coarse_solve(const double* g, double* y) const {
  if (coarse_factor_.rows() > 0) return coarse_factor_.solve(g, y);
  const size_t rows = coarse_rows();
  const uint32_t *const begin = coarse_begin_.data(), *const upper = coarse_upper_begin_.data();
  const uint32_t* const columns = coarse_columns_.data();
  const double* const values = coarse_values_.data();
  const auto relax = [=](size_t c, uint32_t end) {
    Pair s = Pair::load(g + 2 * c);
    for (uint32_t e = begin[c]; e < end; ++e)
      s = s - Pair::load(values + 2 * size_t{e}) * Pair::load(y + 2 * size_t{columns[e]});
    s.store(y + 2 * c);
  };
  for (int sweep = 0; sweep < kCoarseSweeps; ++sweep) {
    // The first forward sweep reads only earlier rows: y is 0 beyond.
    for (size_t c = 0; c < rows; ++c) relax(c, sweep == 0 ? upper[c] : begin[c + 1]);
    for (size_t c = rows; c-- > 0;) relax(c, begin[c + 1]);
  }
}

// Conjugate gradients preconditioned by multicolour symmetric Gauss–Seidel,
// M = (D + L) D⁻¹ (D + U), with the rows ordered by colour (L: entries to
// earlier colours, U = Lᵀ). Eisenstat's trick: CG on Ã = (D + L)⁻¹ A (D +
// U)⁻¹, preconditioned by D (Ã ≈ D⁻¹), is PCG on A with M, and Ã v = t + (D
// + L)⁻¹ (v − D t) with t = (D + U)⁻¹ v: an iteration reads U once and L
// once, against A once for Jacobi, and needs about half the iterations. x
// is updated with t: x̃ = (D + U) x is never formed. An iteration is two
// passes over the rows, one per sweep: α comes out of the first, so the
// second also updates x and r̃ and, near the tolerance, forms the true
// residual r = (D + L) r̃ that the stopping rule uses (before: three passes,
// and a fourth near the tolerance; callgrind, the bench's bunny solves: 858
// M → 830 M instructions, 737 M with the locals below, the same iterations).
// The solver works on Â = S A S, S = diag(1 / √A(i,i)), whose diagonal is
// 1: with D = I the sweeps read no diagonal and multiply by none (x̂ = S⁻¹
// x and b̂ = S b on the way in, x = S x̂ out; the stopping rule's residual is
// r = S⁻¹ r̂). PCG with the Gauss–Seidel M is the same method on either.
// With a coarse level, CG on Ã is preconditioned by B̃⁻¹ = I + Q Ac⁻¹ Qᵀ
// instead of I (paired_cg.h), the same two passes an iteration.
// It iterates on the correction to the caller's x₀, whose first residual is
// formed unscaled: a row with r = 0 and no entries (the smoothing's frozen
// band, b = M x₀) keeps x₀ to the bit, not x₀ √d / √d.
bool SignedPairSolver::solve(std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
                             const std::function<void(int)>& on_iteration) const {
  return solve_rows(b, x, tolerance, max_iterations, on_iteration, true);
}

bool SignedPairSolver::solve_in_solver_order(std::vector<double>& b, std::vector<double>& x, double tolerance,
                                             int max_iterations, const std::function<void(int)>& on_iteration) const {
  return solve_rows(b, x, tolerance, max_iterations, on_iteration, false);
}

bool SignedPairSolver::solve_rows(std::vector<double>& b, std::vector<double>& x, double tolerance, int max_iterations,
                                  const std::function<void(int)>& on_iteration, bool permuted) const {
  const size_t n = diagonal_.size();
  const uint32_t* const input_row = permuted ? order_.data() : nullptr;
  // xp and rt are written before they are read: not zeroed first
  // (callgrind at 1.1M: 32 bytes a row and solve less to write).
  UninitialisedVector<double> xp(2 * n), rt(2 * n);
  // ut (U t), t and the correction in xp start at 0: the first iteration
  // reads none of them but adds to those zeros as any other would (at 1.1M,
  // 22 MB a solve not zero-filled first).
  UninitialisedVector<double> ut(2 * n);
  UninitialisedVector<float> tf(2 * n);
  std::vector<double>& u = b;  // the caller's vector serves as scratch: S⁻¹ x₀ first
  if (!representable_) return false;
  // Field 1 negated in the rows of the other handedness (locality_order).
  parallel_for(n, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const size_t i = input_row ? input_row[k] : k;
      xp[2 * k] = x[2 * i], rt[2 * k] = b[2 * i];
      xp[2 * k + 1] = handed_[k] ? -x[2 * i + 1] : x[2 * i + 1];
      rt[2 * k + 1] = handed_[k] ? -b[2 * i + 1] : b[2 * i + 1];
    }
  });
  parallel_for(n, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) (Pair::load(&xp[2 * k]) * Pair::root_both(diagonal_[k])).store(&u[2 * k]);
  });
  Sums partial;
  const BlockSums b2 = sum_blocks(n, partial, [&](size_t begin, size_t end, BlockSums& sums) {
    for (size_t j = 2 * begin; j < 2 * end; ++j) sums[j & 1] += rt[j] * rt[j];
  });
  // Raw pointers, captured by value, and copied into locals by the two
  // sweeps of every iteration: a store through Pair may alias anything, so
  // the compiler reloads whatever sits in memory, the closure's copies too,
  // once per row (bunny, solve: 830 M → 737 M instructions).
  const double* const diagonal = diagonal_.data();
  const uint32_t *const upper_begin = upper_.begin.data(), *const upper_columns = upper_.columns.data();
  const uint32_t *const lower_begin = lower_.begin.data(), *const lower_columns = lower_.columns.data();
  const float *const upper_weights = upper_.weights.data(), *const lower_weights = lower_.weights.data();
  const uint8_t *const upper_mixed = upper_.mixed.data(), *const lower_mixed = lower_.mixed.data();
  double *const xv = xp.data(), *const rv = rt.data(), *const utv = ut.data(), *const uv = u.data();
  float* const tv = tf.data();
  // r = b − A x₀ = b − D x₀ − S⁻¹ N̂ S⁻¹ x₀ and r̂ = S r, then r̃ = (I + L)⁻¹
  // r̂ in place, colour by colour.
  BlockSums rr = sweep(colour_begin_, false, partial, [=](size_t begin, size_t end, BlockSums& sums) {
    Pair rsum = Pair::load(&sums[0]), dsum = Pair::load(&sums[2]);
    for (size_t i = begin; i < end; ++i) {
      const Pair ri = Pair::root_both(diagonal[i]);
      const Pair r =
          Pair::load(rv + 2 * i) - Pair::both(diagonal[i]) * Pair::load(xv + 2 * i) -
          ri * row_sum(lower_columns, lower_weights, lower_mixed[i], uv, lower_begin[i], lower_begin[i + 1],
                       row_sum(upper_columns, upper_weights, upper_mixed[i], uv, upper_begin[i], upper_begin[i + 1]));
      rsum = rsum + r * r;
      const Pair z =
          r / ri - row_sum(lower_columns, lower_weights, lower_mixed[i], rv, lower_begin[i], lower_begin[i + 1]);
      z.store(rv + 2 * i);
      dsum = dsum + z * z;
    }
    rsum.store(&sums[0]), dsum.store(&sums[2]);
  });
  // xv now holds the correction S⁻¹ (x − x₀), 0 until the first iteration writes it.
  // With a coarse level, z = B̃⁻¹ r̃ = r̃ + Q y, y = Ac⁻¹ Qᵀ r̃ (the coarse
  // solve), and ⟨r̃, z⟩ = ⟨r̃, r̃⟩ + ⟨Qᵀ r̃, y⟩: y is formed after the pass
  // that updates r̃ and Q y gathered in the next pass that forms p.
  const size_t coarse = coarse_rows();
  std::vector<double> restricted(2 * coarse), y(2 * coarse);
  const auto coarse_correction = [&]() {
    const uint32_t *const qt_begin = qt_begin_.data(), *const qt_rows = qt_rows_.data();
    const float* const qt_values = qt_values_.data();
    double* const g = restricted.data();
    parallel_for(coarse, [=](size_t begin, size_t end) {
      for (size_t c = begin; c < end; ++c)
        accumulate(qt_rows, qt_values, rv, qt_begin[c], qt_begin[c + 1]).store(g + 2 * c);
    });
    coarse_solve(restricted.data(), y.data());
    Pair dot = Pair::both(0.0);
    for (size_t j = 0; j < 2 * coarse; j += 2) dot = dot + Pair::load(g + j) * Pair::load(y.data() + j);
    BlockSums out{};
    dot.store(&out[0]);
    return out;
  };
  double rr_tilde[2] = {rr[2], rr[3]};  // ⟨r̃, r̃⟩ per field
  double rz[2] = {rr[2], rr[3]};        // ⟨r̃, z⟩ per field
  if (coarse > 0) {
    const BlockSums gy = coarse_correction();
    for (int k = 0; k < 2; ++k) rz[k] += gy[k];
  }
  bool active[2];
  const double limit[2] = {tolerance * tolerance * b2[0], tolerance * tolerance * b2[1]};
  for (int k = 0; k < 2; ++k) {
    // As Eigen: a zero right-hand side has the solution 0.
    if (b2[k] == 0) {
      for (size_t i = 0; i < n; ++i) x[2 * i + k] = 0;
      active[k] = false;
    } else {
      active[k] = rr[k] > limit[k];
    }
  }
  // ‖r‖² / ⟨r̃, r̃⟩ at the last iterate whose true residual was formed.
  double ratio[2];
  for (int k = 0; k < 2; ++k) ratio[k] = rr_tilde[k] > 0 ? rr[k] / rr_tilde[k] : 0.0;
  // From the first iteration if the residual is within a factor kNearFactor
  // (in norm) of the limit, as the first iteration rarely cuts more.
  bool check = false;  // whether the iteration forms the true residual
  for (int k = 0; k < 2; ++k) check = check || (active[k] && !(rr[k] > kNearFactor * kNearFactor * limit[k]));
  double beta[2] = {0, 0};
  int iterations = 0;  // run: without any, the correction is 0
  for (int it = 0; it < max_iterations && (active[0] || active[1]); ++it) {
    const Pair keep = Pair::of(active[0] ? 1.0 : 0.0, active[1] ? 1.0 : 0.0), beta_pair = Pair::of(beta[0], beta[1]);
    // Last colour first: p = r̃ + β q with the last direction q = (I + U) t
    // (formed from the t and U t kept), t = (I + U)⁻¹ p rounded to float,
    // and ⟨q, Ã q⟩ = ⟨t, A t⟩ (as (I + U)ᵀ = I + L) = Σ t_i (t_i + 2 (U t)_i)
    // from the sums this sweep forms anyway: α is known before the second
    // sweep. The direction is q, p but for t's rounding: x moves along the
    // rounded t and r̃ with it, so r̃ stays (I + L)⁻¹ (b̂ − Â x̂) to double
    // rounding; only conjugacy is perturbed, by 2⁻²⁴. t in float is 8 bytes
    // a row less to write, read and gather: misses −15 % on the bunny (and
    // instructions +2 %), the same iterations on the bunny, 1.1M and dragon.
    const double* const yv = y.data();
    const uint32_t *const q_begin = q_begin_.data(), *const q_columns = q_columns_.data();
    const float* const q_values = q_values_.data();
    const auto first = [=](auto with_coarse, auto fresh, size_t begin, size_t end, BlockSums& sums) {
      const uint32_t *const begin_ = upper_begin, *const columns_ = upper_columns;
      const float* const weights_ = upper_weights;
      const uint8_t* const mixed_ = upper_mixed;
      double *const rv_ = rv, *const utv_ = utv;
      float* const tv_ = tv;
      const Pair keep_ = keep, beta_ = beta_pair;
      Pair sum = Pair::load(&sums[0]);
      for (size_t i = begin; i < end; ++i) {
        Pair zi = Pair::load(rv_ + 2 * i);
        if constexpr (decltype(with_coarse)::value)
          zi = zi + accumulate(q_columns, q_values, yv, q_begin[i], q_begin[i + 1]);
        Pair pi;
        if constexpr (decltype(fresh)::value) {
          pi = keep_ * (zi + Pair::both(0.0));  // β q = 0 · 0
        } else {
          const Pair q = Pair::load(tv_ + 2 * i) + Pair::load(utv_ + 2 * i);
          pi = keep_ * (zi + beta_ * q);
        }
        const Pair uti = row_sum(columns_, weights_, mixed_[i], tv_, begin_[i], begin_[i + 1]);
        (pi - uti).store(tv_ + 2 * i);
        uti.store(utv_ + 2 * i);
        const Pair ti = Pair::load(tv_ + 2 * i);
        sum = sum + ti * (ti + Pair::both(2.0) * uti);
      }
      sum.store(&sums[0]);
    };
    const auto backward = [&](auto fresh) {
      return coarse > 0
                 ? sweep(colour_begin_, true, partial,
                         [=](size_t begin, size_t end, BlockSums& s) { first(std::true_type{}, fresh, begin, end, s); })
                 : sweep(colour_begin_, true, partial, [=](size_t begin, size_t end, BlockSums& s) {
                     first(std::false_type{}, fresh, begin, end, s);
                   });
    };
    const BlockSums pq = it == 0 ? backward(std::true_type{}) : backward(std::false_type{});
    double alpha[2];
    for (int k = 0; k < 2; ++k) alpha[k] = active[k] ? rz[k] / pq[k] : 0.0;
    const Pair alpha_pair = Pair::of(alpha[0], alpha[1]);
    // First colour first: u = (I + L)⁻¹ U t, Ã q = t + u (A t = (I + L) t +
    // U t); x += α t, r̃ −= α Ã q; and, once the residual is near the tolerance, the true
    // residual r = (D + L) r̃, whose L part reads rows of earlier colours,
    // updated already, over the entries that u reads.
    const auto second = [=](auto form_residual, auto fresh, size_t begin, size_t end, BlockSums& s) {
      const double* const diagonal_of = diagonal;
      const uint32_t *const begin_ = lower_begin, *const columns_ = lower_columns;
      const float* const weights_ = lower_weights;
      const uint8_t* const mixed_ = lower_mixed;
      double *const xv_ = xv, *const rv_ = rv, *const utv_ = utv, *const uv_ = uv;
      const float* const tv_ = tv;
      const Pair alpha_ = alpha_pair;
      Pair norm = Pair::load(&s[0]), dot = Pair::load(&s[2]);
      for (size_t i = begin; i < end; ++i) {
        Pair lu, lr;
        if constexpr (decltype(form_residual)::value)
          row_sum2(columns_, weights_, mixed_[i], uv_, rv_, begin_[i], begin_[i + 1], lu, lr);
        else
          lu = row_sum(columns_, weights_, mixed_[i], uv_, begin_[i], begin_[i + 1]);
        const Pair ti = Pair::load(tv_ + 2 * i), ui = Pair::load(utv_ + 2 * i) - lu;
        ui.store(uv_ + 2 * i);
        const Pair xi = decltype(fresh)::value ? Pair::both(0.0) : Pair::load(xv_ + 2 * i);
        (xi + alpha_ * ti).store(xv_ + 2 * i);
        const Pair ri = Pair::load(rv_ + 2 * i) - alpha_ * (ti + ui);
        ri.store(rv_ + 2 * i);
        if constexpr (decltype(form_residual)::value) {
          const Pair r = (ri + lr) * Pair::root_both(diagonal_of[i]);
          norm = norm + r * r;
        }
        dot = dot + ri * ri;
      }
      norm.store(&s[0]), dot.store(&s[2]);
    };
    const auto forward = [&](auto fresh) {
      return check ? sweep(colour_begin_, false, partial,
                           [=](size_t begin, size_t end, BlockSums& s) {
                             second(std::true_type{}, fresh, begin, end, s);
                           })
                   : sweep(colour_begin_, false, partial, [=](size_t begin, size_t end, BlockSums& s) {
                       second(std::false_type{}, fresh, begin, end, s);
                     });
    };
    const BlockSums sums = it == 0 ? forward(std::true_type{}) : forward(std::false_type{});
    ++iterations;
    bool near = false;
    for (int k = 0; k < 2; ++k) {
      if (check) {
        if (active[k] && !(sums[k] > limit[k])) active[k] = false;
        if (sums[2 + k] > 0) ratio[k] = sums[k] / sums[2 + k];
      }
      // The next residual, predicted from this iteration's reduction of
      // ⟨r̃, r̃⟩ and the ratio at the last true residual.
      const double predicted = ratio[k] * sums[2 + k] * (sums[2 + k] / rr_tilde[k]);
      near = near || (active[k] && !(predicted > kNearFactor * limit[k]));
      rr_tilde[k] = sums[2 + k];
    }
    const BlockSums gy = coarse > 0 && (active[0] || active[1]) ? coarse_correction() : BlockSums{};
    for (int k = 0; k < 2; ++k) {
      const double next = coarse > 0 ? sums[2 + k] + gy[k] : sums[2 + k];
      beta[k] = active[k] ? next / rz[k] : 0.0;
      rz[k] = next;
    }
    check = check || near;
    if (on_iteration) on_iteration(it + 1);
  }
  std::atomic<bool> finite{true};
  parallel_for(n, [&](size_t begin, size_t end) {
    bool part_finite = true;
    for (size_t k = begin; k < end; ++k) {
      double root[2];
      Pair::root_both(diagonal_[k]).store(root);
      for (int f = 0; f < 2; ++f) {
        double& v = x[2 * (input_row ? size_t{input_row[k]} : k) + f];
        // The correction is never −0 (it starts as 0 + α t), so 0 − c
        // undoes the handedness to the bit, zero included.
        const double c = iterations > 0 ? xp[2 * k + f] : 0.0;
        if (b2[f] != 0) v += (f == 1 && handed_[k] ? 0.0 - c : c) / root[f];
        part_finite = part_finite && std::isfinite(v);
      }
    }
    if (!part_finite) finite = false;
  });
  if (!finite) return false;
  return !active[0] && !active[1];
}

}  // namespace crestline
