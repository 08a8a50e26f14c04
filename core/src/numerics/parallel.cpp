#include "crestline/numerics/parallel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
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
// The cores, read once (glibc's hardware_concurrency() reads a file in /sys).
const int g_cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
std::atomic<int> g_threads{g_cores};

// True on a thread while it runs a chunk of a parallel loop: a loop nested
// in one runs on that thread alone.
thread_local bool t_in_loop = false;

// Pieces a loop is cut into per thread. Each thread owns a contiguous run of
// pieces and takes them in order, then takes what is left of the others'
// runs: evenly paced threads each do their own run (the contiguous halves of
// a static split), while a thread that starts late, or is descheduled (the
// page's worker shares two cores with the browser's rasteriser), holds up
// the loop by at most the piece it is in instead of by its whole share.
constexpr size_t kPiecesPerThread = 4;

// A thread checks a few times before it sleeps (a kept thread for the
// next loop, the caller for the last piece). In WASM no longer: in the page
// the pipeline's two threads share two cores with the browser's rasteriser,
// which spinning would rob (a 50 µs spin showed no gain there). Natively it
// keeps checking for up to kSpinBeforeSleep: a sleeping thread wakes late
// here (a VM; not timed directly), and the solver starts about a thousand
// loops a run (1,030 on the dragon, acf808b's count). 1.1M triangles, 2
// threads: the pipeline 4–7 % faster with 100–700 µs of spinning than with
// 64 checks, alternated runs.
constexpr int kChecksBeforeSleep = 64;
#if defined(__EMSCRIPTEN__)
constexpr std::chrono::microseconds kSpinBeforeSleep{0};
#else
constexpr std::chrono::microseconds kSpinBeforeSleep{200};
#endif

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// True if ready() became true within kChecksBeforeSleep checks (each after a pause).
template <class Ready>
bool checked(const Ready& ready) {
  for (int i = 0; i < kChecksBeforeSleep; ++i) {
    if (ready()) return true;
    cpu_relax();
  }
  return false;
}

// True if ready() became true within kChecksBeforeSleep checks, or natively
// within kSpinBeforeSleep if `spin` (a loop on no more threads than cores:
// with more, a spinning thread would take the core of the one it waits for).
template <class Ready>
bool soon(const Ready& ready, bool spin) {
  if (checked(ready)) return true;
  if (kSpinBeforeSleep.count() > 0 && spin) {
    const auto until = std::chrono::steady_clock::now() + kSpinBeforeSleep;
    do {
      if (checked(ready)) return true;
    } while (std::chrono::steady_clock::now() < until);
  }
  return ready();
}

// Threads kept waiting between loops (starting a thread costs tens of
// microseconds, far more for a WASM worker). One loop runs at a time; a loop
// started while another runs (from a second caller thread) runs on its
// caller alone, which gives the same results.
//
// A loop is published as a generation: its pieces are claimed by
// compare-and-swap on words holding the generation, the end of a thread's
// run and its next piece, so a kept thread that wakes late cannot claim a
// piece of a loop that ended (the word's generation moved on), and a loop
// ends only once its every piece has run: what a thread reads of the loop
// after a successful claim is that loop's.
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

  // Runs chunk(p) for p in [0, pieces) on up to `threads` threads (the
  // caller and threads − 1 kept ones); false if the pool is busy with
  // another caller's loop (nothing was run then).
  bool run(size_t threads, size_t pieces, const std::function<void(size_t)>& chunk) {
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    while (workers_.size() + 1 < threads) {
      const size_t index = workers_.size() + 1;
      workers_.emplace_back([this, index] { work(index); });
    }
    const uint64_t generation = generation_.load(std::memory_order_relaxed) + 1;
    spin_.store(threads <= static_cast<size_t>(g_cores), std::memory_order_relaxed);
    chunk_.store(&chunk, std::memory_order_relaxed);
    threads_.store(threads, std::memory_order_relaxed);
    pieces_.store(pieces, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    failed_.store(false, std::memory_order_relaxed);
    for (size_t t = 0; t < threads; ++t)  // release: a claim reads the loop's description after it
      next_[t].store(word(generation, run_begin(t + 1, threads, pieces), run_begin(t, threads, pieces)),
                     std::memory_order_release);
    generation_.store(generation, std::memory_order_seq_cst);
    if (sleepers_.load(std::memory_order_seq_cst) > 0) {
      // Under the mutex: a thread between its check and its wait is not missed.
      std::lock_guard<std::mutex> lock(mutex_);
      wake_.notify_all();
    }
    take_pieces(0, generation, threads);
    const auto finished = [&] { return done_.load(std::memory_order_acquire) == pieces; };
    if (!soon(finished, spin_.load(std::memory_order_relaxed))) {
      std::unique_lock<std::mutex> lock(mutex_);
      finished_.wait(lock, finished);
    }
    std::exception_ptr error;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::swap(error, error_);
    }
    if (error) std::rethrow_exception(error);
    return true;
  }

 private:
  static constexpr size_t kMaxThreads = 64;

  static size_t run_begin(size_t t, size_t threads, size_t pieces) { return pieces * t / threads; }
  // generation (low 32 bits) << 32 | end of the run << 16 | next piece (pieces < 2^16).
  static uint64_t word(uint64_t generation, size_t end, size_t next) {
    return (generation & 0xffffffffu) << 32 | uint64_t{end} << 16 | next;
  }

  // Claims and runs pieces of loop `generation`: thread t's own run first,
  // then what is left of the others' (`threads` may be a later loop's: a
  // word of another generation is passed over). Returns once none is left.
  void take_pieces(size_t t, uint64_t generation, size_t threads) {
    for (size_t k = 0; k < threads; ++k) {
      std::atomic<uint64_t>& next = next_[(t + k) % threads];
      uint64_t w = next.load(std::memory_order_relaxed);
      for (;;) {
        if (w >> 32 != (generation & 0xffffffffu) || (w & 0xffff) >= (w >> 16 & 0xffff)) break;
        if (!next.compare_exchange_weak(w, w + 1, std::memory_order_acq_rel, std::memory_order_relaxed)) continue;
        run_piece(static_cast<size_t>(w & 0xffff));
        w = next.load(std::memory_order_relaxed);
      }
    }
  }

  // Piece p, claimed: its loop cannot end before it is counted done.
  void run_piece(size_t p) {
    const size_t pieces = pieces_.load(std::memory_order_relaxed);
    if (!failed_.load(std::memory_order_relaxed)) {
      try {
        (*chunk_.load(std::memory_order_relaxed))(p);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = std::current_exception();
        failed_.store(true, std::memory_order_relaxed);  // the pieces left are skipped
      }
    }
    if (done_.fetch_add(1, std::memory_order_acq_rel) + 1 == pieces) {
      // The last piece: the caller may be asleep, or about to be.
      std::lock_guard<std::mutex> lock(mutex_);
      finished_.notify_one();
    }
  }

  void work(size_t index) {
    t_in_loop = true;
    // A thread started for a loop already running takes part in it.
    uint64_t seen = generation_.load(std::memory_order_acquire) - 1;
    for (;;) {
      const auto published = [&] { return generation_.load(std::memory_order_seq_cst) != seen; };
      if (!soon(published, spin_.load(std::memory_order_relaxed))) {
        std::unique_lock<std::mutex> lock(mutex_);
        sleepers_.fetch_add(1, std::memory_order_seq_cst);
        wake_.wait(lock, [&] { return stop_ || published(); });
        sleepers_.fetch_sub(1, std::memory_order_relaxed);
        if (stop_) return;
      }
      seen = generation_.load(std::memory_order_acquire);
      const size_t threads = threads_.load(std::memory_order_relaxed);
      if (index < threads) take_pieces(index, seen, threads);
    }
  }

  std::mutex busy_;                   // held by the caller of the running loop
  std::vector<std::thread> workers_;  // kept thread i owns run i of a loop
  // The running loop.
  std::atomic<uint64_t> generation_{0};
  std::atomic<const std::function<void(size_t)>*> chunk_{nullptr};
  std::atomic<size_t> threads_{0}, pieces_{0}, done_{0};
  std::atomic<bool> failed_{false};
  std::atomic<bool> spin_{false};  // the latest loop fits on the cores: threads waiting after it spin first (soon)
  std::atomic<uint64_t> next_[kMaxThreads] = {};  // per run (see word())
  std::atomic<int> sleepers_{0};
  std::mutex mutex_;  // guards error_, stop_ and the sleeps
  std::condition_variable wake_, finished_;
  std::exception_ptr error_;
  bool stop_ = false;
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
  const size_t most = count / std::max<size_t>(min_chunk, 1);
  const size_t threads = std::min<size_t>({static_cast<size_t>(max_threads()), most, 64});
#ifdef CRESTLINE_THREADS
  if (threads > 1 && !t_in_loop) {
    // Contiguous pieces, each at least min_chunk long; each thread's run of
    // them contiguous too, so that its writes stay on its own cache lines.
    const size_t pieces = std::min(most, threads * kPiecesPerThread);
    const std::function<void(size_t)> chunk = [&](size_t p) {
      t_in_loop = true;
      body(count * p / pieces, count * (p + 1) / pieces);
    };
    struct Reset {
      ~Reset() { t_in_loop = false; }
    };
    bool ran;
    {
      const Reset reset;
      ran = pool().run(threads, pieces, chunk);
    }
    if (ran) return;
  }
#endif
  (void)threads;
  body(0, count);
}

void run_side_by_side(const std::function<void()>& first, const std::function<void()>& second) {
  parallel_for(
      2,
      [&](size_t begin, size_t end) {
        for (size_t task = begin; task < end; ++task) (task == 0 ? first : second)();
      },
      1);
}

}  // namespace crestline
