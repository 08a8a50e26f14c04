#include "crestline/numerics/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <vector>

#ifdef CRESTLINE_THREADS
#include <mutex>
#include <thread>
#endif

namespace crestline {
namespace {

#ifdef CRESTLINE_THREADS
int hardware_threads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }
std::atomic<int> g_threads{hardware_threads()};
#else
std::atomic<int> g_threads{1};
#endif

}  // namespace

int max_threads() { return g_threads.load(std::memory_order_relaxed); }

void set_max_threads(int threads) {
#ifdef CRESTLINE_THREADS
  g_threads.store(std::max(1, threads), std::memory_order_relaxed);
#else
  (void)threads;
#endif
}

void parallel_for(size_t count, const std::function<void(size_t, size_t)>& body, size_t min_chunk) {
  if (count == 0) return;
  const size_t threads = std::min<size_t>(static_cast<size_t>(max_threads()), count / std::max<size_t>(min_chunk, 1));
  if (threads <= 1) {
    body(0, count);
    return;
  }
#ifdef CRESTLINE_THREADS
  // One contiguous chunk per thread: the loops are uniform, and contiguous
  // ranges keep each thread's writes on its own cache lines.
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&](size_t i) {
    try {
      body(count * i / threads, count * (i + 1) / threads);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (size_t i = 1; i < threads; ++i) pool.emplace_back(run, i);
  run(0);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
#endif
}

}  // namespace crestline
