// The pipeline's stages composed by hand with average_shape_operator after
// the curvature stage: the measurement behind the proposal to make it a
// Pipeline option (see shape_operator_averaging.h).
#include <chrono>

#include "crestline/curvature/extremality.h"
#include "crestline/curvature/shape_operator_averaging.h"
#include "crestline/lines/fairing.h"
#include "crestline/lines/filter.h"
#include "crestline/lines/singular.h"
#include "crestline/mesh/presmooth.h"
#include "quality_metrics.h"

namespace crestline::quality {

Score run_case_averaged(const Surface& surface, double noise, unsigned noise_seed, const PipelineOptions& options,
                        int rings) {
  double h = 0;
  Mesh mesh = noisy_mesh(surface, noise, noise_seed, h);
  const auto start = std::chrono::steady_clock::now();
  const Topology topology = build_topology(mesh);
  const double edge = mean_edge_length(mesh);
  mesh.positions = presmooth_surface(mesh, topology, options.presmooth);
  const Curvature curvature = average_shape_operator(mesh, topology, compute_curvature(mesh, topology), rings);
  const Regularity regularity = classify_triangles(mesh, curvature);
  // Pipeline::run freezes the boundary band the tracer leaves out.
  ExtremalitySmoothingOptions smoothing = options.smoothing;
  const uint32_t band = static_cast<uint32_t>(std::max(options.trace.boundary_rings, 0));
  const std::vector<uint32_t> distance = boundary_ring_distance(mesh, topology, band);
  if (smoothing.vertex_weights.empty()) smoothing.vertex_weights.assign(mesh.positions.size(), 1.0);
  for (size_t v = 0; v < distance.size(); ++v)
    if (distance[v] < band) smoothing.vertex_weights[v] = 0;
  const Extremality extremality =
      smooth_extremality(mesh, topology, curvature, compute_extremality(mesh, curvature), smoothing);
  const SingularResult lines = connect_singular_triangles(
      mesh, topology, regularity,
      trace_regular_triangles(mesh, topology, curvature, extremality, regularity, options.trace));
  std::vector<Polyline> all = join_polylines(lines.lines.ridges);
  for (Polyline& l : join_polylines(lines.lines.valleys)) all.push_back(std::move(l));
  all = fair_polylines(all, edge, options.fairing);
  std::vector<Polyline> kept;
  for (uint32_t i : filter_lines(all, options.filter, h).kept) kept.push_back(all[i]);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Score s = score_lines(surface, kept, h);
  s.vertices = mesh.positions.size();
  s.seconds = seconds;
  return s;
}

}  // namespace crestline::quality
