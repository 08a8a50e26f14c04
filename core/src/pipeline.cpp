#include "crestline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "crestline/parameters.h"

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

// The graph's nodes and segments split by the component they lie on (a
// segment never leaves its component), one part per component that has
// nodes, with that component in `part_component`. Joining then bridges gaps
// only within a component and measures them in that component's segments.
std::vector<FeatureGraph> split_by_component(const FeatureGraph& graph, const Mesh& mesh, const Topology& topology,
                                             const ComponentFrames& frames, std::vector<uint32_t>& part_component) {
  std::vector<FeatureGraph> parts;
  part_component.clear();
  std::vector<uint32_t> part_of(frames.count(), kNone);
  std::vector<uint32_t> index(graph.points.size()), node_part(graph.points.size());
  for (size_t n = 0; n < graph.points.size(); ++n) {
    const uint32_t vertex =
        graph.trisector[n] ? mesh.triangles[graph.source[n]][0] : topology.edges[graph.source[n]][0];
    const uint32_t c = frames.vertex_component[vertex];
    if (part_of[c] == kNone) {
      part_of[c] = static_cast<uint32_t>(parts.size());
      part_component.push_back(c);
      parts.emplace_back().type = graph.type;
    }
    FeatureGraph& part = parts[node_part[n] = part_of[c]];
    index[n] = static_cast<uint32_t>(part.points.size());
    part.points.push_back(graph.points[n]);
    part.curvature.push_back(graph.curvature[n]);
    part.source.push_back(graph.source[n]);
    part.edge_parameter.push_back(graph.edge_parameter[n]);
    part.trisector.push_back(graph.trisector[n]);
  }
  for (const auto& s : graph.segments) parts[node_part[s[0]]].segments.push_back({index[s[0]], index[s[1]]});
  return parts;
}

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
  frames_ = component_frames(input_);
  local_input_ = to_local(input_, frames_);
  double sum = 0;
  size_t count = 0;
  for (size_t c = 0; c < frames_.count(); ++c)
    sum += frames_.scale[c] * frames_.triangle_count[c], count += frames_.triangle_count[c];
  mean_edge_ = count ? sum / count : 0;
  noise_levels_ = surface_noise_levels(local_input_, topology_, frames_.vertex_component, frames_.count());
}

void Pipeline::mark_dirty(Stage from) {
  if (static_cast<int>(from) < static_cast<int>(first_dirty_)) first_dirty_ = from;
}

void Pipeline::set_options(const PipelineOptions& o) {
  // The parameter table knows which stage each option feeds.
  const Stage changed = first_changed_stage(options_, o);
  if (changed != Stage::Count) mark_dirty(changed);
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
    const PresmoothOptions& presmooth = options_.presmooth;
    presmooth_steps_.assign(frames_.count(), 0);
    for (size_t c = 0; c < frames_.count(); ++c)
      if (presmooth.time_step > 0)
        presmooth_steps_[c] = presmooth.steps ? *presmooth.steps : automatic_presmooth_steps(noise_levels_[c]);
    presmoothed_ = *std::max_element(presmooth_steps_.begin(), presmooth_steps_.end()) > 0;
    std::vector<int> vertex_steps(input_.positions.size());
    for (size_t v = 0; v < vertex_steps.size(); ++v) vertex_steps[v] = presmooth_steps_[frames_.vertex_component[v]];
    working_surface_.triangles = input_.triangles;
    working_surface_.positions = presmooth_surface(local_input_, topology_, presmooth.time_step, vertex_steps);
    surface_.triangles = input_.triangles;
    if (!presmoothed_) {
      surface_.positions = input_.positions;
    } else {
      surface_.positions.resize(input_.positions.size());
      for (size_t v = 0; v < surface_.positions.size(); ++v)
        surface_.positions[v] = frames_.to_user(working_surface_.positions[v], frames_.vertex_component[v]);
    }
  });
  const Mesh& surface = working_surface_;
  step(Stage::Curvature, [&] { curvature_ = compute_curvature(surface, topology_); });
  step(Stage::Extremality, [&] { raw_extremality_ = compute_extremality(surface, curvature_); });
  step(Stage::Regularity, [&] { regularity_ = classify_triangles(surface, curvature_); });
  step(Stage::Smoothing, [&] {
    // The boundary band is frozen: its curvature sees half a neighbourhood
    // and must not diffuse into the interior.
    ExtremalitySmoothingOptions smoothing = options_.smoothing;
    const int rings = options_.trace.boundary_rings;
    if (rings > 0) {
      const std::vector<uint32_t> distance = boundary_ring_distance(surface, topology_, static_cast<uint32_t>(rings));
      if (smoothing.vertex_weights.empty()) smoothing.vertex_weights.assign(surface.positions.size(), 1.0);
      for (size_t v = 0; v < distance.size(); ++v)
        if (distance[v] < static_cast<uint32_t>(rings)) smoothing.vertex_weights[v] = 0;
    }
    extremality_ =
        smooth_extremality(surface, topology_, curvature_, raw_extremality_, smoothing, within(Stage::Smoothing));
  });
  step(Stage::Tracing, [&] {
    traced_ = trace_regular_triangles(surface, topology_, curvature_, extremality_, regularity_, options_.trace,
                                      within(Stage::Tracing));
  });
  step(Stage::Singular, [&] { singular_ = connect_singular_triangles(surface, topology_, regularity_, traced_); });
  step(Stage::Polylines, [&] {
    joined_.clear();
    line_component_.clear();
    for (const FeatureGraph* traced : {&singular_.lines.ridges, &singular_.lines.valleys}) {
      // Lines traced on the pre-smoothed surface are drawn on the input one:
      // same edges, same edge parameters, so they lie on what the user gave us.
      FeatureGraph placed;
      if (presmoothed_) {
        placed = *traced;
        place_nodes_on(placed, local_input_, topology_.edges);
        traced = &placed;
      }
      std::vector<FeatureGraph> parts;
      std::vector<uint32_t> part_component{0};
      if (frames_.count() > 1) parts = split_by_component(*traced, local_input_, topology_, frames_, part_component);
      for (size_t i = 0; i < part_component.size(); ++i) {
        std::vector<Polyline> lines = join_polylines(parts.empty() ? *traced : parts[i]);
        line_component_.insert(line_component_.end(), lines.size(), part_component[i]);
        joined_.insert(joined_.end(), std::make_move_iterator(lines.begin()), std::make_move_iterator(lines.end()));
      }
    }
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
  s.components = frames_.count();
  s.threshold = filtered_.threshold;
  s.mean_edge_length = mean_edge_;
  const uint32_t largest = frames_.largest();
  s.noise_level = noise_levels_[largest];
  s.presmooth_steps = presmooth_steps_.empty() ? 0 : presmooth_steps_[largest];
  for (int i = 0; i < static_cast<int>(Stage::Count); ++i) s.seconds[i] = seconds_[i];
  s.topology_seconds = topology_seconds_;
  return s;
}

}  // namespace crestline
