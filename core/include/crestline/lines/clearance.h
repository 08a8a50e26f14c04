#pragma once
// Smooth lines kept clear of the creases (issue 16). With crease boundaries
// (mesh/cut.h) no ridge or valley runs along or across a crease, but a line
// that meets one still ends where the tracer's band of boundary rings ends:
// 1.7–2 edges away on a regular mesh, less where rows of vertices are close.
// This stage cuts every line back to a fixed number of edge lengths from the
// creases, measured in space, so that a drawing shows a gap of about the
// same width beside every sharp edge whatever the triangulation. The edge
// length is the crease's own (the mean edge at its ends), so that a finely
// tessellated small part of a CAD model keeps the lines on its fillets.
#include <array>
#include <cstdint>
#include <vector>

#include "crestline/lines/polylines.h"

namespace crestline {

struct ClearanceOptions {
  /// Parts of smooth lines closer than this many of a crease segment's edge
  /// lengths (CreaseSegment::edge_length) to it are removed. 0 keeps every
  /// line as it is.
  double distance = 2.0;
};

/// A crease edge of one component, in the frame of the lines.
struct CreaseSegment {
  std::array<Vec3, 2> ends;
  uint32_t component = 0;
  /// The length the clearance is counted in: the mean length of the edges at
  /// the segment's two ends (Pipeline), so about an edge of the mesh there.
  double edge_length = 1;
};

struct ClearanceResult {
  /// The parts of the lines at least `distance` edge lengths from every
  /// segment of their component, in the input's order; a cut part ends
  /// exactly at the distance
  /// (found by bisection along the crossing segment, curvature interpolated
  /// there), its length and strength measured again. Lines that stay clear
  /// come out unchanged.
  std::vector<Polyline> lines;
  std::vector<uint32_t> source;  // the input line each part came from
};

/// `line_component` has the component of each line. Tests the lines' points (not their segments' interiors: a segment
/// is about an edge long) against the segments through a uniform grid; linear in the points and the segments' length.
/// Edge lengths above 8 times the median count as 8 times the median, which bounds the cells a segment fills.
ClearanceResult clear_of_creases(std::vector<Polyline> lines, const std::vector<uint32_t>& line_component,
                                 const std::vector<CreaseSegment>& segments, const ClearanceOptions& options);

}  // namespace crestline
