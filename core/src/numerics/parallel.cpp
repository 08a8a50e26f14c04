#include "crestline/numerics/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <vector>

#ifdef CRESTLINE_THREADS
#include <condition_variable>
#include <mutex>
#include <thread>
#endif

namespace crestline {
namespace {

#ifdef CRESTLINE_THREADS
int hardware_threads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }
std::atomic<int> g_threads{hardware_threads()};

// True on a thread while it runs a chunk of a parallel loop: a loop nested
// in one runs on that thread alone.
thread_local bool t_in_loop = false;

// Threads kept waiting between loops: the solver's sweeps start a loop per
// colour, thousands per run, and starting a thread costs tens of
// microseconds (far more for a WASM worker). One loop runs at a time; a loop
// started while another runs (from a second caller thread) runs on its
// caller alone, which gives the same results.
class Pool {
 public:
  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& worker : workers_) worker.join();
  }

  // Runs chunk(i) for i in [0, parts), chunk 0 on the caller; false if the
  // pool is busy with another caller's loop (nothing was run then).
  bool run(size_t parts, const std::function<void(size_t)>& chunk) {
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      while (workers_.size() + 1 < parts) {
        const size_t index = workers_.size() + 1;
        workers_.emplace_back([this, index] { work(index); });
      }
      chunk_ = &chunk;
      parts_ = parts;
      pending_ = parts - 1;
      error_ = nullptr;
      ++generation_;
    }
    wake_.notify_all();
    std::exception_ptr error;
    try {
      chunk(0);
    } catch (...) {
      error = std::current_exception();
    }
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return pending_ == 0; });
    chunk_ = nullptr;
    if (!error) error = error_;
    lock.unlock();
    if (error) std::rethrow_exception(error);
    return true;
  }

 private:
  void work(size_t index) {
    t_in_loop = true;
    uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    // A worker started for a loop already running takes part in it.
    seen = generation_ - 1;
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      if (index >= parts_) continue;
      const std::function<void(size_t)>* chunk = chunk_;
      lock.unlock();
      std::exception_ptr error;
      try {
        (*chunk)(index);
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      if (error && !error_) error_ = error;
      if (--pending_ == 0) done_.notify_one();
    }
  }

  std::mutex busy_;   // held by the caller of the running loop
  std::mutex mutex_;  // guards everything below
  std::condition_variable wake_, done_;
  std::vector<std::thread> workers_;  // worker i runs chunk i + 1
  const std::function<void(size_t)>* chunk_ = nullptr;
  size_t parts_ = 0, pending_ = 0;
  uint64_t generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

Pool& pool() {
  static Pool instance;
  return instance;
}
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
#ifdef CRESTLINE_THREADS
  if (threads > 1 && !t_in_loop) {
    // One contiguous chunk per thread: the loops are uniform, and contiguous
    // ranges keep each thread's writes on its own cache lines.
    const std::function<void(size_t)> chunk = [&](size_t i) {
      t_in_loop = true;
      body(count * i / threads, count * (i + 1) / threads);
    };
    struct Reset {
      ~Reset() { t_in_loop = false; }
    };
    bool ran;
    {
      const Reset reset;
      ran = pool().run(threads, chunk);
    }
    if (ran) return;
  }
#endif
  (void)threads;
  body(0, count);
}

}  // namespace crestline
