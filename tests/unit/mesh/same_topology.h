#pragma once
// Two adjacencies compared field by field (Catch2 names the field that differs).
#include <catch2/catch.hpp>

#include "crestline/mesh/topology.h"

namespace crestline::testing {

inline void check_same_topology(const Topology& a, const Topology& b) {
  CHECK(a.edges == b.edges);
  CHECK(a.edge_triangles == b.edge_triangles);
  CHECK(a.triangle_edges == b.triangle_edges);
  CHECK(a.vertex_offsets == b.vertex_offsets);
  CHECK(a.vertex_triangles == b.vertex_triangles);
  CHECK(a.boundary_vertex == b.boundary_vertex);
}

}  // namespace crestline::testing
