#pragma once
// Runs one computation under a thread limit and restores the limit after it,
// for the tests that compare results on 1, 2 and 3 threads.
#include "crestline/numerics/parallel.h"

namespace crestline::testing {

template <typename Compute>
auto on_threads(int threads, const Compute& compute) {
  struct Limit {
    int before = max_threads();
    explicit Limit(int n) { set_max_threads(n); }
    ~Limit() { set_max_threads(before); }
  } limit(threads);
  return compute();
}

}  // namespace crestline::testing
