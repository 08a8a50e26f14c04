#pragma once
// Data parallelism for the per-vertex, per-edge and per-triangle loops of the
// pipeline. Every parallel loop writes only its own elements and sums in a
// fixed order, so results are bit-identical for any thread count.
//
// Threads exist only when core is built with CRESTLINE_THREADS (the CMake
// option: ON natively, OFF under Emscripten, where the single-threaded
// module is the default); otherwise everything runs on the calling thread.
#include <cstddef>
#include <functional>

namespace crestline {

/// Threads a loop may use: the hardware's count unless set_max_threads()
/// said otherwise; always 1 without CRESTLINE_THREADS.
int max_threads();
/// Process-wide limit (like Eigen::setNbThreads); values < 1 mean 1.
void set_max_threads(int threads);

/// Calls body(begin, end) on consecutive chunks covering [0, count), on up to
/// max_threads() threads; loops shorter than 2·min_chunk stay on the caller.
/// The first exception thrown by a chunk is rethrown here.
void parallel_for(size_t count, const std::function<void(size_t begin, size_t end)>& body, size_t min_chunk = 2048);

/// Runs two serial tasks side by side: on two threads when max_threads() > 1,
/// else first() then second() on the caller. Each task writes only its own
/// results, so they are the same either way.
void run_side_by_side(const std::function<void()>& first, const std::function<void()>& second);

}  // namespace crestline
