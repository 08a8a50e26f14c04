#include "crestline/curvature/extremality_smoothing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "crestline/curvature/shape_operator.h"
#include "crestline/error.h"
#include "crestline/mesh/cotan.h"
#include "crestline/mesh/topology.h"
#include "crestline/numerics/paired_cg.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/sparse_solver.h"

namespace crestline {
namespace {

// A relative residual of 1e-6 instead of the solver's 1e-10: on the bunny
// and the feline it flips the sign of no extremality value and moves line
// crossings by at most 0.0025 edge lengths (mean 1e-5), a hundredth of the
// fairing bound, with identical lines after filtering; it saves a third of
// the iterations. On the dragon (871k) it flips one vertex's sign and moves
// crossings by up to 0.035 edge (mean 1e-6, 99.99 % under 0.001), the same
// line counts; 1e-5 would save 8 of its 50 iterations but move up to 0.21.
constexpr double kTolerance = 1e-6;
// Lockstep CG iterations allowed on the first step before falling back to
// SpdSolver, which then factorizes ill-conditioned systems (see sparse_solver.h).
constexpr int kPairedBudget = 150;
// Progress within a step: i iterations count as i / (i + this) of the step.
constexpr double kTypicalIterations = 10;
// The most the set-up reports of the stage's progress: half the first
// iteration's fraction, 1 / (1 + kTypicalIterations) of one of `steps`, so
// that the fractions keep rising for any step count.
double setup_share(int steps) { return 0.5 / ((1 + kTypicalIterations) * steps); }

// Whether the options smooth at all: without steps or without time the
// values are returned as they are (the system then has no steps).
bool smooths(const ExtremalitySmoothingOptions& options) { return options.steps > 0 && options.time_step > 0; }

// Both fields' matrices M − t L_σ in one pattern (numerics/paired_cg.h); the
// diagonal sums in edge order exactly as smooth_field's does. Each edge's
// signs (two dot products) are found on every thread first; the additions
// to its two rows stay in edge order on the calling thread.
SignedPairMatrix signed_pair_matrix(const Topology& topology, const std::vector<double>& vertex_mass,
                                    const std::vector<double>& edge_strength, const Curvature& curvature,
                                    const std::function<void()>& pause) {
  const size_t nv = vertex_mass.size(), ne = topology.edges.size();
  SignedPairMatrix a;
  a.diagonal = vertex_mass;
  a.offsets.assign(nv + 1, 0);
  // Bit k of an edge's mask: σ = −1 in field k.
  std::vector<uint8_t> mask(ne);
  parallel_for(ne, [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e) {
      const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
      mask[e] = static_cast<uint8_t>((direction_sign(curvature.dir_max[p], curvature.dir_max[q]) > 0 ? 0u : 1u) |
                                     (direction_sign(curvature.dir_min[p], curvature.dir_min[q]) > 0 ? 0u : 2u));
    }
  });
  // Each thread takes a range of rows and reads every edge, adding to its
  // own rows only: each row's sums and entries in edge order, the same for
  // any number of threads (before: one thread, ≈ 140 M instructions at 1.1M).
  const size_t parts = static_cast<size_t>(max_threads());
  const auto by_rows = [&](const auto& add) {
    parallel_for(
        parts,
        [&](size_t first, size_t last) {
          const uint32_t low = static_cast<uint32_t>(nv * first / parts),
                         high = static_cast<uint32_t>(nv * last / parts);
          const std::array<uint32_t, 2>* const edges = topology.edges.data();
          const double* const strength = edge_strength.data();
          const auto each_edge = [&](auto all_rows) {
            for (size_t e = 0; e < ne; ++e) {
              const double w = strength[e];
              if (w == 0) continue;
              const uint32_t p = edges[e][0], q = edges[e][1];
              if (decltype(all_rows)::value || (p >= low && p < high)) add(e, p, q, w);
              if (decltype(all_rows)::value || (q >= low && q < high)) add(e, q, p, w);
            }
          };
          if (low == 0 && high == nv)  // one thread: no range to test
            each_edge(std::true_type{});
          else
            each_edge(std::false_type{});
        },
        1);
  };
  // Raw pointers in locals: a store through one may alias the vectors' own.
  uint32_t* const counts = a.offsets.data() + 1;
  double* const diagonal = a.diagonal.data();
  by_rows([=](size_t, uint32_t row, uint32_t, double w) { ++counts[row], diagonal[row] += w; });
  for (size_t v = 0; v < nv; ++v) a.offsets[v + 1] += a.offsets[v];
  pause();
  a.columns.resize(a.offsets[nv]);
  a.weights.resize(a.offsets[nv]);
  std::vector<uint32_t> fill(a.offsets.begin(), a.offsets.end() - 1);
  // The entry is −σ w: stored as −w, negated where σ = −1.
  uint32_t *const columns = a.columns.data(), *const next = fill.data();
  double* const weights = a.weights.data();
  const uint8_t* const signs = mask.data();
  by_rows([=](size_t e, uint32_t row, uint32_t column, double w) {
    const uint32_t at = next[row]++;
    columns[at] = column | uint32_t{signs[e]} << 30, weights[at] = -w;
  });
  return a;
}

// Both fields in lockstep from the system's matrix (the solver takes it
// over); false if CG does not converge (out's solver_iterations then holds
// what was spent).
bool smooth_fields_paired(ExtremalitySmoothingSystem& system, const Extremality& in,
                          const std::function<void(double)>& progress, SmoothedExtremality& out) {
  const std::vector<double>& mass = system.vertex_mass;
  const size_t nv = mass.size();
  const int steps = system.steps;
  // The set-up's parts report fractions rising towards setup_share(steps)
  // from where extremality_smoothing_system left them: a chance to cancel each.
  const double share = setup_share(steps);
  double setup = 0.75 * share;
  const auto pause = [&] {
    setup = 0.5 * (setup + share);
    if (progress) progress(setup);
  };
  pause();
  const SignedPairSolver solver(std::move(system.matrix), true, pause);
  pause();
  // The fields and masses by the solver's rows through all steps, each
  // value's arithmetic as by vertex: the permutation (random to the
  // vertices' order) is undone once, not in and out of every solve.
  const uint32_t* const vertex = solver.input_rows().data();
  std::vector<double> x(2 * nv), b(2 * nv), row_mass(nv);
  parallel_for(nv, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const size_t v = vertex[k];
      x[2 * k] = in.e_max[v], x[2 * k + 1] = in.e_min[v], row_mass[k] = mass[v];
    }
  });
  for (int step = 0; step < steps; ++step) {
    parallel_for(nv, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) {
        const double m = row_mass[k];
        b[2 * k] = m * x[2 * k], b[2 * k + 1] = m * x[2 * k + 1];
      }
    });
    const size_t before = out.solver_iterations;
    const auto on_iteration = [&](int iteration) {
      out.solver_iterations = before + static_cast<size_t>(iteration);
      if (progress) progress((step + double(iteration) / (iteration + kTypicalIterations)) / steps);
    };
    if (!solver.solve_in_solver_order(b, x, kTolerance, step == 0 ? kPairedBudget : SpdSolver().max_iterations,
                                      on_iteration))
      return false;
  }
  out.e_max.resize(nv);
  out.e_min.resize(nv);
  parallel_for(nv, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const size_t v = vertex[k];
      out.e_max[v] = x[2 * k], out.e_min[v] = x[2 * k + 1];
    }
  });
  return true;
}

// One field: (M − t L_σ) with L_σ e(p) = Σ_q w_pq (σ_pq e(q) − e(p)).
Eigen::VectorXd smooth_field(const Topology& topology, const CotanWeights& cotan,
                             const std::vector<double>& edge_strength, const std::vector<Direction>& directions,
                             const std::vector<double>& values, int steps) {
  const size_t nv = values.size();
  Triplets triplets;
  triplets.reserve(nv + 2 * topology.edges.size());
  std::vector<double> diagonal(cotan.vertex_mass);
  for (size_t e = 0; e < topology.edges.size(); ++e) {
    const double w = edge_strength[e];
    if (w == 0) continue;
    const uint32_t p = topology.edges[e][0], q = topology.edges[e][1];
    const double sigma = direction_sign(directions[p], directions[q]);
    diagonal[p] += w;
    diagonal[q] += w;
    triplets.emplace_back(p, q, -sigma * w);
    triplets.emplace_back(q, p, -sigma * w);
  }
  for (size_t v = 0; v < nv; ++v) triplets.emplace_back(v, v, diagonal[v]);
  SparseMatrix system(nv, nv);
  system.setFromTriplets(triplets.begin(), triplets.end());
  SpdSolver solver;
  solver.tolerance = kTolerance;
  solver.compute(std::move(system));

  const Eigen::Map<const Eigen::VectorXd> mass(cotan.vertex_mass.data(), nv);
  Eigen::VectorXd e = Eigen::Map<const Eigen::VectorXd>(values.data(), nv);
  for (int step = 0; step < steps; ++step) e = solver.solve(mass.cwiseProduct(e), e);
  return e;
}

// The vertex weights with the boundary band frozen (weight 0); empty without a band.
std::vector<double> banded_weights(const Mesh& mesh, const Topology& topology,
                                   const ExtremalitySmoothingOptions& options) {
  std::vector<double> banded;
  if (options.frozen_boundary_rings <= 0) return banded;
  const auto rings = static_cast<uint32_t>(options.frozen_boundary_rings);
  const std::vector<uint32_t> distance = boundary_ring_distance(mesh, topology, rings);
  banded = options.vertex_weights.empty() ? std::vector<double>(mesh.positions.size(), 1.0) : options.vertex_weights;
  for (size_t v = 0; v < distance.size() && v < banded.size(); ++v)
    if (distance[v] < rings) banded[v] = 0;
  return banded;
}

// The vertex weights the edge strengths read (banded_weights or the
// options'), checked; `banded` holds the banded ones.
const std::vector<double>& checked_weights(const Mesh& mesh, const Topology& topology,
                                           const ExtremalitySmoothingOptions& options, std::vector<double>& banded) {
  const size_t nv = mesh.positions.size();
  banded = banded_weights(mesh, topology, options);
  const std::vector<double>& weights = options.frozen_boundary_rings > 0 ? banded : options.vertex_weights;
  if (!weights.empty() && weights.size() != nv)
    throw Error(ErrorKind::InvalidInput, "the smoothing weights have " + std::to_string(weights.size()) +
                                             " values but the mesh has " + std::to_string(nv) + " vertices.");
  for (double w : weights)
    if (!(w >= 0) || !std::isfinite(w))
      throw Error(ErrorKind::InvalidInput, "smoothing weights must be finite and not negative.");
  return weights;
}

// t times each edge's cotan weight and strength: an edge is smoothed as
// strongly as its weaker end, so a region with weight 0 is frozen and
// exchanges nothing with its surroundings. Scaled in place: the cotan
// weights are not needed apart from it.
std::vector<double> edge_strengths(const Mesh& mesh, const Topology& topology, const std::vector<double>& weights,
                                   double time_step, std::vector<double> cotan_weight) {
  const double h = mean_edge_length(mesh);
  const double t = time_step * h * h;
  parallel_for(topology.edges.size(), [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e) {
      const double s = weights.empty() ? 1.0 : std::min(weights[topology.edges[e][0]], weights[topology.edges[e][1]]);
      cotan_weight[e] = t * s * cotan_weight[e];
    }
  });
  return cotan_weight;
}

}  // namespace

ExtremalitySmoothingSystem extremality_smoothing_system(const Mesh& mesh, const Topology& topology,
                                                        const Curvature& curvature,
                                                        const ExtremalitySmoothingOptions& options,
                                                        const std::function<void(double)>& progress) {
  ExtremalitySmoothingSystem system;
  if (!smooths(options)) return system;
  system.steps = options.steps;
  std::vector<double> banded;
  const std::vector<double>& weights = checked_weights(mesh, topology, options, banded);
  // Chances to cancel before and after the cotan weights, and between the
  // matrix's parts.
  const double share = setup_share(options.steps);
  if (progress) progress(0.25 * share);
  CotanWeights cotan = cotan_weights(mesh.positions, mesh, topology);
  if (progress) progress(0.5 * share);
  std::vector<double> edge_strength =
      edge_strengths(mesh, topology, weights, options.time_step, std::move(cotan.edge_weight));
  system.vertex_mass = std::move(cotan.vertex_mass);
  // Not needed beyond here (8 bytes a vertex).
  std::vector<double>().swap(banded);
  if (system.vertex_mass.size() > SignedPairMatrix::kColumnMask) return system;  // no paired solve
  system.matrix = signed_pair_matrix(topology, system.vertex_mass, edge_strength, curvature, [&] {
    if (progress) progress(0.75 * share);
  });
  return system;
}

PairedSmoothing solve_extremality_smoothing(ExtremalitySmoothingSystem system, const Extremality& extremality,
                                            const std::function<void(double)>& progress) {
  PairedSmoothing out;
  if (system.steps <= 0) {  // !smooths(options): extremality_smoothing_system left it at 0
    out.smoothed = {extremality};
    out.converged = true;
    return out;
  }
  // Both fields in lockstep wherever it converges: each matrix entry is read
  // once for both, the rows are split over the threads, and the arithmetic
  // is the same as the single-threaded WASM build's.
  if (system.matrix.rows() == system.vertex_mass.size())
    out.converged = smooth_fields_paired(system, extremality, progress, out.smoothed);
  return out;
}

SmoothedExtremality smooth_extremality_unpaired(const Mesh& mesh, const Topology& topology, const Curvature& curvature,
                                                const Extremality& extremality,
                                                const ExtremalitySmoothingOptions& options, size_t iterations_spent) {
  SmoothedExtremality out;
  out.solver_iterations = iterations_spent;
  if (!smooths(options)) {
    static_cast<Extremality&>(out) = extremality;
    return out;
  }
  const size_t nv = mesh.positions.size();
  std::vector<double> banded;
  const std::vector<double>& weights = checked_weights(mesh, topology, options, banded);
  CotanWeights cotan = cotan_weights(mesh.positions, mesh, topology);
  const std::vector<double> edge_strength =
      edge_strengths(mesh, topology, weights, options.time_step, std::move(cotan.edge_weight));
  // The two fields are independent systems: one thread each where there are two.
  const std::vector<Direction>* directions[2] = {&curvature.dir_max, &curvature.dir_min};
  const std::vector<double>* values[2] = {&extremality.e_max, &extremality.e_min};
  Eigen::VectorXd smoothed[2];
  parallel_for(
      2,
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i)
          smoothed[i] = smooth_field(topology, cotan, edge_strength, *directions[i], *values[i], options.steps);
      },
      1);
  out.e_max.assign(smoothed[0].data(), smoothed[0].data() + nv);
  out.e_min.assign(smoothed[1].data(), smoothed[1].data() + nv);
  return out;
}

SmoothedExtremality smooth_extremality(const Mesh& mesh, const Topology& topology, const Curvature& curvature,
                                       const Extremality& extremality, const ExtremalitySmoothingOptions& options,
                                       const std::function<void(double)>& progress) {
  PairedSmoothing paired = solve_extremality_smoothing(
      extremality_smoothing_system(mesh, topology, curvature, options, progress), extremality, progress);
  if (paired.converged) return std::move(paired.smoothed);
  return smooth_extremality_unpaired(mesh, topology, curvature, extremality, options,
                                     paired.smoothed.solver_iterations);
}

}  // namespace crestline
