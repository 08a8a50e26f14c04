#pragma once
// Per-triangle or per-edge terms summed onto vertices in item order, on any
// number of threads with the same bits: compute_curvature's two sums and
// compute_extremality's.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "../mesh/parts.h"
#include "crestline/numerics/parallel.h"

namespace crestline::detail {

/// in_vertex_part's part of vertex v, (v >> 6) % parts, without a division
/// (tens of cycles, once per vertex and item on more than one thread): the
/// quotient is (v >> 6) · ⌈2³² / parts⌉ >> 32, exact for every 32-bit v and
/// parts ≤ 8 (the error term stays below 1 / parts).
struct VertexParts {
  explicit VertexParts(size_t count) : parts(count), inverse(((uint64_t{1} << 32) + count - 1) / count) {}
  size_t of(uint32_t v) const {
    const uint64_t run = v >> 6;
    return run - ((run * inverse) >> 32) * parts;
  }
  size_t parts;
  uint64_t inverse;
};

/// Sums the terms of `count` items onto their vertices, a block of `block`
/// items at a time (the caller's buffer of terms holds one block, item i's at
/// i % block): form(begin, first, last) forms the terms of items begin +
/// [first, last), on every thread; then add(i, mine) adds item i's terms to
/// each of its vertices v with mine(v), going through the block in item order
/// (its captures best by value: it runs on a copy, kept in registers). That addition is split over
/// the threads by vertex (in_vertex_part; one part below four blocks), so that
/// every vertex's sum is in item order for any number of threads. Item
/// i + kAhead's sums lie anywhere in their arrays: prefetch(i + kAhead) asks
/// for them while item i is added (natively; WASM has no prefetch). done(end)
/// after each block, for progress.
template <size_t kAhead, typename Form, typename Prefetch, typename Add, typename Done>
void scatter_to_vertices(size_t count, size_t block, const Form& form, const Prefetch& prefetch, const Add& add,
                         const Done& done) {
  const VertexParts parts(count < 4 * block ? 1 : std::min<size_t>(size_t(max_threads()), 8));
  for (size_t begin = 0; begin < count; begin += block) {
    const size_t end = std::min(count, begin + block);
    parallel_for(end - begin, [&](size_t first, size_t last) { form(begin, first, last); });
    parallel_for(
        parts.parts,
        [&](size_t first_part, size_t last_part) {
          // Copies, so that what they captured stays in registers (through
          // the references, GCC reloaded it for every item).
          const Prefetch prefetch_sums = prefetch;
          const Add add_terms = add;
          const size_t block_begin = begin, block_end = end;
          const auto add_all = [&](const auto& mine) {
            for (size_t i = block_begin; i < block_end; ++i) {
              if (i + kAhead < block_end) prefetch_sums(i + kAhead);
              add_terms(i, mine);
            }
          };
          // One part (one thread, or a short loop) tests nothing.
          if (parts.parts == 1) return add_all([](uint32_t) { return true; });
          for (size_t part = first_part; part < last_part; ++part)
            add_all([part, parts](uint32_t v) { return parts.of(v) == part; });
        },
        1);
    done(end);
  }
}

}  // namespace crestline::detail
