#pragma once
// Paper §5.2: smoothing feature lines as space curves with a Hausdorff bound.
#include <vector>

#include "crestline/lines/polylines.h"

namespace crestline {

struct FairingOptions {
  /// Largest distance a point may move, in units of mean edge length. Since
  /// every vertex stays within it of its original position, the Hausdorff
  /// distance between faired and unfaired polyline is below it too. 0 disables.
  double hausdorff_bound = 0.25;
  /// Bi-Laplacian iterations.
  int iterations = 30;
};

/// End points (line ends and trisector junctions) stay fixed; closed lines
/// are smoothed all round.
std::vector<Polyline> fair_polylines(const std::vector<Polyline>& lines, double mean_edge_length,
                                     const FairingOptions& options);

}  // namespace crestline
