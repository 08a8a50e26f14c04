#pragma once
// Paper §4 (beginning), [OBS04]: drop weak lines by their strength ∫|κ| ds.
#include <cstdint>
#include <vector>

#include "crestline/lines/polylines.h"

namespace crestline {

struct FilterOptions {
  /// Lines with strength below this are dropped. Negative: automatic, chosen
  /// from the distribution of strengths on the mesh itself, and lines both
  /// weak (strength < 1) and short (< 6 mean edges) are dropped too (see
  /// filter.cpp).
  double threshold = -1;
};

struct FilterResult {
  std::vector<uint32_t> kept;  // indices into the input lines, in order
  double threshold = 0;        // the threshold actually used
};

/// Only reads strengths and lengths: re-filtering never touches anything
/// upstream. mean_edge_length is the mesh's (the automatic threshold measures
/// line length in edges; 0 leaves length out).
FilterResult filter_lines(const std::vector<Polyline>& lines, const FilterOptions& options, double mean_edge_length);

}  // namespace crestline
