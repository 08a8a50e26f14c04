#include "session.h"

#include <emscripten/heap.h>
#include <emscripten/val.h>

#include <algorithm>
#include <iterator>
#include <limits>
#include <new>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "crestline/io/write_lines.h"
#include "crestline/lines/detail.h"
#include "crestline/mesh/repair.h"
#include "crestline/mesh/topology.h"

namespace crestline::wasm {
namespace {

using emscripten::typed_memory_view;

constexpr int kStages = static_cast<int>(Stage::Count);

/// Copies a JS typed array (any numeric kind) into a new vector. The heap
/// view exists only during TypedArray.set, which allocates nothing here.
template <class T>
std::vector<T> copy_in(const val& array) {
  std::vector<T> out(array["length"].as<size_t>());
  val(typed_memory_view(out.size(), out.data())).call<void>("set", array);
  return out;
}

/// A JS-owned copy: survives heap growth and can be transferred.
template <class T>
val copy_out(const T* data, size_t count) {
  return val(typed_memory_view(count, data)).call<val>("slice");
}

val positions_out(const std::vector<Vec3>& points) {
  return copy_out(points.empty() ? nullptr : points.front().data(), points.size() * 3);
}

val error_value(const char* kind, const std::string& message) {
  val out = val::object();
  out.set("error", message);
  out.set("kind", std::string(kind));
  return out;
}

// 12000000 → "12,000,000": the sentences below are read by people.
std::string with_thousands(size_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string over_limit(size_t triangles, size_t limit) {
  return "the mesh has " + with_thousands(triangles) + " triangles, more than the " + with_thousands(limit) +
         " this page accepts.";
}

std::string out_of_memory(size_t triangles) {
  const size_t gigabytes = (emscripten_get_heap_max() + (size_t(1) << 29)) >> 30;  // rounded
  return "the browser ran out of memory for a mesh of " + with_thousands(triangles) +
         " triangles (a page has at most " + std::to_string(gigabytes) +
         " GB); the command-line tool has no such limit.";
}

/// Runs `body`, mapping every exception to {error, kind}. `triangles` is read
/// only when memory runs out, so a body may still set it.
template <class F>
val guarded(const size_t& triangles, F&& body) {
  try {
    return body();
  } catch (const Cancelled&) {
    val out = val::object();
    out.set("cancelled", true);
    return out;
  } catch (const Error& e) {
    return error_value(error_kind_name(e.kind()), e.what());
  } catch (const std::bad_alloc&) {
    return error_value(error_kind_name(ErrorKind::TooLarge), out_of_memory(triangles));
  } catch (const std::exception& e) {
    return error_value("internal", e.what());
  }
}

template <class T>
void read(const val& object, const char* key, T& out) {
  const val v = object[key];
  if (!v.isUndefined() && !v.isNull()) out = v.as<T>();
}

val report_value(const RepairReport& r) {
  val out = val::object();
  out.set("inputVertices", r.input_vertices);
  out.set("inputTriangles", r.input_triangles);
  out.set("weldedVertices", r.welded_vertices);
  out.set("nonfiniteTriangles", r.nonfinite_triangles);
  out.set("degenerateTriangles", r.degenerate_triangles);
  out.set("duplicateTriangles", r.duplicate_triangles);
  out.set("unreferencedVertices", r.unreferenced_vertices);
  out.set("nonmanifoldEdges", r.nonmanifold_edges);
  out.set("nonmanifoldVertices", r.nonmanifold_vertices);
  out.set("flippedTriangles", r.flipped_triangles);
  out.set("components", r.components);
  out.set("boundaryEdges", r.boundary_edges);
  return out;
}

RepairOptions repair_options(const val& options) {
  RepairOptions repair;
  if (!options.isUndefined() && !options.isNull()) {
    read(options, "weldTolerance", repair.weld_tolerance);
    read(options, "maxTriangles", repair.max_triangles);
  }
  return repair;
}

}  // namespace

val Session::load(val positions, val indices, val options) {
  pipeline_.reset();
  triangles_ = indices["length"].as<size_t>() / 3;
  return guarded(triangles_, [&] {
    const RepairOptions repair = repair_options(options);
    if (triangles_ > repair.max_triangles)
      throw Error(ErrorKind::TooLarge, over_limit(triangles_, repair.max_triangles));
    TriangleSoup soup;
    soup.positions = copy_in<double>(positions);
    soup.indices = copy_in<uint32_t>(indices);
    return adopt(std::move(soup), repair);
  });
}

val Session::loadFile(std::string name, val bytes, val companions, val options) {
  pipeline_.reset();
  triangles_ = 0;
  return guarded(triangles_, [&] {
    const RepairOptions repair = repair_options(options);
    io::ReadOptions read_options;
    read_options.max_triangles = repair.max_triangles;
    std::vector<io::NamedBuffer> files;
    if (!companions.isUndefined() && !companions.isNull()) {
      const size_t count = companions["length"].as<size_t>();
      for (size_t i = 0; i < count; ++i) {
        const val file = companions[i];
        files.push_back({file["name"].as<std::string>(), copy_in<uint8_t>(file["bytes"])});
      }
    }
    TriangleSoup soup = io::read_mesh_bytes(name, copy_in<uint8_t>(bytes), files, read_options);
    triangles_ = soup.indices.size() / 3;
    return adopt(std::move(soup), repair);
  });
}

val Session::adopt(TriangleSoup soup, const RepairOptions& repair) {
  RepairResult repaired = repair_mesh(std::move(soup), repair);  // its notes stay
  val notes = val::array();
  for (const std::string& note : soup.notes) notes.call<void>("push", note);
  for (const std::string& note : repaired.report.notes()) notes.call<void>("push", note);
  soup = {};
  val out = val::object();
  out.set("ok", true);
  out.set("vertices", repaired.mesh.vertex_count());
  out.set("triangles", repaired.mesh.triangle_count());
  out.set("report", report_value(repaired.report));
  out.set("notes", notes);
  // Here, while the repair's adjacency is at hand (a run may release it).
  closed_outward_ = is_closed_outward(repaired.mesh, repaired.topology);
  pipeline_ = std::make_unique<Pipeline>(std::move(repaired.mesh), std::move(repaired.topology),
                                         std::move(repaired.components));
  pipeline_->set_options(settings_.pipeline);  // weights belong to the last mesh
  return out;
}

namespace {

/// A JavaScript value for parameter p, checked against the table; throws
/// UsageError naming `key`.
ParameterValue value_from_js(const Parameter& p, const val& v, const std::string& key) {
  const std::string type = v.typeOf().as<std::string>();
  if (type == "string") return parse_parameter(p, v.as<std::string>(), key);
  ParameterValue out;
  if (type == "boolean" && p.kind == ParameterKind::Boolean)
    out.number = v.as<bool>() ? 1 : 0;
  else if (type == "number" && p.kind != ParameterKind::Choice)
    out.number = v.as<double>();
  else
    return parse_parameter(p, type == "undefined" || type == "object" ? type : v.call<std::string>("toString"), key);
  check_parameter(p, out, key);
  return out;
}

val value_to_js(const Parameter& p, const ParameterValue& v) {
  if (v.automatic) return val("auto");
  switch (p.kind) {
    case ParameterKind::Boolean:
      return val(v.number != 0);
    case ParameterKind::Choice:
      return val(v.choice);
    default:
      return val(v.number);
  }
}

const char* kind_name(ParameterKind kind) {
  switch (kind) {
    case ParameterKind::Integer:
      return "integer";
    case ParameterKind::Number:
      return "number";
    case ParameterKind::Boolean:
      return "boolean";
    case ParameterKind::Choice:
      return "choice";
  }
  return "";
}

/// Applies every key of `o` to a copy of `settings`: all or nothing.
Settings with_options(Settings settings, const val& o, std::vector<double>* weights, bool* weights_given) {
  const val keys = val::global("Object").call<val>("keys", o);
  const size_t count = keys["length"].as<size_t>();
  for (size_t i = 0; i < count; ++i) {
    const std::string key = keys[i].as<std::string>();
    const val v = o[key];
    if (key == "vertexWeights") {
      *weights_given = true;
      if (v.isNull() || v.isUndefined())
        weights->clear();
      else
        *weights = copy_in<double>(v);
      continue;
    }
    const Parameter* p = find_parameter_by_key(key);
    if (!p) throw UsageError("there is no option \"" + key + "\".");
    p->set(settings, value_from_js(*p, v, key));
  }
  return settings;
}

}  // namespace

val Session::setOptions(val o) {
  return guarded(triangles_, [&] {
    std::vector<double> weights;
    bool weights_given = false;
    try {
      settings_ = with_options(settings_, o, &weights, &weights_given);
    } catch (const UsageError& e) {
      return error_value("usage", e.what());
    }
    if (pipeline_) {
      PipelineOptions p = settings_.pipeline;
      p.smoothing.vertex_weights = weights_given ? weights : pipeline_->options().smoothing.vertex_weights;
      pipeline_->set_options(p);
    }
    val out = val::object();
    out.set("ok", true);
    return out;
  });
}

val Session::options() const {
  val o = val::object();
  for (const Parameter& p : parameters()) o.set(p.key, value_to_js(p, p.get(settings_)));
  o.set("weighted", pipeline_ && !pipeline_->options().smoothing.vertex_weights.empty());
  return o;
}

val Session::describe() const {
  val table = val::array();
  const Settings defaults;
  for (const Parameter& p : parameters()) {
    val d = val::object();
    d.set("key", std::string(p.key));
    d.set("flag", std::string(p.flag));
    d.set("group", std::string(p.group));
    d.set("kind", std::string(kind_name(p.kind)));
    d.set("automatic", p.may_be_automatic);
    d.set("default", value_to_js(p, p.get(defaults)));
    if (p.kind == ParameterKind::Integer || p.kind == ParameterKind::Number) {
      d.set("min", p.min);
      d.set("max", p.max);
    } else {
      d.set("min", val::null());
      d.set("max", val::null());
    }
    val choices = val::array();
    for (const std::string& c : p.choices) choices.call<void>("push", c);
    d.set("choices", choices);
    d.set("unit", std::string(p.unit));
    d.set("help", std::string(p.help));
    d.set("stage", p.stage == Stage::Count ? val::null() : val(std::string(stage_name(p.stage))));
    table.call<void>("push", d);
  }
  return table;
}

val Session::run(val progress) {
  if (!pipeline_) return error_value(error_kind_name(ErrorKind::InvalidInput), "no mesh is loaded");
  return guarded(triangles_, [&] {
    std::vector<bool> ran(kStages, false);
    const PipelineStats before = pipeline_->stats();
    const bool report = progress.typeOf().as<std::string>() == "function";
    pipeline_->run([&](Stage stage, double fraction) {
      ran[static_cast<int>(stage)] = true;
      return !report || !progress(val(stage_name(stage)), val(fraction)).strictlyEquals(val(false));
    });
    const PipelineStats after = pipeline_->stats();
    val names = val::array();
    for (int s = 0; s < kStages; ++s) {
      // A stage ran if it reported progress or its timing changed.
      if (ran[s] || after.seconds[s] != before.seconds[s])
        names.call<void>("push", std::string(stage_name(static_cast<Stage>(s))));
    }
    val out = val::object();
    out.set("ok", true);
    out.set("ran", names);
    out.set("stats", stats());
    return out;
  });
}

val Session::surface() const {
  val out = val::object();
  if (!pipeline_) return out;
  // Lines are placed on the input surface even when they were traced on the
  // pre-smoothed one, so that is the surface to draw.
  const Mesh& mesh = pipeline_->input_mesh();
  out.set("positions", positions_out(mesh.positions));
  out.set("indices",
          copy_out(mesh.triangles.empty() ? nullptr : mesh.triangles.front().data(), mesh.triangles.size() * 3));
  // What the page draws, ready for the GPU, so that its main thread builds
  // no geometry (on 871k triangles that took it 0.3–0.8 s): float32
  // positions relative to the bounding box's centre (float32 cannot hold
  // far-off coordinates), area-weighted unit vertex normals, and the
  // bounding sphere about that centre.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 centre = mesh.positions.empty() ? Vec3::Zero() : Vec3(0.5 * (lo + hi));
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3 n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);  // |n| = 2·area
    for (uint32_t v : t) normals[v] += n;
  }
  std::vector<float> local(3 * mesh.positions.size()), unit(3 * mesh.positions.size());
  double radius = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3 d = mesh.positions[v] - centre;
    radius = std::max(radius, d.norm());
    const double length = normals[v].norm();
    for (int k = 0; k < 3; ++k) {
      local[3 * v + k] = static_cast<float>(d[k]);
      unit[3 * v + k] = length > 0 ? static_cast<float>(normals[v][k] / length) : 0.0f;
    }
  }
  val view = val::object();
  view.set("positions", copy_out(local.data(), local.size()));
  view.set("normals", copy_out(unit.data(), unit.size()));
  view.set("origin", copy_out(centre.data(), 3));
  view.set("radius", radius);
  view.set("closed", closed_outward_);
  out.set("view", view);
  return out;
}

namespace {

// Lines as flat typed arrays (see Session::lines and Session::creases).
val flat_lines(const std::vector<Polyline>& lines, bool creases, double mean_edge) {
  std::vector<Vec3> points;
  std::vector<uint32_t> offsets{0};
  std::vector<uint8_t> types, closed, convex;
  std::vector<double> strengths, lengths, angles;
  for (const Polyline& line : lines) {
    points.insert(points.end(), line.points.begin(), line.points.end());
    offsets.push_back(static_cast<uint32_t>(points.size()));
    types.push_back(static_cast<uint8_t>(line.type));
    closed.push_back(line.closed ? 1 : 0);
    strengths.push_back(line.strength);
    lengths.push_back(line.length);
    convex.push_back(line.convex ? 1 : 0);
    // strength = ∑ |angle|·length / h, so the mean angle is strength·h / length.
    angles.push_back(line.length > 0 ? line.strength * mean_edge / line.length * 180 / 3.14159265358979323846 : 0);
  }
  val out = val::object();
  out.set("points", positions_out(points));
  out.set("offsets", copy_out(offsets.data(), offsets.size()));
  if (!creases) out.set("types", copy_out(types.data(), types.size()));
  out.set("closed", copy_out(closed.data(), closed.size()));
  out.set("strengths", copy_out(strengths.data(), strengths.size()));
  out.set("lengths", copy_out(lengths.data(), lengths.size()));
  // The page draws lines at a level of detail (web/src/three/line-detail.js).
  const std::vector<float> importance = point_importance(lines);
  out.set("importance", copy_out(importance.data(), importance.size()));
  if (creases) {
    out.set("convex", copy_out(convex.data(), convex.size()));
    out.set("angles", copy_out(angles.data(), angles.size()));
  }
  return out;
}

}  // namespace

val Session::lines(bool all) const {
  std::vector<Polyline> kept;
  if (pipeline_ && !all) kept = pipeline_->lines();
  return flat_lines(all && pipeline_ ? pipeline_->all_lines() : kept, false, 0);
}

val Session::creases() const {
  if (!pipeline_) return flat_lines({}, true, 0);
  return flat_lines(pipeline_->creases(), true, pipeline_->stats().mean_edge_length);
}

val Session::keptLines() const {
  if (!pipeline_) return copy_out<uint32_t>(nullptr, 0);
  const std::vector<uint32_t>& kept = pipeline_->filtered().kept;
  return copy_out(kept.data(), kept.size());
}

val Session::fields() const {
  val out = val::object();
  if (!pipeline_) return out;
  const Curvature& c = pipeline_->curvature();
  const Extremality& e = pipeline_->extremality();
  const Regularity& r = pipeline_->regularity();
  // Per input vertex: a vertex on a boundary crease shows its first side
  // (the copies of its other sides follow in the working mesh).
  const size_t nv = std::min(pipeline_->input_mesh().positions.size(), c.kappa_max.size());
  out.set("kappaMax", copy_out(c.kappa_max.data(), nv));
  out.set("kappaMin", copy_out(c.kappa_min.data(), nv));
  out.set("eMax", copy_out(e.e_max.data(), std::min(nv, e.e_max.size())));
  out.set("eMin", copy_out(e.e_min.data(), std::min(nv, e.e_min.size())));
  out.set("regularMax", copy_out(r.regular_max.data(), r.regular_max.size()));
  out.set("regularMin", copy_out(r.regular_min.data(), r.regular_min.size()));
  return out;
}

val Session::stats() const {
  val out = val::object();
  if (!pipeline_) return out;
  const PipelineStats s = pipeline_->stats();
  out.set("vertices", s.vertices);
  out.set("triangles", s.triangles);
  out.set("singularMax", s.singular_max);
  out.set("singularMin", s.singular_min);
  out.set("ridges", s.ridges);
  out.set("valleys", s.valleys);
  out.set("ridgeLength", s.ridge_length);
  out.set("valleyLength", s.valley_length);
  out.set("creases", s.creases);
  out.set("creaseLength", s.crease_length);
  out.set("creaseAngle", s.crease_angle);
  out.set("threshold", s.threshold);
  out.set("meanEdgeLength", s.mean_edge_length);
  out.set("noiseLevel", s.noise_level);
  out.set("presmoothStepsUsed", s.presmooth_steps);
  out.set("components", s.components);
  val seconds = val::object();
  for (int i = 0; i < kStages; ++i) seconds.set(stage_name(static_cast<Stage>(i)), s.seconds[i]);
  out.set("seconds", seconds);
  return out;
}

std::string Session::linesObj() const {
  return pipeline_ ? io::write_lines_obj(pipeline_->all_kinds()) : std::string();
}

std::string Session::linesJson() const {
  return pipeline_ ? io::write_lines_json(pipeline_->all_kinds(), pipeline_->stats()) : std::string();
}

std::string Session::statsJson() const { return pipeline_ ? io::stats_json(pipeline_->stats()) : std::string(); }

namespace {

const char* const kViewKeys[] = {"camera",      "ridges",      "valleys",      "creases",    "ridgeColor",
                                 "valleyColor", "creaseColor", "concaveColor", "background", "silhouetteColor"};

bool is_view_key(const std::string& key) {
  return std::find(std::begin(kViewKeys), std::end(kViewKeys), key) != std::end(kViewKeys);
}

/// `o` without the drawing keys that are not parameters: the table's keys.
val table_keys(const val& o) {
  val rest = val::object();
  const val keys = val::global("Object").call<val>("keys", o);
  for (size_t i = 0, n = keys["length"].as<size_t>(); i < n; ++i) {
    const std::string key = keys[i].as<std::string>();
    if (!is_view_key(key)) rest.set(key, o[key]);
  }
  return rest;
}

/// A viewer's camera and style (kViewKeys) from `o` into `svg`.
void apply_view_keys(const val& o, io::SvgOptions& svg) {
  const val camera = o["camera"];
  if (!camera.isUndefined() && !camera.isNull()) {
    const std::vector<double> m = copy_in<double>(camera["matrix"]);
    if (m.size() != 16) throw UsageError("camera.matrix must hold 16 numbers (column-major).");
    io::SvgCamera c;
    c.matrix = Eigen::Map<const Eigen::Matrix4d>(m.data());  // column-major, as three.js's Matrix4.elements
    c.width = camera["width"].as<int>();
    c.height = camera["height"].as<int>();
    if (c.width < 1 || c.height < 1 || c.width > 16384 || c.height > 16384)
      throw UsageError("camera.width and camera.height must be between 1 and 16384 pixels.");
    svg.camera = c;
  }
  read(o, "ridges", svg.ridges);
  read(o, "valleys", svg.valleys);
  read(o, "creases", svg.creases);
  read(o, "ridgeColor", svg.ridge_color);
  read(o, "valleyColor", svg.valley_color);
  read(o, "creaseColor", svg.crease_color);
  read(o, "concaveColor", svg.concave_color);
  read(o, "background", svg.background);
  read(o, "silhouetteColor", svg.silhouette_color);
}

}  // namespace

val Session::linesSvg(val o) const {
  if (!pipeline_) return error_value(error_kind_name(ErrorKind::InvalidInput), "no mesh is loaded");
  Settings settings = settings_;
  try {
    if (!o.isUndefined() && !o.isNull()) {
      std::vector<double> weights;
      bool weights_given = false;
      settings = with_options(settings_, table_keys(o), &weights, &weights_given);
      apply_view_keys(o, settings.svg);
    }
  } catch (const UsageError& e) {
    return error_value("usage", e.what());
  }
  return guarded(triangles_, [&] {
    return val(
        io::write_lines_svg(pipeline_->all_kinds(), pipeline_->input_mesh(), pipeline_->topology(), settings.svg));
  });
}

val Session::linesGlb(val o) const {
  if (!pipeline_) return error_value(error_kind_name(ErrorKind::InvalidInput), "no mesh is loaded");
  io::SvgOptions shown;  // only its ridges / valleys / creases flags
  if (!o.isUndefined() && !o.isNull()) {
    read(o, "ridges", shown.ridges);
    read(o, "valleys", shown.valleys);
    read(o, "creases", shown.creases);
  }
  return guarded(triangles_, [&] {
    std::vector<Polyline> lines = pipeline_->all_kinds();
    lines.erase(std::remove_if(lines.begin(), lines.end(),
                               [&](const Polyline& l) {
                                 return l.type == LineType::Ridge    ? !shown.ridges
                                        : l.type == LineType::Valley ? !shown.valleys
                                                                     : !shown.creases;
                               }),
                lines.end());
    const std::vector<uint8_t> bytes = io::write_glb(&pipeline_->input_mesh(), lines);
    return copy_out(bytes.data(), bytes.size());
  });
}

}  // namespace crestline::wasm
