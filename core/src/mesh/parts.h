#pragma once
// Loops cut into a few consecutive parts whose results are then combined in
// part order (counts turned into offsets, boxes merged): the combined result
// is the same however many parts there are or run at once, so the parts can
// follow the thread count. Shared by repair_mesh, build_topology,
// component_frames and the scans of a few matches (indices_where).
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "crestline/numerics/parallel.h"

namespace crestline::detail {

/// Parts for a loop of `count` items: one per thread (at most 8), one below
/// 2^15 items, where the threads would not pay for themselves.
inline size_t part_count(size_t count) {
  return count < (size_t{1} << 15) ? 1 : std::min<size_t>(size_t(max_threads()), 8);
}

/// Whether vertex v's sums are `part`'s when a scatter of per-triangle or
/// per-edge terms onto vertices is split over `parts` threads by vertex: runs
/// of 64 vertices (whole cache lines of their sums) dealt out in turn, each
/// part going through the terms in order, so every vertex's additions happen
/// on one thread in the same order for any number of parts.
inline bool in_vertex_part(uint32_t v, size_t part, size_t parts) { return parts == 1 || (v >> 6) % parts == part; }

/// Calls body(part, begin, end) for `parts` consecutive ranges covering [0, count), on as many threads.
template <typename Body>
void for_each_part(size_t parts, size_t count, const Body& body) {
  parallel_for(
      parts,
      [&](size_t first, size_t last) {
        for (size_t p = first; p < last; ++p) body(p, count * p / parts, count * (p + 1) / parts);
      },
      1);
}

/// Lowers `target` to `value` if it is smaller, whichever thread gets there
/// first: the smallest value offered wins.
template <typename T>
void atomic_min(std::atomic<T>& target, T value) {
  T seen = target.load(std::memory_order_relaxed);
  while (value < seen && !target.compare_exchange_weak(seen, value, std::memory_order_relaxed)) {
  }
}

/// An ordered compaction on every thread: counts the i in [0, count) with
/// keep(i), calls sized(total), then place(i, rank) for each kept i, rank
/// being the number of kept indices before it. Returns the total. keep is
/// called twice per index.
template <typename Keep, typename Sized, typename Place>
size_t place_kept(size_t count, const Keep& keep, const Sized& sized, const Place& place) {
  const size_t parts = part_count(count);
  std::vector<size_t> offset(parts + 1, 0);
  for_each_part(parts, count, [&](size_t p, size_t begin, size_t end) {
    size_t n = 0;
    for (size_t i = begin; i < end; ++i) n += keep(i) ? 1 : 0;
    offset[p + 1] = n;
  });
  for (size_t p = 0; p < parts; ++p) offset[p + 1] += offset[p];
  sized(offset[parts]);
  for_each_part(parts, count, [&](size_t p, size_t begin, size_t end) {
    size_t rank = offset[p];
    for (size_t i = begin; i < end; ++i)
      if (keep(i)) place(i, rank++);
  });
  return offset[parts];
}

/// The i in [0, count) with keep(i), ascending (count < 2^32): place_kept's
/// result in one pass instead of two, each part listing its own, for scans
/// whose matches are few. keep is called once per index.
template <typename Keep>
std::vector<uint32_t> indices_where(size_t count, const Keep& keep) {
  const size_t parts = part_count(count);
  std::vector<std::vector<uint32_t>> found(parts);
  for_each_part(parts, count, [&](size_t p, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      if (keep(i)) found[p].push_back(static_cast<uint32_t>(i));
  });
  std::vector<uint32_t> out = std::move(found[0]);
  for (size_t p = 1; p < parts; ++p) out.insert(out.end(), found[p].begin(), found[p].end());
  return out;
}

}  // namespace crestline::detail
