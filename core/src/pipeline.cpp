#include "crestline/pipeline.h"

#include <chrono>

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

bool same(const ExtremalitySmoothingOptions& a, const ExtremalitySmoothingOptions& b) {
  return a.steps == b.steps && a.time_step == b.time_step && a.vertex_weights == b.vertex_weights;
}

}  // namespace

const char* stage_name(Stage stage) {
  static const char* names[] = {"presmooth", "curvature", "extremality", "regularity", "smoothing",
                                "tracing",   "singular",  "polylines",   "fairing",    "filter"};
  const int i = static_cast<int>(stage);
  return i >= 0 && i < static_cast<int>(Stage::Count) ? names[i] : "unknown";
}

Pipeline::Pipeline(Mesh mesh) : input_(std::move(mesh)) {
  {
    StageTimer timer(topology_seconds_);
    topology_ = build_topology(input_);
  }
  mean_edge_ = mean_edge_length(input_);
  noise_level_ = surface_noise_level(input_, topology_);
}

void Pipeline::mark_dirty(Stage from) {
  if (static_cast<int>(from) < static_cast<int>(first_dirty_)) first_dirty_ = from;
}

void Pipeline::set_options(const PipelineOptions& o) {
  const PipelineOptions& p = options_;
  if (o.presmooth.steps != p.presmooth.steps || o.presmooth.time_step != p.presmooth.time_step)
    mark_dirty(Stage::Presmooth);
  if (!same(o.smoothing, p.smoothing)) mark_dirty(Stage::Smoothing);
  if (o.trace.boundary_rings != p.trace.boundary_rings) mark_dirty(Stage::Smoothing);  // freezes the band too
  if (o.fairing.hausdorff_bound != p.fairing.hausdorff_bound || o.fairing.iterations != p.fairing.iterations)
    mark_dirty(Stage::Fairing);
  if (o.filter.threshold != p.filter.threshold) mark_dirty(Stage::Filter);
  options_ = o;
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
    PresmoothOptions presmooth = options_.presmooth;
    if (presmooth.steps < 0) presmooth.steps = automatic_presmooth_steps(noise_level_);
    presmooth_steps_ = presmooth.time_step > 0 ? presmooth.steps : 0;
    surface_.triangles = input_.triangles;
    surface_.positions = presmooth_surface(input_, topology_, presmooth);
  });
  step(Stage::Curvature, [&] { curvature_ = compute_curvature(surface_, topology_); });
  step(Stage::Extremality, [&] { raw_extremality_ = compute_extremality(surface_, curvature_); });
  step(Stage::Regularity, [&] { regularity_ = classify_triangles(surface_, curvature_); });
  step(Stage::Smoothing, [&] {
    // The boundary band is frozen: its curvature sees half a neighbourhood
    // and must not diffuse into the interior.
    ExtremalitySmoothingOptions smoothing = options_.smoothing;
    const int rings = options_.trace.boundary_rings;
    if (rings > 0) {
      const std::vector<uint32_t> distance = boundary_ring_distance(surface_, topology_, static_cast<uint32_t>(rings));
      if (smoothing.vertex_weights.empty()) smoothing.vertex_weights.assign(surface_.positions.size(), 1.0);
      for (size_t v = 0; v < distance.size(); ++v)
        if (distance[v] < static_cast<uint32_t>(rings)) smoothing.vertex_weights[v] = 0;
    }
    extremality_ =
        smooth_extremality(surface_, topology_, curvature_, raw_extremality_, smoothing, within(Stage::Smoothing));
  });
  step(Stage::Tracing, [&] {
    traced_ = trace_regular_triangles(surface_, topology_, curvature_, extremality_, regularity_, options_.trace,
                                      within(Stage::Tracing));
  });
  step(Stage::Singular, [&] { singular_ = connect_singular_triangles(surface_, topology_, regularity_, traced_); });
  step(Stage::Polylines, [&] {
    // Lines traced on the pre-smoothed surface are drawn on the input one:
    // same edges, same edge parameters, so they lie on what the user gave us.
    const FeatureGraph* ridges = &singular_.lines.ridges;
    const FeatureGraph* valleys_graph = &singular_.lines.valleys;
    FeatureGraph placed_ridges, placed_valleys;
    if (presmooth_steps_ > 0) {  // the surface was smoothed
      placed_ridges = *ridges;
      placed_valleys = *valleys_graph;
      place_nodes_on(placed_ridges, input_, topology_.edges);
      place_nodes_on(placed_valleys, input_, topology_.edges);
      ridges = &placed_ridges;
      valleys_graph = &placed_valleys;
    }
    joined_ = join_polylines(*ridges);
    std::vector<Polyline> valleys = join_polylines(*valleys_graph);
    joined_.insert(joined_.end(), std::make_move_iterator(valleys.begin()), std::make_move_iterator(valleys.end()));
  });
  step(Stage::Fairing, [&] { faired_ = fair_polylines(joined_, mean_edge_, options_.fairing); });
  step(Stage::Filter, [&] { filtered_ = filter_lines(faired_, options_.filter, mean_edge_); });
}

std::vector<Polyline> Pipeline::lines() const {
  std::vector<Polyline> out;
  out.reserve(filtered_.kept.size());
  for (uint32_t i : filtered_.kept) out.push_back(faired_[i]);
  return out;
}

PipelineStats Pipeline::stats() const {
  PipelineStats s;
  s.vertices = input_.positions.size();
  s.triangles = input_.triangles.size();
  s.singular_max = regularity_.singular_max;
  s.singular_min = regularity_.singular_min;
  for (uint32_t i : filtered_.kept) {
    const Polyline& l = faired_[i];
    if (l.type == LineType::Ridge)
      ++s.ridges, s.ridge_length += l.length;
    else
      ++s.valleys, s.valley_length += l.length;
  }
  s.threshold = filtered_.threshold;
  s.mean_edge_length = mean_edge_;
  s.noise_level = noise_level_;
  s.presmooth_steps = presmooth_steps_;
  for (int i = 0; i < static_cast<int>(Stage::Count); ++i) s.seconds[i] = seconds_[i];
  s.topology_seconds = topology_seconds_;
  return s;
}

}  // namespace crestline
