#pragma once
// Resident memory of this process, from /proc (Linux only; 0 elsewhere).
#include <cstddef>

namespace crestline::bench {

/// Current resident set size in bytes.
size_t current_rss();
/// Highest resident set size since the process started or since the last
/// reset_peak_rss().
size_t peak_rss();
/// Makes the peak start again from the current RSS (clear_refs 5, Linux ≥ 4.0).
/// Returns false where the kernel does not allow it.
bool reset_peak_rss();

}  // namespace crestline::bench
