#pragma once
// A polyline for writer tests: given type and points, curvature 1 everywhere.
#include <utility>
#include <vector>

#include "crestline/lines/polylines.h"

namespace crestline::testing {

inline Polyline test_line(LineType type, std::vector<Vec3> points, bool closed = false) {
  Polyline line;
  line.type = type;
  line.points = std::move(points);
  line.curvature.assign(line.points.size(), 1.0);
  line.closed = closed;
  return line;
}

}  // namespace crestline::testing
