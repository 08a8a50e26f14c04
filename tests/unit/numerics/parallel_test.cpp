// parallel_for (numerics/parallel.h) over its kept threads: every index runs
// once, a loop nested in a chunk runs on that chunk's thread, an exception in
// any chunk reaches the caller and leaves the threads usable, and two callers
// at once both finish (the second on its own thread).
#include "crestline/numerics/parallel.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <stdexcept>
#include <thread>
#include <vector>

#include "../../../core/src/mesh/parts.h"

using namespace crestline;

namespace {

// Sets the thread limit for one test and restores it.
struct ThreadLimit {
  int before = max_threads();
  explicit ThreadLimit(int threads) { set_max_threads(threads); }
  ~ThreadLimit() { set_max_threads(before); }
};

// Runs an outer loop of `count` indices with a nested loop of 4,096 in each
// chunk; returns how often each outer index ran (all 1 if correct), the
// nested loops' total and the outer chunks.
std::vector<int> covered(size_t count, std::atomic<long>& nested, std::atomic<long>* chunks = nullptr) {
  std::vector<int> hits(count, 0);
  parallel_for(
      count,
      [&](size_t begin, size_t end) {
        if (chunks) ++*chunks;
        for (size_t i = begin; i < end; ++i) ++hits[i];
        parallel_for(
            4096, [&](size_t b, size_t e) { nested += static_cast<long>(e - b); }, 16);
      },
      16);
  return hits;
}

}  // namespace

TEST_CASE("parallel_for runs every index once, nested loops included, on 1 to 4 threads", "[numerics][threads]") {
  for (int threads : {1, 2, 3, 4}) {
    INFO("threads " << threads);
    const ThreadLimit limit(threads);
    for (int repeat = 0; repeat < 50; ++repeat) {
      std::atomic<long> nested{0}, chunks{0};
      const std::vector<int> hits = covered(1000, nested, &chunks);
      CHECK(std::count(hits.begin(), hits.end(), 1) == 1000);
      CHECK(nested == 4096L * chunks);                    // one nested loop per chunk, each whole
      CHECK(chunks == (threads == 1 ? 1 : 4 * threads));  // 4 pieces per thread
    }
  }
}

TEST_CASE("an exception in a chunk of parallel_for reaches the caller and the loop after it runs",
          "[numerics][threads]") {
  const ThreadLimit limit(2);
  for (size_t failing : {size_t{0}, size_t{9999}}) {  // the caller's chunk, a kept thread's chunk
    INFO("failing index " << failing);
    CHECK_THROWS_AS(parallel_for(
                        10000,
                        [&](size_t begin, size_t end) {
                          if (failing >= begin && failing < end) throw std::runtime_error("chunk failed");
                        },
                        16),
                    std::runtime_error);
    std::atomic<long> nested{0};
    const std::vector<int> hits = covered(1000, nested);
    CHECK(std::count(hits.begin(), hits.end(), 1) == 1000);
  }
}

TEST_CASE("two callers of parallel_for at once both finish with every index", "[numerics][threads]") {
  const ThreadLimit limit(2);
  std::vector<int> hits[2];
  std::atomic<long> nested[2];
  std::thread other([&] {
    for (int repeat = 0; repeat < 200; ++repeat) nested[1] = 0, hits[1] = covered(2000, nested[1]);
  });
  for (int repeat = 0; repeat < 200; ++repeat) nested[0] = 0, hits[0] = covered(2000, nested[0]);
  other.join();
  for (int k = 0; k < 2; ++k) {
    INFO("caller " << k);
    CHECK(std::count(hits[k].begin(), hits[k].end(), 1) == 2000);
    CHECK(nested[k] >= 4096);
  }
}

TEST_CASE("run_side_by_side runs each task once, first then second on one thread, and passes on an exception",
          "[numerics][threads]") {
  for (int threads : {1, 2}) {
    INFO("threads " << threads);
    const ThreadLimit limit(threads);
    for (int repeat = 0; repeat < 50; ++repeat) {
      std::vector<int> order;
      std::atomic<int> runs[2] = {{0}, {0}};
      std::atomic<long> nested{0};
      std::vector<int> hits;
      run_side_by_side(
          [&] {
            ++runs[0];
            if (threads == 1) order.push_back(0);
            hits = covered(1000, nested);  // a loop nested in a task
          },
          [&] {
            ++runs[1];
            if (threads == 1) order.push_back(1);
          });
      CHECK(runs[0] == 1);
      CHECK(runs[1] == 1);
      CHECK(std::count(hits.begin(), hits.end(), 1) == 1000);
      if (threads == 1) CHECK(order == std::vector<int>{0, 1});
    }
    CHECK_THROWS_AS(run_side_by_side([] {}, [] { throw std::runtime_error("second failed"); }), std::runtime_error);
  }
}

TEST_CASE("indices_where lists the matches in ascending order, the same on 1 to 4 threads", "[numerics][threads]") {
  // Matches at every seventh index and in a dense run, over counts that make
  // one part (stays on the caller) and one per thread.
  for (size_t count : {100u, 3000u, 200000u}) {
    std::vector<uint32_t> want;
    const auto keep = [](size_t i) { return i % 7 == 3 || (i >= 900 && i < 1400); };
    for (size_t i = 0; i < count; ++i)
      if (keep(i)) want.push_back(static_cast<uint32_t>(i));
    for (int threads : {1, 2, 3, 4}) {
      INFO("count " << count << ", threads " << threads);
      const ThreadLimit limit(threads);
      CHECK(detail::indices_where(count, keep) == want);
    }
  }
  CHECK(detail::indices_where(0, [](size_t) { return true; }).empty());
}
