// The coarse level of the paired solver's two-level preconditioner
// (numerics/paired_cg.h): aggregates of the rows that the Gauss–Seidel
// sweeps smooth slowly, and the operators Q = L P and Ac = Pᵀ Â P the solve
// uses. Each row's arithmetic is its own or in a fixed order, on any
// thread (the per-row passes, Ac's and Q's rows; Qᵀ and Ac's factor side by
// side): the same for any number of threads.
#include <algorithm>
#include <cmath>
#include <limits>

#include "crestline/numerics/paired_cg.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/uninitialised.h"

namespace crestline {
namespace {

// Neighbours joined into one aggregate: |a_ij| ≥ this · √(a_ii a_jj).
constexpr double kStrong = 0.08;
constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// The fields (bit k) in which entry e is positive: across it a smooth mode
// changes sign (x_j = σ x_i where the entry is −σ w).
uint32_t sign_change(const SignedPairMatrix& a, uint32_t e) {
  return (a.columns[e] >> 30 & 3) ^ (a.weights[e] > 0 ? 3u : 0u);
}

// Rows of a sparse matrix made on every thread: fill(r, found, sums,
// columns, values) appends row r's entries (found and sums: scratch for the
// row, cleared before each). The rows are made in kBlocks blocks, each into
// its own arrays, then copied into place (begin: rows + 1 offsets): each
// row's arithmetic is its own, the same for any number of threads.
template <typename Value, typename Fill>
void rows_in_blocks(size_t rows, std::vector<uint32_t>& begin, std::vector<uint32_t>& columns,
                    std::vector<Value>& values, const Fill& fill) {
  constexpr size_t kBlocks = 64;
  std::vector<std::vector<uint32_t>> block_columns(kBlocks);
  std::vector<std::vector<Value>> block_values(kBlocks);
  begin.assign(rows + 1, 0);
  parallel_for(
      kBlocks,
      [&](size_t first, size_t last) {
        std::vector<uint32_t> found;
        std::vector<double> sums;
        for (size_t b = first; b < last; ++b)
          for (size_t r = rows * b / kBlocks; r < rows * (b + 1) / kBlocks; ++r) {
            const size_t before = block_columns[b].size();
            found.clear(), sums.clear();
            fill(r, found, sums, block_columns[b], block_values[b]);
            begin[r + 1] = static_cast<uint32_t>(block_columns[b].size() - before);
          }
      },
      1);
  for (size_t r = 0; r < rows; ++r) begin[r + 1] += begin[r];
  columns.resize(begin[rows]);
  values.resize(2 * size_t{begin[rows]});
  parallel_for(
      kBlocks,
      [&](size_t first, size_t last) {
        for (size_t b = first; b < last; ++b) {
          const size_t at = begin[rows * b / kBlocks];
          std::copy(block_columns[b].begin(), block_columns[b].end(), columns.begin() + at);
          std::copy(block_values[b].begin(), block_values[b].end(), values.begin() + 2 * at);
          std::vector<uint32_t>().swap(block_columns[b]);
          std::vector<Value>().swap(block_values[b]);
        }
      },
      1);
}

// The index of c among found, appended (with a pair of zero sums) if new: a
// row's few distinct neighbours, in the order first reached.
inline size_t find_or_add(std::vector<uint32_t>& found, std::vector<double>& sums, uint32_t c) {
  const size_t at = static_cast<size_t>(std::find(found.begin(), found.end(), c) - found.begin());
  if (at == found.size()) found.push_back(c), sums.push_back(0.0), sums.push_back(0.0);
  return at;
}

}  // namespace

// Aggregation as in smoothed aggregation's first phases (Vaněk, Mandel and
// Brezina 1996), over the slow rows only, in breadth-first order: a slow row
// whose strong slow neighbours are all free roots an aggregate of itself and
// them; the slow rows left join the aggregate of their strongest neighbour
// of the first phase; those still left group with their free strong
// neighbours. Rows alone stay out (a sweep solves a single row exactly).
// Each aggregate is a tree of its rows' joins, and P's column for it is the
// mode smooth along that tree, ±1 in each field by the signs of the entries
// crossed (±√a_ii in the scaled variables).
SignedPairSolver::Aggregation SignedPairSolver::build_coarse_matrix(const SignedPairMatrix& a,
                                                                    const UninitialisedVector<double>& excess,
                                                                    const std::vector<uint32_t>& bfs_order,
                                                                    const UninitialisedVector<uint32_t>& position,
                                                                    const std::function<void()>& pause) {
  const size_t n = a.rows();
  UninitialisedVector<uint8_t> slow(n);
  UninitialisedVector<double> inverse_root(n);  // 1 / √a_ii, by input row
  parallel_for(n, [&](size_t begin, size_t end) {
    // Raw pointers in locals: a store through one may alias the vectors' own.
    const double *const diagonal = a.diagonal.data(), *const excess_of = excess.data(), *const roots = roots_.data();
    const uint32_t* const offsets = a.offsets.data();
    uint8_t* const slow_of = slow.data();
    double* const inverse = inverse_root.data();
    for (size_t i = begin; i < end; ++i) {
      slow_of[i] = detail::is_slow(diagonal[i], excess_of[i], offsets[i + 1] > offsets[i]);
      inverse[i] = 1 / roots[i];
    }
  });
  const auto column = [&](uint32_t e) { return a.columns[e] & SignedPairMatrix::kColumnMask; };
  const auto strength = [&](uint32_t i, uint32_t e) {  // |a_ij| / √(a_ii a_jj)
    return std::abs(a.weights[e]) * inverse_root[i] * inverse_root[column(e)];
  };
  const auto strong = [&](uint32_t i, uint32_t e) { return slow[column(e)] && strength(i, e) >= kStrong; };
  std::vector<uint32_t> aggregate(n, kNone);
  std::vector<uint8_t> flips(n, 0);  // bit k: the row's value in field k's column of P is negative
  uint32_t aggregates = 0;
  size_t aggregated = 0;
  // i roots a new aggregate of itself and its strong neighbours that are free.
  const auto root = [&](uint32_t i) {
    aggregate[i] = aggregates, flips[i] = 0, ++aggregated;
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
      const uint32_t j = column(e);
      if (strong(i, e) && aggregate[j] == kNone)
        aggregate[j] = aggregates, flips[j] = static_cast<uint8_t>(sign_change(a, e)), ++aggregated;
    }
    ++aggregates;
  };
  for (const uint32_t i : bfs_order) {
    if (!slow[i] || aggregate[i] != kNone) continue;
    bool any = false, free = true;
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e)
      if (strong(i, e)) any = true, free = free && aggregate[column(e)] == kNone;
    if (any && free) root(i);
  }
  pause();
  const std::vector<uint32_t> first = aggregate;
  for (const uint32_t i : bfs_order) {
    if (!slow[i] || aggregate[i] != kNone) continue;
    uint32_t best = kNone;
    double strongest = 0;
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
      const double s = strength(i, e);
      if (first[column(e)] != kNone && strong(i, e) && s > strongest) strongest = s, best = e;
    }
    if (best == kNone) continue;
    const uint32_t j = column(best);
    aggregate[i] = first[j], flips[i] = static_cast<uint8_t>(flips[j] ^ sign_change(a, best)), ++aggregated;
  }
  for (const uint32_t i : bfs_order) {
    if (!slow[i] || aggregate[i] != kNone) continue;
    bool any = false;
    for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e)
      any = any || (strong(i, e) && aggregate[column(e)] == kNone);
    if (any) root(i);
  }
  if (aggregated < detail::min_aggregated(n)) return {};
  pause();

  // The members of each aggregate, in breadth-first order.
  std::vector<uint32_t> member_begin(aggregates + 1, 0), members(aggregated);
  for (size_t i = 0; i < n; ++i)
    if (aggregate[i] != kNone) ++member_begin[aggregate[i] + 1];
  for (uint32_t c = 0; c < aggregates; ++c) member_begin[c + 1] += member_begin[c];
  {
    std::vector<uint32_t> fill(member_begin.begin(), member_begin.end() - 1);
    for (const uint32_t i : bfs_order)
      if (aggregate[i] != kNone) members[fill[aggregate[i]]++] = i;
  }
  // Ac = Pᵀ A P with P's columns the signed indicators s of the aggregates.
  // Its diagonal as a sum of terms ≥ 0 (no cancellation where R is large):
  // sᵀ A s = Σ excess_i + Σ over entries to other rows |a_ij| + Σ over
  // entries inside (|a_ij| + s_i s_j a_ij), the last 0 where the signs follow
  // the entry. Diagonally dominant, so positive definite. Only the entries
  // to earlier aggregates are kept: the factorisation reads no others.
  const auto signed_entry = [&](uint32_t i, uint32_t j, uint32_t e, int k) {  // s_i s_j a_ij in field k
    return (a.columns[e] >> 30 ^ flips[i] ^ flips[j]) >> k & 1 ? -a.weights[e] : a.weights[e];
  };
  // Each aggregate's row on every thread (rows_in_blocks): its neighbours in
  // the order its members' entries first reach them, the same sums as by
  // one thread (before: serial, with a slot per aggregate).
  std::vector<double> diagonal(2 * size_t{aggregates}, 0.0), off_values;
  std::vector<uint32_t> off_begin, off_columns;
  rows_in_blocks(aggregates, off_begin, off_columns, off_values,
                 [&](size_t c, std::vector<uint32_t>& found, std::vector<double>& sums, std::vector<uint32_t>& columns,
                     std::vector<double>& values) {
                   for (uint32_t m = member_begin[c]; m < member_begin[c + 1]; ++m) {
                     const uint32_t i = members[m];
                     double sum[2] = {excess[i], excess[i]};
                     for (uint32_t e = a.offsets[i]; e < a.offsets[i + 1]; ++e) {
                       const uint32_t j = column(e), d = aggregate[j];
                       const double magnitude = std::abs(a.weights[e]);
                       if (d == c) {
                         for (int k = 0; k < 2; ++k) sum[k] += magnitude + signed_entry(i, j, e, k);
                         continue;
                       }
                       sum[0] += magnitude, sum[1] += magnitude;
                       if (d == kNone) continue;
                       const size_t at = find_or_add(found, sums, d);
                       for (int k = 0; k < 2; ++k) sums[2 * at + k] += signed_entry(i, j, e, k);
                     }
                     diagonal[2 * c] += sum[0], diagonal[2 * c + 1] += sum[1];
                   }
                   for (size_t at = 0; at < found.size(); ++at)
                     if (found[at] < c)
                       columns.push_back(found[at]), values.insert(values.end(), {sums[2 * at], sums[2 * at + 1]});
                 });
  // An aggregate without excess or neighbours outside it (Ac_cc = 0: a
  // whole component whose diagonals are the sums of their off-diagonal
  // magnitudes, to rounding) would make Ac singular: no coarse level then,
  // the one-level solve as before.
  for (const double d : diagonal)
    if (!(d > 0)) return {};
  // Scaled to a unit diagonal per field, as the fine level.
  std::vector<double> coarse_root(2 * size_t{aggregates});
  for (size_t j = 0; j < coarse_root.size(); ++j) coarse_root[j] = std::sqrt(diagonal[j]);
  for (uint32_t c = 0; c < aggregates; ++c)
    for (uint32_t e = off_begin[c]; e < off_begin[c + 1]; ++e)
      for (int k = 0; k < 2; ++k)
        off_values[2 * size_t{e} + k] /= coarse_root[2 * size_t{c} + k] * coarse_root[2 * size_t{off_columns[e]} + k];
  aggregated_ = aggregated;

  // By the solver's rows, for P (build_coarse_transfer); every row written
  // once (position is a permutation).
  Aggregation out;
  out.aggregate.resize(n);
  out.flips.resize(n);
  parallel_for(n, [&](size_t begin, size_t end) {
    const uint32_t *const at = position.data(), *const from = aggregate.data();
    const uint8_t* const flips_from = flips.data();
    uint32_t* const to = out.aggregate.data();
    uint8_t* const flips_to = out.flips.data();
    for (size_t i = begin; i < end; ++i) to[at[i]] = from[i], flips_to[at[i]] = flips_from[i];
  });
  out.coarse_root = std::move(coarse_root);
  out.lower_begin = std::move(off_begin), out.lower_columns = std::move(off_columns);
  out.lower_values = std::move(off_values);
  return out;
}

// Ac = L D Lᵀ, both fields in lockstep (one pattern), by rows: row k of L
// solves the rows before it against row k of Ac (up-looking, as Davis's LDL
// package: its pattern is the reach of Ac's entries in the elimination tree).
// Aggregates in breadth-first order fill in little (the dragon: 55 k entries
// below Ac's diagonal, 121 k in L). Every operation is one field's alone and
// in a fixed order: the same bits natively and in WASM.
bool detail::PairFactor::factor(const std::vector<uint32_t>& row_begin, const std::vector<uint32_t>& row_columns,
                                const std::vector<double>& row_values, size_t max_fill) {
  const uint32_t rows = static_cast<uint32_t>(row_begin.size() - 1);
  // Symbolic: the elimination tree and the entries of each column of L.
  std::vector<uint32_t> parent(rows, kNone), flag(rows), column_count(rows, 0);
  for (uint32_t k = 0; k < rows; ++k) {
    flag[k] = k;
    for (uint32_t e = row_begin[k]; e < row_begin[k + 1]; ++e)
      for (uint32_t i = row_columns[e]; flag[i] != k; i = parent[i]) {
        if (parent[i] == kNone) parent[i] = k;
        ++column_count[i], flag[i] = k;
      }
  }
  std::vector<uint32_t> column_begin(rows + 1, 0);
  for (uint32_t i = 0; i < rows; ++i) column_begin[i + 1] = column_begin[i] + column_count[i];
  // Where L would fill in far beyond Ac, Ac is solved by sweeps instead
  // (SignedPairSolver::keep_coarse_rows): the factorization and its reads
  // would cost more than the iterations they save, and its memory would be
  // the run's peak. L's entries over Ac's rows
  // and entries below the diagonal, and smoothing seconds (CLI, 1 thread)
  // with the factor against no coarse level at all: at the default time step
  // 0.65 (1.1M), 1.04 (dragon), 1.26 (4.4M); at 1.5× it, the dragon 5.9 (1.33
  // s against 1.71, 53 against 167 iterations), the 1.1M 9.8 (1.30 against
  // 1.05 s, 311 against 264 MB peak) and the 4.4M 19 (8.38 against 6.81 s,
  // 1,374 against 1,028 MB).
  const size_t entries = column_begin[rows];
  refused_for_fill = max_fill > 0 && entries > max_fill * (size_t{rows} + row_begin[rows]);
  if (refused_for_fill) return false;
  std::vector<uint32_t> column_rows(entries), pattern(rows);
  std::vector<double> column_values(2 * entries), y(2 * size_t{rows}, 0.0), pivot(2 * size_t{rows});
  std::fill(column_count.begin(), column_count.end(), 0);
  for (uint32_t k = 0; k < rows; ++k) {
    uint32_t top = rows;
    flag[k] = k;
    for (uint32_t e = row_begin[k]; e < row_begin[k + 1]; ++e) {
      uint32_t i = row_columns[e], length = 0;
      for (int f = 0; f < 2; ++f) y[2 * size_t{i} + f] += row_values[2 * size_t{e} + f];
      for (; flag[i] != k; i = parent[i]) pattern[length++] = i, flag[i] = k;
      while (length > 0) pattern[--top] = pattern[--length];
    }
    double d[2] = {1.0, 1.0};  // Ac's unit diagonal
    for (; top < rows; ++top) {
      const uint32_t i = pattern[top];
      const double yi[2] = {y[2 * size_t{i}], y[2 * size_t{i} + 1]};
      y[2 * size_t{i}] = y[2 * size_t{i} + 1] = 0.0;
      const uint32_t last = column_begin[i] + column_count[i];
      for (uint32_t p = column_begin[i]; p < last; ++p)
        for (int f = 0; f < 2; ++f) y[2 * size_t{column_rows[p]} + f] -= column_values[2 * size_t{p} + f] * yi[f];
      column_rows[last] = k;
      for (int f = 0; f < 2; ++f) {
        const double l = yi[f] / pivot[2 * size_t{i} + f];
        d[f] -= l * yi[f];
        column_values[2 * size_t{last} + f] = l;
      }
      ++column_count[i];
    }
    // Ac is positive definite (diagonally dominant); a pivot lost to
    // rounding would leave the coarse level out.
    if (!(d[0] > 0) || !(d[1] > 0)) return false;
    pivot[2 * size_t{k}] = d[0], pivot[2 * size_t{k} + 1] = d[1];
  }
  // By row for the forward solve, whose gathers read rows done before.
  begin.assign(rows + 1, 0);
  for (const uint32_t r : column_rows) ++begin[r + 1];
  for (uint32_t r = 0; r < rows; ++r) begin[r + 1] += begin[r];
  columns.resize(entries);
  values.resize(2 * entries);
  std::vector<uint32_t> fill(begin.begin(), begin.end() - 1);
  for (uint32_t i = 0; i < rows; ++i)
    for (uint32_t p = column_begin[i]; p < column_begin[i + 1]; ++p) {
      const uint32_t to = fill[column_rows[p]]++;
      columns[to] = i;
      for (int f = 0; f < 2; ++f) values[2 * size_t{to} + f] = column_values[2 * size_t{p} + f];
    }
  inverse_pivot.resize(pivot.size());
  for (size_t j = 0; j < pivot.size(); ++j) inverse_pivot[j] = 1 / pivot[j];
  // The trees of the elimination forest (Ac's connected components; L joins
  // no two) dealt into kGroups groups of about equal work (rows and
  // entries), each tree whole, in order of their first rows.
  std::vector<uint32_t>& root = parent;  // each row's tree by its root, the tree's last row
  for (uint32_t k = rows; k-- > 0;) root[k] = parent[k] == kNone ? k : root[parent[k]];
  std::vector<size_t> tree_work(rows, 0);
  for (uint32_t k = 0; k < rows; ++k) tree_work[root[k]] += 1 + begin[k + 1] - begin[k];
  std::vector<uint32_t>& group = flag;  // of each tree, by its root
  std::fill(group.begin(), group.end(), kNone);
  const size_t work = size_t{rows} + entries;
  size_t dealt = 0;
  uint32_t current = 0;
  group_begin.assign(kGroups + 1, 0);
  for (uint32_t k = 0; k < rows; ++k) {
    if (group[root[k]] != kNone) continue;
    while (current + 1 < kGroups && dealt * kGroups >= (current + 1) * work) ++current;
    group[root[k]] = current, dealt += tree_work[root[k]];
  }
  for (uint32_t k = 0; k < rows; ++k) ++group_begin[group[root[k]] + 1];
  for (uint32_t c = 0; c < kGroups; ++c) group_begin[c + 1] += group_begin[c];
  order.resize(rows);
  std::vector<uint32_t> next(group_begin.begin(), group_begin.end() - 1);
  for (uint32_t k = 0; k < rows; ++k) order[next[group[root[k]]]++] = k;
  return true;
}

// Each row's entries to earlier rows as given (columns ascending or not),
// then those to later rows in ascending order (the transpose's).
void SignedPairSolver::keep_coarse_rows(const std::vector<uint32_t>& lower_begin,
                                        const std::vector<uint32_t>& lower_columns,
                                        const std::vector<double>& lower_values) {
  const size_t rows = lower_begin.size() - 1;
  std::vector<uint32_t> upper_count(rows, 0);
  for (const uint32_t d : lower_columns) ++upper_count[d];
  coarse_begin_.assign(rows + 1, 0);
  coarse_upper_begin_.resize(rows);
  for (size_t c = 0; c < rows; ++c)
    coarse_begin_[c + 1] = coarse_begin_[c] + (lower_begin[c + 1] - lower_begin[c]) + upper_count[c];
  coarse_columns_.resize(coarse_begin_[rows]);
  coarse_values_.resize(2 * size_t{coarse_begin_[rows]});
  std::vector<uint32_t> next(rows);
  for (size_t c = 0; c < rows; ++c) {
    uint32_t to = coarse_begin_[c];
    for (uint32_t e = lower_begin[c]; e < lower_begin[c + 1]; ++e, ++to) {
      coarse_columns_[to] = lower_columns[e];
      coarse_values_[2 * size_t{to}] = lower_values[2 * size_t{e}];
      coarse_values_[2 * size_t{to} + 1] = lower_values[2 * size_t{e} + 1];
    }
    coarse_upper_begin_[c] = next[c] = to;
  }
  for (size_t c = 0; c < rows; ++c)
    for (uint32_t e = lower_begin[c]; e < lower_begin[c + 1]; ++e) {
      const uint32_t to = next[lower_columns[e]]++;
      coarse_columns_[to] = static_cast<uint32_t>(c);
      coarse_values_[2 * size_t{to}] = lower_values[2 * size_t{e}];
      coarse_values_[2 * size_t{to} + 1] = lower_values[2 * size_t{e} + 1];
    }
}

// P in the solver's rows and scaled variables, s_i √a_ii / √Ac_cc, formed
// where Q reads it (not stored: 16 bytes a row).
bool SignedPairSolver::build_coarse_transfer(Aggregation& aggregation) {
  const size_t n = diagonal_.size();
  const uint32_t aggregates = static_cast<uint32_t>(aggregation.coarse_root.size() / 2);
  const std::vector<uint32_t>& fine_aggregate = aggregation.aggregate;
  // In the solver's handedness: field 1's column of P negated where handed_.
  // √a_jj formed where read (correctly rounded: the bits the set-up's roots had).
  const auto p = [&](uint32_t j, int k) {
    const double root = std::sqrt(diagonal_[j]);
    const double s = (aggregation.flips[j] >> k ^ (k == 1 ? handed_[j] : 0)) & 1 ? -root : root;
    return s / aggregation.coarse_root[2 * size_t{fine_aggregate[j]} + k];
  };
  // Q = L P by fine row, from the float entries the sweeps use, on every
  // thread (rows_in_blocks; before: appended to one array on the calling
  // thread, then copied to its size): a row's aggregates in the order its
  // entries first reach them.
  rows_in_blocks(n, q_begin_, q_columns_, q_values_,
                 [&](size_t r, std::vector<uint32_t>& found, std::vector<double>& sums, std::vector<uint32_t>& columns,
                     std::vector<float>& values) {
                   for (uint32_t e = lower_.begin[r]; e < lower_.begin[r + 1]; ++e) {
                     const uint32_t j = lower_.columns[e], c = fine_aggregate[j];
                     if (c == kNone) continue;
                     const size_t at = find_or_add(found, sums, c);
                     // The entry's two values (detail::stored_entry).
                     bool flip;
                     const double value = detail::entry_value(lower_.weights[e], flip);
                     const double a[2] = {value, flip ? -value : value};
                     for (int k = 0; k < 2; ++k) sums[2 * at + k] += a[k] * p(j, k);
                   }
                   columns.insert(columns.end(), found.begin(), found.end());
                   for (const double v : sums) values.push_back(static_cast<float>(v));
                 });
  // Qᵀ by coarse row, fine rows in order; beside it, Ac factored (each
  // serial, ≈ 30 and 40 M instructions on the dragon; neither reads what
  // the other writes).
  bool factored = true;
  run_side_by_side(
      [&] {
        qt_begin_.assign(aggregates + 1, 0);
        for (const uint32_t c : q_columns_) ++qt_begin_[c + 1];
        for (uint32_t c = 0; c < aggregates; ++c) qt_begin_[c + 1] += qt_begin_[c];
        qt_rows_.resize(q_columns_.size());
        qt_values_.resize(q_values_.size());
        std::vector<uint32_t> fill(qt_begin_.begin(), qt_begin_.end() - 1);
        for (uint32_t r = 0; r < n; ++r)
          for (uint32_t e = q_begin_[r]; e < q_begin_[r + 1]; ++e) {
            const uint32_t to = fill[q_columns_[e]]++;
            qt_rows_[to] = r;
            qt_values_[2 * size_t{to}] = q_values_[2 * size_t{e}],
                           qt_values_[2 * size_t{to} + 1] = q_values_[2 * size_t{e} + 1];
          }
      },
      [&] {
        if (coarse_factor_.factor(aggregation.lower_begin, aggregation.lower_columns, aggregation.lower_values)) return;
        if (coarse_factor_.refused_for_fill)
          keep_coarse_rows(aggregation.lower_begin, aggregation.lower_columns, aggregation.lower_values);
        else
          factored = false;
      });
  if (factored) return true;
  // A pivot lost to rounding: no coarse level, the one-level solve.
  for (std::vector<uint32_t>* v : {&q_begin_, &q_columns_, &qt_begin_, &qt_rows_}) std::vector<uint32_t>().swap(*v);
  for (std::vector<float>* v : {&q_values_, &qt_values_}) std::vector<float>().swap(*v);
  aggregated_ = 0;
  return false;
}

}  // namespace crestline
