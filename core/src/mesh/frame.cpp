#include "crestline/mesh/frame.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "crestline/mesh/topology.h"

namespace crestline {

uint32_t ComponentFrames::largest() const {
  return static_cast<uint32_t>(std::max_element(triangle_count.begin(), triangle_count.end()) - triangle_count.begin());
}

ComponentFrames component_frames(const Mesh& mesh) {
  const size_t nv = mesh.positions.size();
  std::vector<uint32_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Triangle& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) {
      const uint32_t a = find(t[0]), b = find(t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  ComponentFrames f;
  f.vertex_component.assign(nv, kNone);
  std::vector<uint32_t> root_component(nv, kNone);
  for (const Triangle& t : mesh.triangles)
    for (uint32_t v : t) {
      uint32_t& c = root_component[find(v)];
      if (c == kNone) c = static_cast<uint32_t>(f.triangle_count.size()), f.triangle_count.push_back(0);
      f.vertex_component[v] = c;
    }
  for (const Triangle& t : mesh.triangles) ++f.triangle_count[f.vertex_component[t[0]]];
  const size_t n = f.triangle_count.size();
  // Unreferenced vertices (none after repair) join component 0.
  for (uint32_t& c : f.vertex_component)
    if (c == kNone) c = 0;

  // Centre: the bounding box's, halved before adding so it cannot overflow.
  std::vector<Vec3> lo(n, Vec3::Constant(INFINITY)), hi(n, Vec3::Constant(-INFINITY));
  for (size_t v = 0; v < nv; ++v) {
    const uint32_t c = f.vertex_component[v];
    lo[c] = lo[c].cwiseMin(mesh.positions[v]), hi[c] = hi[c].cwiseMax(mesh.positions[v]);
  }
  f.centre.resize(n);
  std::vector<double> extent(n, 0.0);
  for (size_t c = 0; c < n; ++c) {
    f.centre[c] = 0.5 * lo[c] + 0.5 * hi[c];
    extent[c] = std::max((hi[c] - f.centre[c]).maxCoeff(), (f.centre[c] - lo[c]).maxCoeff());
    if (!(extent[c] > 0)) extent[c] = 1;  // a single point: nothing to scale
  }
  // Mean edge length on coordinates divided by the extent (|y| ≤ 1: squares
  // neither overflow nor underflow), then scaled back.
  std::vector<double> sum(n, 0.0);
  for (const Triangle& t : mesh.triangles) {
    const uint32_t c = f.vertex_component[t[0]];
    for (int k = 0; k < 3; ++k) sum[c] += ((mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]) / extent[c]).norm();
  }
  f.scale.resize(n);
  for (size_t c = 0; c < n; ++c) {
    const double mean = f.triangle_count[c] ? sum[c] / (3.0 * f.triangle_count[c]) : 0;
    f.scale[c] = mean > 0 ? extent[c] * mean : extent[c];
  }
  return f;
}

Mesh to_local(const Mesh& mesh, const ComponentFrames& frames) {
  Mesh local;
  local.triangles = mesh.triangles;
  local.positions.resize(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const uint32_t c = frames.vertex_component[v];
    local.positions[v] = (mesh.positions[v] - frames.centre[c]) / frames.scale[c];
  }
  return local;
}

}  // namespace crestline
