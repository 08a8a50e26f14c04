#include "crestline/parameters.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace crestline {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const char* const kViewNames[] = {"front", "back", "left", "right", "top", "bottom"};

ParameterValue number(double v) {
  ParameterValue out;
  out.number = v;
  return out;
}

ParameterValue automatic_or(const std::optional<double>& v) {
  ParameterValue out;
  out.automatic = !v.has_value();
  out.number = v.value_or(0);
  return out;
}

std::string noisy_surface_help() {
  char text[256];
  std::snprintf(text, sizeof text,
                "Implicit mean-curvature-flow steps on the surface before curvature; 0: off; auto: %d steps when "
                "the measured noise exceeds %g mean edge lengths (up to %d above %g), else none",
                kNoisySurfaceSteps, kNoisySurface, kVeryNoisySurfaceSteps, kVeryNoisySurface);
  return text;
}

// Numbers in help sentences as --help prints the defaults.
std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// Ranges: counts are bounded so that no setting can hang a run on a small
// mesh (each step or iteration costs at most one sparse solve or one pass
// over the lines); time steps and lengths by what still makes sense on a
// mesh measured in mean edge lengths.
std::vector<Parameter> make_table() {
  static const std::string presmooth_help = noisy_surface_help();
  static const std::string crease_filter_help_text =
      "Steps of the feature-preserving normal filter before crease angles are measured; 0: raw normals; auto: " +
      std::to_string(kNoisyCreaseFilterSteps) + " when the measured noise exceeds " + number_text(kNoisySurface) +
      " mean edge lengths, else 0";
  static const std::string boundaries_help =
      "Ridges and valleys stop at the creases of the automatic angle: curvature and smoothing do not reach across "
      "them and no smooth line is traced within the boundary rings of one (not on surfaces whose measured noise "
      "exceeds " +
      number_text(kBoundaryNoiseLimit) + " mean edge lengths)";
  std::vector<Parameter> t;
  t.push_back({"presmoothSteps",
               "--presmooth-steps",
               "pipeline",
               ParameterKind::Integer,
               true,
               0,
               20,
               {},
               "",
               presmooth_help.c_str(),
               Stage::Presmooth,
               [](const Settings& s) {
                 const auto& steps = s.pipeline.presmooth.steps;
                 return automatic_or(steps ? std::optional<double>(*steps) : std::nullopt);
               },
               [](Settings& s, const ParameterValue& v) {
                 s.pipeline.presmooth.steps = v.automatic ? std::nullopt : std::optional<int>(int(v.number));
               }});
  t.push_back({"presmoothTimeStep",
               "--presmooth-time-step",
               "pipeline",
               ParameterKind::Number,
               false,
               0,
               10,
               {},
               "mean edge lengths squared",
               "Time step of each pre-smoothing step; 0: no pre-smoothing",
               Stage::Presmooth,
               [](const Settings& s) { return number(s.pipeline.presmooth.time_step); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.presmooth.time_step = v.number; }});
  t.push_back({"smoothingSteps",
               "--smoothing-steps",
               "pipeline",
               ParameterKind::Integer,
               false,
               0,
               50,
               {},
               "",
               "Implicit extremality smoothing steps (paper 5.1); 0: off",
               Stage::Smoothing,
               [](const Settings& s) { return number(s.pipeline.smoothing.steps); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.smoothing.steps = int(v.number); }});
  t.push_back({"smoothingTimeStep",
               "--smoothing-time-step",
               "pipeline",
               ParameterKind::Number,
               false,
               0,
               100,
               {},
               "mean edge lengths squared",
               "Time step of each extremality smoothing step",
               Stage::Smoothing,
               [](const Settings& s) { return number(s.pipeline.smoothing.time_step); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.smoothing.time_step = v.number; }});
  // The band is frozen during smoothing as well as left untraced.
  t.push_back({"boundaryRings",
               "--boundary-rings",
               "pipeline",
               ParameterKind::Integer,
               false,
               0,
               20,
               {},
               "",
               "Vertex rings next to the mesh boundary where no lines are traced",
               Stage::Smoothing,
               [](const Settings& s) { return number(s.pipeline.trace.boundary_rings); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.trace.boundary_rings = int(v.number); }});
  t.push_back({"hausdorffBound",
               "--fairing-bound",
               "pipeline",
               ParameterKind::Number,
               false,
               0,
               10,
               {},
               "mean edge lengths",
               "Largest distance faired lines may move; 0: no fairing",
               Stage::Fairing,
               [](const Settings& s) { return number(s.pipeline.fairing.hausdorff_bound); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.fairing.hausdorff_bound = v.number; }});
  t.push_back({"fairingIterations",
               "--fairing-iterations",
               "pipeline",
               ParameterKind::Integer,
               false,
               0,
               1000,
               {},
               "",
               "Line fairing iterations (paper 5.2)",
               Stage::Fairing,
               [](const Settings& s) { return number(s.pipeline.fairing.iterations); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.fairing.iterations = int(v.number); }});
  t.push_back({"threshold",
               "--threshold",
               "pipeline",
               ParameterKind::Number,
               true,
               0,
               kInf,
               {},
               "",
               "Drop lines whose strength (integral of |curvature| along the line) is below this; auto: chosen "
               "from the distribution of strengths on the mesh",
               Stage::Filter,
               [](const Settings& s) { return automatic_or(s.pipeline.filter.threshold); },
               [](Settings& s, const ParameterValue& v) {
                 s.pipeline.filter.threshold = v.automatic ? std::nullopt : std::optional<double>(v.number);
               }});
  t.push_back({"creaseAngle",
               "--crease-angle",
               "pipeline",
               ParameterKind::Number,
               true,
               20,
               180,
               {},
               "degrees",
               "Sharp creases: edges whose dihedral angle is at least this (a selection, no curvature is "
               "recomputed; 180: none); auto: 35, or 12 times the median dihedral angle where larger",
               Stage::Creases,
               [](const Settings& s) {
                 const double a = s.pipeline.creases.angle;
                 return automatic_or(a < 0 ? std::nullopt : std::optional<double>(a));
               },
               [](Settings& s, const ParameterValue& v) { s.pipeline.creases.angle = v.automatic ? -1 : v.number; }});
  t.push_back({"creaseMaxTurn",
               "--crease-max-turn",
               "pipeline",
               ParameterKind::Number,
               false,
               0,
               180,
               {},
               "degrees",
               "Split a crease line where it turns by more than this",
               Stage::Creases,
               [](const Settings& s) { return number(s.pipeline.creases.max_turn); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.creases.max_turn = v.number; }});
  t.push_back({"creaseFilterSteps",
               "--crease-filter-steps",
               "pipeline",
               ParameterKind::Integer,
               true,
               0,
               50,
               {},
               "",
               crease_filter_help_text.c_str(),
               Stage::Creases,
               [](const Settings& s) {
                 const int steps = s.pipeline.creases.normal_filter_steps;
                 return automatic_or(steps < 0 ? std::nullopt : std::optional<double>(steps));
               },
               [](Settings& s, const ParameterValue& v) {
                 s.pipeline.creases.normal_filter_steps = v.automatic ? -1 : int(v.number);
               }});
  t.push_back({"creaseBoundaries",
               "--crease-boundaries",
               "pipeline",
               ParameterKind::Boolean,
               false,
               0,
               1,
               {},
               "",
               boundaries_help.c_str(),
               Stage::Presmooth,
               [](const Settings& s) { return number(s.pipeline.creases.boundaries ? 1 : 0); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.creases.boundaries = v.number != 0; }});
  t.push_back({"creaseClearance",
               "--crease-clearance",
               "pipeline",
               ParameterKind::Number,
               false,
               0,
               20,
               {},
               "edge lengths at the crease",
               "Ridges and valleys stop this far from the creases they stop at (--crease-boundaries); 0: where "
               "the boundary band ends",
               Stage::Polylines,
               [](const Settings& s) { return number(s.pipeline.clearance.distance); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.clearance.distance = v.number; }});
  t.push_back({"shortLineLength",
               "--short-line-length",
               "pipeline",
               ParameterKind::Number,
               false,
               0,
               1000,
               {},
               "mean edge lengths",
               "Weak lines (strength below 1) shorter than this are dropped too, whatever the threshold; 0 keeps them",
               Stage::Filter,
               [](const Settings& s) { return number(s.pipeline.filter.short_line_edges); },
               [](Settings& s, const ParameterValue& v) { s.pipeline.filter.short_line_edges = v.number; }});

  t.push_back({"view", "--view", "svg", ParameterKind::Choice, false, 0, 0,
               std::vector<std::string>(std::begin(kViewNames), std::end(kViewNames)), "",
               "SVG view direction (front looks along -z with +y up)", Stage::Count,
               [](const Settings& s) {
                 ParameterValue v;
                 v.choice = kViewNames[static_cast<int>(s.svg.view)];
                 return v;
               },
               [](Settings& s, const ParameterValue& v) {
                 for (int i = 0; i < 6; ++i)
                   if (v.choice == kViewNames[i]) s.svg.view = static_cast<io::View>(i);
               }});
  t.push_back({"svgWidth",
               "--svg-width",
               "svg",
               ParameterKind::Integer,
               false,
               16,
               100000,
               {},
               "pixels",
               "SVG size of the longer side",
               Stage::Count,
               [](const Settings& s) { return number(s.svg.width); },
               [](Settings& s, const ParameterValue& v) { s.svg.width = int(v.number); }});
  t.push_back({"strokeWidth",
               "--stroke-width",
               "svg",
               ParameterKind::Number,
               false,
               0.01,
               100,
               {},
               "pixels",
               "SVG line width",
               Stage::Count,
               [](const Settings& s) { return number(s.svg.stroke_width); },
               [](Settings& s, const ParameterValue& v) { s.svg.stroke_width = v.number; }});
  t.push_back({"silhouette",
               "--silhouette",
               "svg",
               ParameterKind::Boolean,
               false,
               0,
               1,
               {},
               "",
               "Also draw the surface's outline in the SVG",
               Stage::Count,
               [](const Settings& s) { return number(s.svg.silhouette ? 1 : 0); },
               [](Settings& s, const ParameterValue& v) { s.svg.silhouette = v.number != 0; }});
  t.push_back({"svgSurfaceTolerance",
               "--svg-surface-tolerance",
               "svg",
               ParameterKind::Number,
               false,
               0,
               100,
               {},
               "mean edge lengths",
               "How far lines may lie off the surface and still show in the SVG, as faired lines move off it",
               Stage::Count,
               [](const Settings& s) { return number(s.svg.surface_tolerance); },
               [](Settings& s, const ParameterValue& v) { s.svg.surface_tolerance = v.number; }});
  return t;
}

std::string format_number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

/// The user's word, quoted short: a 309-digit number is not repeated back.
std::string quoted(const std::string& text) {
  constexpr size_t kMost = 24;
  return "\"" + (text.size() <= kMost ? text : text.substr(0, kMost) + "…") + "\"";
}

[[noreturn]] void refuse(const Parameter& p, const std::string& name, const std::string& got) {
  std::string expected;
  switch (p.kind) {
    case ParameterKind::Boolean:
      expected = "true or false";
      break;
    case ParameterKind::Choice:
      expected = "one of " + describe_range(p);
      break;
    case ParameterKind::Integer:
      expected = (p.may_be_automatic ? "auto or a whole number from " : "a whole number from ") + format_number(p.min) +
                 " to " + format_number(p.max);
      break;
    case ParameterKind::Number:
      expected = (p.may_be_automatic ? "auto or a number from " : "a number from ") + format_number(p.min) + " to " +
                 format_number(p.max);
      break;
  }
  throw UsageError(name + " must be " + expected + "; got " + got + ".");
}

}  // namespace

const std::vector<Parameter>& parameters() {
  static const std::vector<Parameter> table = make_table();
  return table;
}

const Parameter* find_parameter_by_key(const std::string& key) {
  for (const Parameter& p : parameters())
    if (key == p.key) return &p;
  return nullptr;
}

std::string describe_range(const Parameter& p) {
  switch (p.kind) {
    case ParameterKind::Boolean:
      return "";
    case ParameterKind::Choice: {
      std::string out;
      for (const std::string& c : p.choices) out += (out.empty() ? "" : ", ") + c;
      return out;
    }
    default:
      return (p.may_be_automatic ? "auto or " : "") + format_number(p.min) + " to " + format_number(p.max);
  }
}

void check_parameter(const Parameter& p, const ParameterValue& v, const std::string& name) {
  if (v.automatic) {
    if (!p.may_be_automatic) refuse(p, name, "auto");
    return;
  }
  switch (p.kind) {
    case ParameterKind::Boolean:
      if (v.number != 0 && v.number != 1) refuse(p, name, format_number(v.number));
      return;
    case ParameterKind::Choice:
      for (const std::string& c : p.choices)
        if (c == v.choice) return;
      refuse(p, name, quoted(v.choice));
    case ParameterKind::Integer:
    case ParameterKind::Number:
      // NaN fails both comparisons and is refused with the rest.
      if (!(v.number >= p.min && v.number <= p.max) ||
          (p.kind == ParameterKind::Integer && v.number != std::floor(v.number)))
        refuse(p, name, format_number(v.number));
      return;
  }
}

ParameterValue parse_parameter(const Parameter& p, const std::string& text, const std::string& given_name) {
  const std::string name = given_name.empty() ? std::string(p.flag) : given_name;
  ParameterValue v;
  if (p.kind == ParameterKind::Choice) {
    v.choice = text;
    for (const std::string& c : p.choices)
      if (c == text) return v;
    refuse(p, name, quoted(text));
  }
  if (p.kind == ParameterKind::Boolean) {
    if (text == "true" || text == "1") return number(1);
    if (text == "false" || text == "0") return number(0);
    refuse(p, name, quoted(text));
  }
  if (p.may_be_automatic && text == "auto") {
    v.automatic = true;
    return v;
  }
  // strtod accepts what people type ("3", "0.5", "1e-3", "inf") and also
  // "nan", hex floats and leading spaces: only the first kinds pass below.
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value =
      text.empty() || std::isspace(static_cast<unsigned char>(text[0])) ? std::nan("") : std::strtod(begin, &end);
  const bool hex = text.find_first_of("xX") != std::string::npos;
  if (end != begin + text.size() || std::isnan(value) || hex) refuse(p, name, quoted(text));
  v.number = value;
  try {
    check_parameter(p, v, name);
  } catch (const UsageError&) {
    refuse(p, name, quoted(text));  // the word as typed, not its rounding
  }
  return v;
}

std::string format_parameter(const Parameter& p, const ParameterValue& v) {
  if (v.automatic) return "auto";
  switch (p.kind) {
    case ParameterKind::Boolean:
      return v.number != 0 ? "true" : "false";
    case ParameterKind::Choice:
      return v.choice;
    default:
      return format_number(v.number);
  }
}

Stage first_changed_stage(const PipelineOptions& before, const PipelineOptions& after) {
  Settings a, b;
  a.pipeline = before;
  b.pipeline = after;
  int first = static_cast<int>(Stage::Count);
  for (const Parameter& p : parameters())
    if (static_cast<int>(p.stage) < first && p.get(a) != p.get(b)) first = static_cast<int>(p.stage);
  if (before.smoothing.vertex_weights != after.smoothing.vertex_weights)
    first = std::min(first, static_cast<int>(Stage::Smoothing));
  // Not offered to users (tests/quality tunes it), so not in the table.
  if (before.averaging.rings != after.averaging.rings) first = std::min(first, static_cast<int>(Stage::Curvature));
  return static_cast<Stage>(first);
}

}  // namespace crestline
