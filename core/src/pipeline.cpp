#include "crestline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <utility>

#include "crestline/parameters.h"
#include "mesh/parts.h"

namespace crestline {
namespace {

class StageTimer {
 public:
  StageTimer(double& seconds) : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() { seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

// A line from the working frame to the input's coordinates.
Polyline to_user(Polyline line, const ComponentFrames& frames, uint32_t component) {
  const double scale = frames.scale[component];
  for (Vec3& p : line.points) p = frames.to_user(p, component);
  for (double& k : line.curvature) k /= scale;
  line.length *= scale;
  return line;
}

}  // namespace

const char* stage_name(Stage stage) {
  static const char* names[] = {"presmooth", "curvature", "extremality", "regularity", "smoothing", "tracing",
                                "singular",  "polylines", "fairing",     "filter",     "creases"};
  const int i = static_cast<int>(stage);
  return i >= 0 && i < static_cast<int>(Stage::Count) ? names[i] : "unknown";
}

Pipeline::Pipeline(Mesh mesh) : Pipeline(std::move(mesh), Topology()) {}

Pipeline::Pipeline(Mesh mesh, Topology topology) : Pipeline(std::move(mesh), std::move(topology), {}) {}

Pipeline::Pipeline(Mesh mesh, Topology topology, VertexComponents components)
    : input_(std::move(mesh)), topology_(std::move(topology)) {
  // All the constructor's work, so that --stats accounts for it: the
  // adjacency and components (unless repair_mesh's are given), frames and
  // noise levels.
  StageTimer timer(topology_seconds_);
  if (topology_.triangle_edges.size() != input_.triangles.size()) {
    topology_ = build_topology(input_);
    components = {};  // not this mesh's either
  }
  topology_valid_ = true;
  frames_ = component_frames(input_, topology_, std::move(components));
  const Mesh& local = local_input();
  double sum = 0;
  size_t count = 0;
  for (size_t c = 0; c < frames_.count(); ++c)
    sum += frames_.scale[c] * frames_.triangle_count[c], count += frames_.triangle_count[c];
  mean_edge_ = count ? sum / count : 0;
  noise_levels_ = surface_noise_levels(local, topology_, frames_.vertex_component, frames_.count());
  // With one component every vertex's is 0 (frames_.component()): not kept
  // (4 bytes a vertex).
  if (frames_.count() == 1) frames_.vertex_component = std::vector<uint32_t>();
}

const Topology& Pipeline::topology() const {
  if (!topology_valid_) topology_ = build_topology(input()), topology_valid_ = true;
  // Without a cut it is also the working adjacency, whose triangle lists a run releases.
  if (!cut_active_) restore_triangle_lists(local_input_valid_ ? local_input_ : input(), topology_);
  return topology_;
}

const Topology& Pipeline::working_topology() const {
  if (!cut_active_) return topology();
  restore_triangle_lists(cut_.mesh, cut_topology_);
  return cut_topology_;
}

std::vector<Triangle> Pipeline::input_triangles() const {
  if (!input_.triangles.empty()) return input_.triangles;
  // The working frame's copy has the same triangles.
  if (!cut_active_) return local_input_.triangles;
  // So has the cut mesh, some corners moved to a copy of their vertex.
  std::vector<Triangle> triangles = cut_.mesh.triangles;
  for (Triangle& t : triangles)
    for (uint32_t& v : t) v = cut_.source(v);
  return triangles;
}

const Mesh& Pipeline::input() const {
  if (input_.triangles.empty()) input_.triangles = input_triangles();
  return input_;
}

const Mesh& Pipeline::surface() const {
  if (!presmoothed_) return input();
  // Nothing in the pipeline reads it: made here, not kept by a run (24 bytes
  // per triangle through the smoothing's solves).
  if (surface_.triangles.empty() && working_surface_.positions.size() >= input_.positions.size()) {
    surface_.triangles = input_triangles();
    surface_.positions.resize(input_.positions.size());
    for (size_t v = 0; v < surface_.positions.size(); ++v)
      surface_.positions[v] = frames_.to_user(working_surface_.positions[v], frames_.component(v));
  }
  return surface_;
}

const Mesh& Pipeline::local_input() {
  if (!local_input_valid_) local_input_ = to_local(input(), frames_), local_input_valid_ = true;
  return local_input_;
}

void Pipeline::release_local_input() {
  // While the cut mesh serves the smooth stages, the input in the working
  // frame is needed only to measure and select creases: rebuilt then (the
  // same bytes), not kept (24 bytes per triangle).
  if (cut_active_) local_input_ = Mesh(), local_input_valid_ = false;
}

void Pipeline::release_smooth_geometry() {
  // The input's positions in the working frame, or the cut's, whose copies
  // sit where their vertices do (cut.h): both follow from input_ and the
  // frames. Not the pre-smoothed surface's, which would take its smoothing again.
  Mesh& mesh = cut_active_ ? cut_.mesh : local_input_;
  mesh.positions = std::vector<Vec3>();
  Topology& topology = smooth_topology();
  released_edges_ = topology.edges.size();
  topology.edges = std::vector<std::array<uint32_t, 2>>();
}

void Pipeline::restore_smooth_geometry() {
  Mesh& mesh = cut_active_ ? cut_.mesh : local_input_;
  if (mesh.positions.empty() && !input_.positions.empty()) {
    // to_local without copying the input's triangles (a run has released them).
    std::vector<Triangle> triangles = std::move(input_.triangles);
    std::vector<Vec3> positions = to_local(input_, frames_).positions;
    input_.triangles = std::move(triangles);
    mesh.positions = cut_active_ ? on_cut_vertices(cut_, std::move(positions)) : std::move(positions);
  }
  // Each edge is some triangle's side, (smaller end, larger end); written
  // on one thread, as an edge's two triangles write it both.
  Topology& topology = smooth_topology();
  if (!topology.edges.empty() || released_edges_ == 0) return;
  topology.edges.resize(released_edges_);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      topology.edges[topology.triangle_edges[t][k]] = {std::min(a, b), std::max(a, b)};
    }
  released_edges_ = 0;
}

void Pipeline::mark_dirty(Stage from) {
  if (static_cast<int>(from) < static_cast<int>(first_dirty_)) first_dirty_ = from;
}

void Pipeline::set_options(const PipelineOptions& o) {
  // The parameter table knows which stage each option feeds; shape-operator
  // averaging is not a user parameter (the quality harness sets it).
  Stage changed = first_changed_stage(options_, o);
  if (o.averaging.rings != options_.averaging.rings) changed = std::min(changed, Stage::Curvature);
  if (changed != Stage::Count) mark_dirty(changed);
  // The creases depend on nothing upstream: their own flags (run() reports them last).
  if (o.creases.normal_filter_steps != options_.creases.normal_filter_steps)
    crease_angles_valid_ = false, creases_dirty_ = true, boundaries_dirty_ = true;
  if (o.creases.angle != options_.creases.angle || o.creases.max_turn != options_.creases.max_turn)
    creases_dirty_ = true;
  // The boundary creases do not depend on the crease angle (a selection).
  if (o.creases.max_turn != options_.creases.max_turn || o.creases.boundaries != options_.creases.boundaries)
    boundaries_dirty_ = true;
  options_ = o;
}

void Pipeline::measure_creases(const std::function<void(double)>& progress) {
  if (crease_angles_valid_ && crease_angles_compact_) {
    CreaseAngles& a = crease_angles_;
    a.angle.assign(crease_edge_count_, 0.0);
    a.support.assign(crease_edge_count_, 0.0);
    for (const CreaseEdge& c : crease_edges_) a.angle[c.edge] = c.angle, a.support[c.edge] = c.support;
    crease_edges_ = std::vector<CreaseEdge>(), crease_angles_compact_ = false;
  }
  if (crease_angles_valid_) return;
  crease_edges_ = std::vector<CreaseEdge>(), crease_angles_compact_ = false;
  // Measured on the input mesh (pre-smoothing rounds creases) in the working
  // frame (angles do not depend on it, but the normals of a model at 1e-100
  // would underflow), the automatic filter decided by the largest
  // component's noise level, as stats() reports it.
  CreaseMeasureOptions measure{options_.creases.normal_filter_steps};
  const double noise = noise_levels_.empty() ? 0.0 : noise_levels_[frames_.largest()];
  if (measure.normal_filter_steps < 0) measure.normal_filter_steps = automatic_normal_filter_steps(noise);
  // With one component its level (`noise`) is the whole mesh's, which the stage would measure again.
  if (frames_.count() == 1 && !noise_levels_.empty()) measure.noise_level = noise;
  // The frames measured every edge: the median one is theirs.
  measure.median_edge_length = frames_.median_edge_length;
  crease_angles_ = measure_crease_angles(local_input(), topology(), measure, progress);
  // Where the filter does not run the stage measures no noise, but the
  // automatic angle asks whether the mesh is piecewise planar.
  if (!crease_angles_.noise_measured && !noise_levels_.empty()) {
    crease_angles_.noise_level = noise;
    crease_angles_.noise_measured = true;
  }
  crease_angles_valid_ = true;
}

void Pipeline::compact_crease_angles() {
  // Kept through the smooth stages when no cut serves, for a new crease angle
  // to select from; but most edges turn by less than 20°, stored as 0, so
  // only the others are (24 bytes per triangle less on a scan), and
  // measure_creases() rebuilds the arrays, the same bits.
  CreaseAngles& a = crease_angles_;
  if (!crease_angles_valid_ || crease_angles_compact_ || a.angle.size() != a.support.size()) return;
  auto kept = [&a](size_t e) {
    auto nonzero = [](double x) { return x != 0 || std::signbit(x); };
    return nonzero(a.angle[e]) || nonzero(a.support[e]);
  };
  size_t count = 0;
  for (size_t e = 0; e < a.angle.size(); ++e) count += kept(e);
  if (count * sizeof(CreaseEdge) >= a.angle.size() * 2 * sizeof(double)) return;  // no smaller
  crease_edges_.reserve(count);
  for (size_t e = 0; e < a.angle.size(); ++e)
    if (kept(e)) crease_edges_.push_back({static_cast<uint32_t>(e), a.angle[e], a.support[e]});
  crease_edge_count_ = a.angle.size();
  a.angle = std::vector<double>(), a.support = std::vector<double>();
  crease_angles_compact_ = true;
}

// The crease selection's checkpoints: the measure's progress at its end
// (the selection follows it; its time is not known beforehand).
static std::function<void()> at_measure_end(const std::function<void(double)>& measure_progress) {
  if (!measure_progress) return {};
  return [&measure_progress] { measure_progress(1.0); };
}

Pipeline::BoundarySelection Pipeline::select_boundaries(const std::function<void(double)>& measure_progress) {
  BoundarySelection out;
  if (!boundaries_dirty_) return out;
  const Topology& topology = this->topology();
  std::vector<uint32_t> edges;
  if (options_.creases.boundaries) {
    measure_creases(measure_progress);
    CreaseOptions automatic = options_.creases;
    automatic.angle = -1;
    CreaseResult selected =
        select_creases(local_input(), topology, crease_angles_, automatic, 1.0, at_measure_end(measure_progress));
    edges = selected.edges;
    // With the automatic angle the creases stage selects exactly these: kept for it.
    if (options_.creases.angle < 0 && creases_dirty_) out.automatic = std::move(selected);
    // Not on noisy components, where creases are not to be trusted.
    edges.erase(std::remove_if(edges.begin(), edges.end(),
                               [&](uint32_t e) {
                                 const uint32_t c = frames_.component(topology.edges[e][0]);
                                 return noise_levels_[c] > kBoundaryNoiseLimit;
                               }),
                edges.end());
    std::sort(edges.begin(), edges.end());
  }
  boundaries_dirty_ = false;
  if (edges != boundary_edges_) out.changed = std::move(edges);
  return out;
}

void Pipeline::measure_boundary_segments(const Topology& topology, const Mesh& local) {
  // The mean length of the edges at each end vertex, over both ends
  // (a slot per crease vertex: they are few).
  constexpr uint32_t kNone = ~0u;
  std::vector<uint32_t> slot(local.positions.size(), kNone);
  std::vector<double> sum;
  std::vector<uint32_t> count;
  for (uint32_t e : boundary_edges_)
    for (uint32_t v : topology.edges[e])
      if (slot[v] == kNone) slot[v] = static_cast<uint32_t>(sum.size()), sum.push_back(0), count.push_back(0);
  // The edges at them found on every thread (at 1.1M triangles the scan was
  // ≈ 4 ms of the calling thread alone on 2), added in edge order.
  const std::vector<uint32_t> at_ends = detail::indices_where(topology.edges.size(), [&](size_t e) {
    return slot[topology.edges[e][0]] != kNone || slot[topology.edges[e][1]] != kNone;
  });
  for (uint32_t e : at_ends) {
    const auto [a, b] = topology.edges[e];
    const double length = (local.positions[b] - local.positions[a]).norm();
    for (uint32_t v : {a, b})
      if (slot[v] != kNone) sum[slot[v]] += length, ++count[slot[v]];
  }
  // At most the component's mean edge (1 in the working frame): the long
  // fans of a CAD tessellation's flat faces would push lines off whole faces.
  boundary_segments_.clear();
  for (uint32_t e : boundary_edges_) {
    const auto [a, b] = topology.edges[e];
    const double edge = std::min(1.0, (sum[slot[a]] + sum[slot[b]]) / (count[slot[a]] + count[slot[b]]));
    boundary_segments_.push_back({{local.positions[a], local.positions[b]}, frames_.component(a), edge});
  }
}

void Pipeline::cut_along_boundaries(std::vector<uint32_t> edges) {
  boundary_edges_ = std::move(edges);
  mark_dirty(Stage::Presmooth);
  input();  // its triangles back from the cut before the cut goes
  cut_ = CutMesh(), cut_active_ = false, cut_topology_ = Topology();
  // The cut takes over the input's mesh in the working frame and its
  // adjacency (no copy of either: at 1.1M triangles 24 and 50 bytes per
  // triangle); they are rebuilt, the same, when asked for again.
  const Topology& topology = this->topology();
  measure_boundary_segments(topology, local_input());
  local_input_valid_ = false;
  cut_ = cut_along_edges(std::move(local_input_), topology, boundary_edges_);
  // Without copies the cut changed nothing: the input's mesh and adjacency
  // serve, and the smooth stages run exactly as without creases.
  cut_active_ = !cut_.copy_of.empty();
  if (!cut_active_) {
    local_input_ = std::move(cut_.mesh), local_input_valid_ = true;
    cut_ = CutMesh();
    return;
  }
  topology_valid_ = false;
  cut_topology_ = cut_topology(std::move(topology_), cut_);
}

double Pipeline::select_crease_lines(std::optional<CreaseResult> automatic,
                                     const std::function<void(double)>& measure_progress) {
  double seconds = 0;
  {
    StageTimer timer(seconds);
    measure_creases(measure_progress);
    // In the working frame (every component's mean edge 1, as the spur and
    // turn lengths expect), then mapped back per component.
    creases_ = automatic ? std::move(*automatic)
                         : select_creases(local_input(), topology(), crease_angles_, options_.creases, 1.0,
                                          at_measure_end(measure_progress));
    for (size_t i = 0; i < creases_.lines.size(); ++i) {
      const uint32_t component = frames_.component(creases_.line_vertex[i]);
      creases_.lines[i] = to_user(std::move(creases_.lines[i]), frames_, component);
    }
  }
  return seconds;
}

void Pipeline::run(const ProgressCallback& progress) {
  // Progress inside a stage; cancelling there abandons the stage.
  auto within = [&](Stage stage) {
    std::function<void(double)> report;
    if (progress)
      report = [&progress, stage](double fraction) {
        if (!progress(stage, fraction)) throw Cancelled();
      };
    return report;
  };
  const bool boundaries_due = boundaries_dirty_;
  const bool creases_due = creases_dirty_;
  double boundary_seconds = 0;
  double crease_seconds = 0;
  // The creases are selected now, while the input's adjacency and crease
  // angles are at hand (the boundaries read them too), and before the cut
  // along the boundary creases takes the adjacency over, so that while a cut
  // serves the smooth stages these need not be held through them: released
  // (at 1.1M triangles 50 and 24 bytes per triangle), rebuilt the same when
  // the crease options change (a new crease angle then takes the adjacency
  // and the measure again) or an SVG asks for the adjacency.
  double cut_seconds = 0;
  // The creases stage starts here, where its work is done (a measure over
  // every edge, seconds on a noisy scan), so that its progress and a cancel
  // come before the smooth stages, not after them; the measure reports its
  // fractions as the stage's up to kCreaseMeasureShare, the selections at
  // kCreaseMeasureShare (between their rounds and bridge walks). Without creases due
  // (a boundary option changed) a measure reports fractions but no start.
  constexpr double kCreaseMeasureShare = 0.9;
  if (creases_due && progress && !progress(Stage::Creases, 0.0)) throw Cancelled();
  std::function<void(double)> measure_progress;
  if (progress)
    measure_progress = [&](double fraction) {
      if (!progress(Stage::Creases, kCreaseMeasureShare * fraction)) throw Cancelled();
    };
  {
    BoundarySelection boundaries;
    {
      StageTimer timer(boundary_seconds);
      boundaries = select_boundaries(measure_progress);
    }
    if (creases_due) crease_seconds = select_crease_lines(std::move(boundaries.automatic), measure_progress);
    if (boundaries.changed) {
      StageTimer timer(cut_seconds);
      cut_along_boundaries(std::move(*boundaries.changed));
    }
  }  // an unused boundary selection is freed here, before the smooth stages
  if (cut_active_) {
    topology_ = Topology(), topology_valid_ = false;
    crease_angles_ = CreaseAngles(), crease_angles_valid_ = false;
  } else {
    compact_crease_angles();
  }
  release_local_input();
  // The input's triangles too: the mesh the smooth stages run on (the
  // working frame's copy or the cut) has them; input() rebuilds them, the
  // same (12 bytes per triangle).
  input_.triangles = std::vector<Triangle>();
  surface_ = Mesh();  // so is the pre-smoothed one in the input's coordinates (surface())
  // The working adjacency's triangle lists are read by the stages up to the
  // curvature, which releases them (26 bytes per triangle less through the
  // smoothing's solves): restored, the same, only when one of those re-runs.
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Curvature))
    restore_triangle_lists(smooth_input(), smooth_topology());
  else
    release_triangle_lists(smooth_topology());
  // The line graphs are rebuilt whenever tracing re-runs: released now, not
  // held through the smoothing solves, the peak of a re-run.
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Tracing)) singular_ = SingularResult();
  // So are the per-vertex fields a stage is about to recompute: not held
  // beside their new values (at 1.1M triangles the old curvature is 48 bytes
  // per triangle, each extremality 8).
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Smoothing)) extremality_ = SmoothedExtremality();
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Regularity)) regularity_ = Regularity();
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Extremality)) raw_extremality_ = Extremality();
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Curvature)) curvature_ = Curvature();
  // And the lines (three copies, ≈ 15 bytes per triangle at 1.1M), which a
  // re-smoothing would otherwise hold through its solves; the filter's
  // indices go with the lines they index.
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Polylines))
    joined_ = std::vector<Polyline>(), line_component_ = std::vector<uint32_t>();
  if (static_cast<int>(first_dirty_) <= static_cast<int>(Stage::Fairing))
    faired_local_ = std::vector<Polyline>(), faired_ = std::vector<Polyline>(), filtered_ = FilterResult();
  auto step = [&](Stage stage, auto&& work) {
    if (static_cast<int>(stage) < static_cast<int>(first_dirty_)) return;
    if (progress && !progress(stage, 0.0)) throw Cancelled();
    {
      StageTimer timer(seconds_[static_cast<int>(stage)]);
      work();
    }
    // The stage is done: a cancel after this point keeps it.
    first_dirty_ = static_cast<Stage>(static_cast<int>(stage) + 1);
  };

  step(Stage::Presmooth, [&] {
    const PresmoothOptions& presmooth = options_.presmooth;
    presmooth_steps_.assign(frames_.count(), 0);
    for (size_t c = 0; c < frames_.count(); ++c)
      if (presmooth.time_step > 0)
        presmooth_steps_[c] = presmooth.steps ? *presmooth.steps : automatic_presmooth_steps(noise_levels_[c]);
    presmoothed_ = *std::max_element(presmooth_steps_.begin(), presmooth_steps_.end()) > 0;
    // The last run's surface is not held through this one's solves; without
    // pre-smoothing there are no copies: surface() and working_surface() are
    // the input then (48 bytes per triangle less).
    working_surface_ = Mesh();
    if (!presmoothed_) return;
    const Mesh& in = smooth_input();
    std::vector<int> vertex_steps(in.positions.size());
    for (size_t v = 0; v < vertex_steps.size(); ++v)
      vertex_steps[v] = presmooth_steps_[frames_.component(cut_active_ ? cut_.source(uint32_t(v)) : v)];
    // The triangle lists, which pre-smoothing does not read, are released
    // through its solves and restored for the curvature (26 bytes per
    // triangle; a cancel leaves them to the next run, which restores them);
    // the triangles are copied after them (12).
    release_triangle_lists(smooth_topology());
    working_surface_.positions =
        presmooth_surface(in, smooth_topology(), presmooth.time_step, vertex_steps, within(Stage::Presmooth));
    restore_triangle_lists(in, smooth_topology());
    working_surface_.triangles = in.triangles;
    // Each side of a crease smooths its copy of a crease vertex along the
    // crease; they meet again at the mean.
    if (cut_active_) merge_copies(cut_, working_surface_.positions);
  });
  const Mesh& surface = working_surface();
  Topology& topology = smooth_topology();
  step(Stage::Curvature, [&] {
    curvature_ = compute_curvature(surface, topology, within(Stage::Curvature));
    if (options_.averaging.rings > 0)
      curvature_ = average_shape_operator(surface, topology, curvature_, options_.averaging.rings);
    release_triangle_lists(topology);
  });
  step(Stage::Extremality, [&] {
    raw_extremality_ = compute_extremality(surface, curvature_, within(Stage::Extremality));
    // No later stage reads the normals or star areas, and no option re-runs
    // this stage without the curvature one: released (16 bytes per triangle).
    // Assigning a new vector frees; `= {}` would only clear (it keeps the capacity).
    curvature_.vertex_normals = std::vector<Vec3>();
    curvature_.star_area = std::vector<double>();
  });
  step(Stage::Regularity, [&] { regularity_ = classify_triangles(surface, curvature_); });
  step(Stage::Smoothing, [&] {
    ExtremalitySmoothingOptions smoothing = options_.smoothing;
    smoothing.frozen_boundary_rings = options_.trace.boundary_rings;
    // Weights are painted on the input's vertices; the copies a crease cut
    // made take the weight of the vertex they split from.
    std::vector<double>& weights = smoothing.vertex_weights;
    if (cut_active_ && weights.size() == cut_.input_vertices) weights = on_cut_vertices(cut_, std::move(weights));
    const std::function<void(double)> report = within(Stage::Smoothing);
    ExtremalitySmoothingSystem system = extremality_smoothing_system(surface, topology, curvature_, smoothing, report);
    // The solves read neither the positions nor the edges: released through
    // them (at 1.1M triangles 24 bytes per triangle at the run's peak) and
    // made again, the same, after them or a cancel.
    release_smooth_geometry();
    PairedSmoothing paired;
    try {
      paired = solve_extremality_smoothing(std::move(system), raw_extremality_, report);
    } catch (...) {
      restore_smooth_geometry();
      throw;
    }
    restore_smooth_geometry();
    extremality_ = paired.converged ? std::move(paired.smoothed)
                                    : smooth_extremality_unpaired(surface, topology, curvature_, raw_extremality_,
                                                                  smoothing, paired.smoothed.solver_iterations);
  });
  step(Stage::Tracing, [&] {
    traced_ = trace_regular_triangles(surface, topology, curvature_, extremality_, regularity_, options_.trace,
                                      within(Stage::Tracing));
  });
  // The traced graphs move into the singular stage's result instead of being
  // copied (≈ 13 bytes per triangle, kept until the next run). Nothing else
  // reads them, and the singular stage runs again only after tracing has, or
  // after a cancel before it started, when they are still here.
  // Polylines need neither the per-edge node index nor the excluded
  // triangles: released (≈ 7 bytes per triangle).
  step(Stage::Singular, [&] {
    singular_ = connect_singular_triangles(surface, topology, regularity_, std::move(traced_));
    singular_.lines.ridges.edge_node = std::vector<uint32_t>();
    singular_.lines.valleys.edge_node = std::vector<uint32_t>();
    singular_.lines.excluded = std::vector<uint8_t>();
  });
  step(Stage::Polylines, [&] {
    PolylinesInput input;
    if (presmoothed_) input.place_on = &smooth_input();
    // The components of the cut's vertices, made here (each copy is its
    // vertex's) rather than kept through the solves; one component needs none.
    std::vector<uint32_t> cut_components;
    if (cut_active_ && frames_.count() > 1) cut_components = on_cut_vertices(cut_, frames_.vertex_component);
    input.vertex_component = cut_active_ ? &cut_components : &frames_.vertex_component;
    input.components = frames_.count();
    PolylinesResult joined = build_polylines(singular_.lines.ridges, singular_.lines.valleys, surface, topology, input);
    if (cut_active_ && options_.clearance.distance > 0) {
      ClearanceResult clear =
          clear_of_creases(std::move(joined.lines), joined.component, boundary_segments_, options_.clearance);
      for (uint32_t& source : clear.source) source = joined.component[source];
      joined.lines = std::move(clear.lines), joined.component = std::move(clear.source);
    }
    joined_ = std::move(joined.lines);
    line_component_ = std::move(joined.component);
  });
  // In the working frame every component's mean edge length is 1.
  step(Stage::Fairing, [&] {
    faired_local_ = fair_polylines(joined_, 1.0, options_.fairing);
    faired_.resize(faired_local_.size());
    for (size_t i = 0; i < faired_.size(); ++i) faired_[i] = to_user(faired_local_[i], frames_, line_component_[i]);
  });
  step(Stage::Filter, [&] {
    if (frames_.count() == 1) {
      filtered_ = filter_lines(faired_local_, options_.filter, 1.0);
      return;
    }
    // The automatic threshold is each component's own: lines grouped by
    // component (a stable sort keeps their order within one).
    std::vector<uint32_t> order(faired_local_.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return line_component_[a] < line_component_[b]; });
    const uint32_t largest = frames_.largest();
    filtered_ = filter_lines({}, options_.filter, 1.0);  // the largest component's if it has no lines
    std::vector<Polyline> lines;
    for (size_t begin = 0, end = 0; begin < order.size(); begin = end) {
      const uint32_t c = line_component_[order[begin]];
      lines.clear();
      for (end = begin; end < order.size() && line_component_[order[end]] == c; ++end)
        lines.push_back(faired_local_[order[end]]);
      const FilterResult part = filter_lines(lines, options_.filter, 1.0);
      for (uint32_t k : part.kept) filtered_.kept.push_back(order[begin + k]);
      if (c == largest) filtered_.threshold = part.threshold;
    }
    std::sort(filtered_.kept.begin(), filtered_.kept.end());
  });
  if (creases_due || boundaries_due) {
    // Outside step(): no other stage makes it dirty, and a new crease angle
    // re-runs nothing else. Its work was done before the smooth stages; it
    // is done here, last, as the stage order says (a cancel before this
    // point leaves it dirty: the next run selects again). Its time includes
    // the measure and the boundary creases' selection, cut and adjacency, so
    // that the stages account for the whole run.
    seconds_[static_cast<int>(Stage::Creases)] = crease_seconds + boundary_seconds + cut_seconds;
    creases_dirty_ = false;
  }
}

std::vector<Polyline> Pipeline::lines() const {
  std::vector<Polyline> out;
  out.reserve(filtered_.kept.size());
  for (uint32_t i : filtered_.kept) out.push_back(faired_[i]);
  return out;
}

std::vector<Polyline> Pipeline::all_kinds() const {
  std::vector<Polyline> out = lines();
  out.insert(out.end(), creases_.lines.begin(), creases_.lines.end());
  return out;
}

PipelineStats Pipeline::stats() const {
  PipelineStats s;
  s.vertices = input_.positions.size();
  s.triangles = smooth_input().triangles.size();
  s.singular_max = regularity_.singular_max;
  s.singular_min = regularity_.singular_min;
  for (uint32_t i : filtered_.kept) {
    const Polyline& l = faired_[i];
    if (l.type == LineType::Ridge)
      ++s.ridges, s.ridge_length += l.length;
    else
      ++s.valleys, s.valley_length += l.length;
  }
  s.components = frames_.count();
  for (const Polyline& l : creases_.lines) ++s.creases, s.crease_length += l.length;
  s.crease_angle = creases_.angle;
  s.threshold = filtered_.threshold;
  s.mean_edge_length = mean_edge_;
  s.smoothing_iterations = extremality_.solver_iterations;
  const uint32_t largest = frames_.largest();
  s.noise_level = noise_levels_[largest];
  s.presmooth_steps = presmooth_steps_.empty() ? 0 : presmooth_steps_[largest];
  for (int i = 0; i < static_cast<int>(Stage::Count); ++i) s.seconds[i] = seconds_[i];
  s.topology_seconds = topology_seconds_;
  return s;
}

}  // namespace crestline
