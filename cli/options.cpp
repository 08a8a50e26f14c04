#include "options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <iostream>
#include <map>

namespace crestline::cli {
namespace {

const std::map<std::string, io::View> kViews = {{"front", io::View::Front}, {"back", io::View::Back},
                                                {"left", io::View::Left},   {"right", io::View::Right},
                                                {"top", io::View::Top},     {"bottom", io::View::Bottom}};

std::string lowercase_extension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

int parse_options(int argc, char** argv, CliOptions& o) {
  CLI::App app{
      "crestline: smooth feature lines (ridges and valleys) on a triangle mesh, after\n"
      "Hildebrandt, Polthier and Wardetzky, Smooth Feature Lines on Surface Meshes (SGP 2005).\n"
      "Lengths and times are unitless: relative to the mesh's mean edge length."};
  app.option_defaults()->always_capture_default();
  app.get_formatter()->column_width(34);

  app.add_option("input", o.input, "Input mesh: .obj, .ply, .stl, .off, .gltf or .glb")->required();
  app.add_option("-o,--output", o.output, "Output lines; the format follows the extension: .obj, .json, .svg or .glb")
      ->required();

  PipelineOptions& p = o.pipeline;
  // Every pipeline parameter but the threshold and the pre-smoothing steps
  // (negative: automatic) is a non-negative number.
  auto parameter = [&app](const char* name, auto& value, const char* help) {
    return app.add_option(name, value, help)->check(CLI::NonNegativeNumber)->group("Pipeline");
  };
  char noisy[32];
  std::snprintf(noisy, sizeof noisy, "%g", kNoisySurface);
  app.add_option("--presmooth-steps", p.presmooth.steps,
                 "Implicit mean-curvature-flow steps on the surface before curvature (0: off); negative: automatic, " +
                     std::to_string(kNoisySurfaceSteps) + " steps when the measured noise exceeds " + noisy +
                     " mean edge lengths, else none")
      ->group("Pipeline");
  parameter("--presmooth-time-step", p.presmooth.time_step,
            "Time step of each presmoothing step, in mean edge lengths squared");
  parameter("--smoothing-steps", p.smoothing.steps, "Implicit extremality smoothing steps (paper 5.1; 0: off)");
  parameter("--smoothing-time-step", p.smoothing.time_step,
            "Time step of each extremality smoothing step, in mean edge lengths squared");
  app.add_option("--weights", o.weights,
                 "Per-vertex smoothing strength for inhomogeneous smoothing: a text file with one "
                 "number per vertex and line (0 freezes a vertex, 1 is the global time step)")
      ->check(CLI::ExistingFile)
      ->group("Pipeline");
  parameter("--boundary-rings", p.trace.boundary_rings,
            "Vertex rings next to the mesh boundary where no lines are traced");
  parameter("--fairing-bound", p.fairing.hausdorff_bound,
            "Largest distance faired lines may move, in mean edge lengths (0: no fairing)");
  parameter("--fairing-iterations", p.fairing.iterations, "Line fairing iterations (paper 5.2)");
  app.add_option("--threshold", p.filter.threshold,
                 "Drop lines whose strength (integral of |curvature| along the line) is below this; "
                 "negative: chosen automatically from the mesh, also dropping weak lines (strength < 1) "
                 "shorter than 6 mean edge lengths")
      ->group("Pipeline");

  std::string view = "front";
  app.add_option("--view", view, "SVG view direction (front looks along -z with +y up)")
      ->check(CLI::IsMember([] {
        std::vector<std::string> names;
        for (const auto& entry : kViews) names.push_back(entry.first);
        return names;
      }()))
      ->group("SVG");
  app.add_option("--svg-width", o.svg.width, "SVG size in pixels of the longer side")
      ->check(CLI::Range(16, 100000))
      ->group("SVG");
  app.add_option("--stroke-width", o.svg.stroke_width, "SVG line width in pixels")
      ->check(CLI::PositiveNumber)
      ->group("SVG");
  app.add_flag("--silhouette", o.svg.silhouette, "Also draw the surface's outline in the SVG")->group("SVG");
  app.add_option("--svg-surface-tolerance", o.svg.surface_tolerance,
                 "How far lines may lie off the surface and still show, in mean edge lengths "
                 "(faired lines move off it)")
      ->check(CLI::NonNegativeNumber)
      ->group("SVG");

  app.add_flag("--with-mesh", o.with_mesh,
               "Also write the welded surface into the output, so it opens in any viewer (.obj and .glb only)");
  app.add_flag("--stats", o.stats, "Print one JSON object of statistics and per-stage seconds on stdout");
  app.add_flag("--repair-report", o.repair_report, "Print every count of the mesh repair on stderr, including zeros");
  app.add_option("--threads", o.threads,
                 "Threads for the stages that are linear in the mesh (0: every core); the lines are the same for any "
                 "count")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", o.quiet, "No notes and no progress on stderr; errors only");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "crestline: " << e.what() << " (see crestline --help)\n";
    return 2;
  }
  o.svg.view = kViews.at(view);

  const std::string ext = lowercase_extension(o.output);
  if (ext == ".obj")
    o.format = OutputFormat::Obj;
  else if (ext == ".json")
    o.format = OutputFormat::Json;
  else if (ext == ".svg")
    o.format = OutputFormat::Svg;
  else if (ext == ".glb")
    o.format = OutputFormat::Glb;
  else {
    std::cerr << "crestline: " << o.output
              << ": unsupported output format; use an output name ending in .obj, .json, .svg or .glb.\n";
    return 2;
  }
  if (o.with_mesh && o.format != OutputFormat::Obj && o.format != OutputFormat::Glb) {
    std::cerr << "crestline: " << o.output << ": --with-mesh needs an .obj or .glb output.\n";
    return 2;
  }
  return -1;
}

}  // namespace crestline::cli
