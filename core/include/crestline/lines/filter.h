#pragma once
// Paper §4 (beginning), [OBS04]: drop weak lines by their strength ∫|κ| ds.
#include <cstdint>
#include <optional>
#include <vector>

#include "crestline/lines/polylines.h"

namespace crestline {

struct FilterOptions {
  /// Lines with strength below this are dropped. std::nullopt: automatic,
  /// chosen from the distribution of strengths on the mesh itself (see
  /// filter.cpp).
  std::optional<double> threshold;
  /// Lines that are weak (strength < kWeakStrength) must also be at least
  /// this long, in mean edge lengths; 0 keeps weak short lines. Applied
  /// whatever the threshold's mode, so an automatic threshold and the same
  /// value set by hand keep the same lines.
  double short_line_edges = 6.0;
};

/// Below this strength a line counts as weak for FilterOptions::short_line_edges.
constexpr double kWeakStrength = 1.0;

struct FilterResult {
  std::vector<uint32_t> kept;  // indices into the input lines, in order
  double threshold = 0;        // the threshold actually used
};

/// Only reads strengths and lengths: re-filtering never touches anything
/// upstream. mean_edge_length is the mesh's (the automatic threshold measures
/// line length in edges; 0 leaves length out).
FilterResult filter_lines(const std::vector<Polyline>& lines, const FilterOptions& options, double mean_edge_length);

}  // namespace crestline
