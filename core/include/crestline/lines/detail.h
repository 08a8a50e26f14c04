#pragma once
// Levels of detail for drawing lines (the page's line layer): a faired line
// has a point at every edge it crosses, far more than a view of a whole
// large mesh can show. A point's importance is the largest tolerance at
// which Douglas–Peucker keeps it, so for any tolerance ε the points of
// importance above ε draw every line within ε of all its points.
#include <vector>

#include "crestline/lines/polylines.h"

namespace crestline {

/// Per point of `lines`, in order (line 0's points, then line 1's, …), in
/// the lines' units: a line's first and last points +∞; every other one its
/// distance to the chord (as a segment) of the interval of Douglas–Peucker's
/// recursion it splits, capped by the importance of that interval's own
/// splitting point; 0 for a point no interval splits. A closed line keeps
/// its closing segment as it is. Computed in double and rounded to float by
/// the same operations in the same order as web/src/three/line-detail.js's
/// pointImportance: the same numbers.
std::vector<float> point_importance(const std::vector<Polyline>& lines);

}  // namespace crestline
