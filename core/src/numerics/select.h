#pragma once
// The value at a rank (a median) in about one streaming pass over the
// values. std::nth_element over all of them costs not many more
// instructions (the crease measure's and the frames' medians over 1.67M
// edges at 1.1M triangles: 30 and 22 M, against 21 and 20 M) but more
// time, its partitions' branches going either way at random (thread CPU,
// 1 thread: the measure 123 → 113 ms, the frames 66 → 59 ms).
#include <algorithm>
#include <array>
#include <cstddef>

#include "crestline/numerics/parallel.h"
#include "crestline/numerics/uninitialised.h"

namespace crestline::detail {

/// The value at `rank` (0-based, < count) of values[0, count) in ascending
/// order, none of them NaN: what std::nth_element(values, values + rank,
/// values + count) puts at values[rank], so the same bits for any order of
/// the values (equal values have equal bits, but for ±0, either of which
/// nth_element may return too). A sample of every (count / 2^14)-th value
/// bounds a window around the rank; one pass (on every thread) counts the
/// values below it and copies those inside, and nth_element finds the rank
/// among the copies. The sample decides the speed only, never the value: where the window
/// misses the rank (an unrepresentative sample) or holds more than an
/// eighth of the values (many equal), nth_element over all of them, which
/// reorders them; otherwise they are only read.
template <typename T>
T value_at_rank(T* values, size_t count, size_t rank) {
  // The wanted value's rank in a random sample of 2^14 spreads by
  // √(2^14)/2 = 64; the window is ±8 of those (a sixteenth of the values).
  constexpr size_t kSample = size_t{1} << 14, kMargin = 8 * 64;
  if (count < 8 * kSample) {
    std::nth_element(values, values + rank, values + count);
    return values[rank];
  }
  const size_t stride = count / kSample;
  // Room for every value (address space: only the pages written are touched).
  UninitialisedVector<T> inside(count);
  T* sample = inside.data();
  for (size_t i = 0; i < kSample; ++i) sample[i] = values[i * stride];
  const size_t at = std::min(kSample - 1, rank / stride);
  const size_t low = at > kMargin ? at - kMargin : 0, high = std::min(kSample - 1, at + kMargin);
  std::nth_element(sample, sample + low, sample + kSample);
  const T lo = sample[low];
  std::nth_element(sample + low, sample + high, sample + kSample);
  const T hi = sample[high];
  // One pass in blocks, on every thread: each block counts the values below
  // the window and copies those inside to its own stretch of `inside` (over
  // the sample, which is done with); moved together in block order they are
  // the copies a serial pass makes, in the same order, so the value is the
  // same for any thread count (±0 included). At 1.1M triangles the serial
  // pass over 1.67M edges was ≈ 10 ms of the calling thread alone on 2.
  constexpr size_t kBlocks = 64;
  std::array<size_t, kBlocks> below_of{}, inside_of{};
  parallel_for(
      kBlocks,
      [&](size_t first, size_t last) {
        for (size_t b = first; b < last; ++b) {
          const size_t begin = count * b / kBlocks, end = count * (b + 1) / kBlocks;
          T* const out = inside.data() + begin;
          // Branch-free either side of the window (the branch on the
          // window's sixteenth is mostly not taken).
          size_t below = 0, n = 0;
          for (size_t i = begin; i < end; ++i) {
            const T x = values[i];
            below += x < lo;
            if (lo <= x && x <= hi) out[n++] = x;
          }
          below_of[b] = below, inside_of[b] = n;
        }
      },
      1);
  // More than an eighth inside (many equal values): nth_element over all.
  const size_t cap = count / 8;
  size_t below = 0, n = 0;
  for (size_t b = 0; b < kBlocks && n < cap; ++b) {
    const T* const from = inside.data() + count * b / kBlocks;
    if (from != inside.data() + n) std::copy(from, from + inside_of[b], inside.data() + n);  // down: n < start
    below += below_of[b], n += inside_of[b];
  }
  if (n < cap && below <= rank && rank < below + n) {
    std::nth_element(sample, sample + (rank - below), sample + n);
    return sample[rank - below];
  }
  std::nth_element(values, values + rank, values + count);
  return values[rank];
}

}  // namespace crestline::detail
