// crestline_quality_report: line quality on the analytic surfaces (issue 9),
// for Crestline's defaults, with two pre-smoothing steps added, and without
// extremality smoothing, at every noise level and on every meshing. Prints
// Markdown tables: one row per case, then a summary per configuration and
// noise level, then the defaults per meshing and noise level.
//
//   crestline_quality_report [--summary] [--defaults-only] [--steps N] [--time-step T]
//                            [--threshold S] [--presmooth N] [--cells N] [--seeds N]
//                            [--surface NAME]... [--meshing NAME]... [--noise σ]...
//                            [--presmooth-time-step T] [--averaging RINGS]
// --steps/--time-step/--threshold/--presmooth… replace the defaults' values (for tuning).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "quality_metrics.h"

using namespace crestline;
using namespace crestline::quality;

namespace {

struct Config {
  std::string name;
  PipelineOptions options;
};

struct Summary {
  int cases = 0, met = 0, spurious_valleys = 0, control_lines = 0;
  double coverage_sum = 0, precision_sum = 0, fragments_sum = 0;
  double coverage_min = 1, precision_min = 1, fragments_max = 0;
  int types = 0, fragment_types = 0;
  double offset_sum = 0, offset_max = 0;
  int offsets = 0;
  void add(const Score& s) {
    if (s.control) {
      control_lines += s.ridge.lines + s.valley.lines;
      return;
    }
    ++cases;
    met += target_failures(s).empty();
    if (s.offset() >= 0) ++offsets, offset_sum += s.offset(), offset_max = std::max(offset_max, s.offset());
    spurious_valleys += s.spurious_valleys();
    for (const TypeScore* t : {&s.ridge, &s.valley}) {
      if (t->true_curves == 0) {
        // No truth of this type: only precision (of spurious lines) counts.
        if (t->lines > 0) precision_min = std::min(precision_min, t->precision);
        continue;
      }
      ++types;
      coverage_sum += t->coverage, precision_sum += t->precision;
      coverage_min = std::min(coverage_min, t->coverage), precision_min = std::min(precision_min, t->precision);
      if (t->fragments > 0)
        ++fragment_types, fragments_sum += t->fragments, fragments_max = std::max(fragments_max, t->fragments);
    }
  }
};

void usage() {
  std::fprintf(stderr,
               "usage: crestline_quality_report [--summary] [--defaults-only] [--steps N] [--time-step T]\n"
               "                                [--threshold S] [--presmooth N] [--presmooth-time-step T]\n"
               "                                [--averaging RINGS] [--cells N] [--seeds N]\n"
               "                                [--surface NAME]... [--meshing NAME]... [--noise SIGMA]...\n");
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  PipelineOptions tuned;
  bool summary_only = false, defaults_only = false;
  int cells = 32, seeds = 1;
  std::vector<std::string> surfaces;
  std::vector<Triangulation> meshings;
  std::vector<double> noises;
  for (int i = 1; i < argc; ++i) {
    auto value = [&] {
      if (i + 1 >= argc) usage();
      return argv[++i];
    };
    if (!std::strcmp(argv[i], "--summary"))
      summary_only = true;
    else if (!std::strcmp(argv[i], "--defaults-only"))
      defaults_only = true;
    else if (!std::strcmp(argv[i], "--averaging"))
      tuned.averaging.rings = std::atoi(value());
    else if (!std::strcmp(argv[i], "--noise"))
      noises.push_back(std::atof(value()));
    else if (!std::strcmp(argv[i], "--meshing")) {
      const std::string name = value();
      bool known = false;
      for (Triangulation t : triangulations())
        if (name == triangulation_name(t)) meshings.push_back(t), known = true;
      if (!known) usage();
    } else if (!std::strcmp(argv[i], "--steps"))
      tuned.smoothing.steps = std::atoi(value());
    else if (!std::strcmp(argv[i], "--time-step"))
      tuned.smoothing.time_step = std::atof(value());
    else if (!std::strcmp(argv[i], "--presmooth"))
      tuned.presmooth.steps = std::atoi(value());
    else if (!std::strcmp(argv[i], "--presmooth-time-step"))
      tuned.presmooth.time_step = std::atof(value());
    else if (!std::strcmp(argv[i], "--threshold"))
      tuned.filter.threshold = std::atof(value());
    else if (!std::strcmp(argv[i], "--cells"))
      cells = std::atoi(value());
    else if (!std::strcmp(argv[i], "--seeds"))
      seeds = std::atoi(value());
    else if (!std::strcmp(argv[i], "--surface"))
      surfaces.push_back(value());
    else
      usage();
  }
  if (surfaces.empty()) surfaces = surface_names();
  if (meshings.empty()) meshings = triangulations();
  if (noises.empty()) noises = {0.0, 0.1, 0.25, 0.5};
  PipelineOptions unsmoothed = tuned;
  unsmoothed.smoothing.steps = 0;
  std::vector<Config> configs = {{"defaults", tuned}, {"no extremality smoothing", unsmoothed}};
  if (defaults_only) configs.resize(1);
  if (tuned.presmooth.steps == 0 && !defaults_only) {
    configs.insert(configs.begin() + 1, {"defaults + presmooth 2", with_presmoothing(tuned)});
    PipelineOptions averaged = with_presmoothing(tuned);
    averaged.averaging.rings = 1;
    configs.insert(configs.begin() + 2, {"defaults + presmooth 2 + S averaged over 1 ring", averaged});
  }
  const size_t nn = noises.size();
  std::vector<std::vector<Summary>> summary(configs.size(), std::vector<Summary>(nn));
  // The defaults per meshing and noise level.
  std::vector<std::vector<Summary>> by_meshing(meshings.size(), std::vector<Summary>(nn));
  if (!summary_only) {
    std::printf(
        "| surface | mesh | seed | noise | config | ridge cov | prec | frag | valley cov | prec | frag | "
        "spurious valleys | offset (edges) | s |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  auto cell = [](double v, bool vacuous) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return vacuous ? std::string("–") : std::string(buf);
  };
  auto cell3 = [](double v, bool vacuous) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.3f", v);
    return vacuous ? std::string("–") : std::string(buf);
  };
  for (const std::string& name : surfaces)
    for (size_t m = 0; m < meshings.size(); ++m)
      for (int seed = 1; seed <= seeds; ++seed) {
        const Triangulation tri = meshings[m];
        SurfaceParams params;
        params.cells_per_unit = cells;
        params.triangulation = tri;
        params.seed = static_cast<unsigned>(seed);
        const Surface surface = make_surface(name, params);
        for (size_t n = 0; n < nn; ++n)
          for (size_t c = 0; c < configs.size(); ++c) {
            const unsigned noise_seed = 100u + static_cast<unsigned>(seed);
            const Config& config = configs[c];
            const Score s = run_case(surface, noises[n], noise_seed, config.options);
            summary[c][n].add(s);
            if (c == 0) by_meshing[m][n].add(s);
            if (summary_only) continue;
            std::printf("| %s | %s | %d | %.2f | %s | %s | %s | %s | %s | %s | %s | %d | %s | %.2f |\n", name.c_str(),
                        triangulation_name(tri), seed, noises[n], configs[c].name.c_str(),
                        cell(s.ridge.coverage, s.ridge.true_curves == 0).c_str(),
                        cell(s.ridge.precision, s.ridge.lines == 0).c_str(),
                        cell(s.ridge.fragments, s.ridge.true_curves == 0).c_str(),
                        cell(s.valley.coverage, s.valley.true_curves == 0).c_str(),
                        cell(s.valley.precision, s.valley.lines == 0).c_str(),
                        cell(s.valley.fragments, s.valley.true_curves == 0).c_str(), s.spurious_valleys(),
                        cell3(s.offset(), s.offset() < 0).c_str(), s.seconds);
          }
      }

  std::printf(
      "\n| config | noise (mean edges) | coverage mean / min | precision mean / min | fragments mean / max | "
      "spurious valleys (convex) | cases meeting all targets | offset mean / max (edges) | lines on the torus "
      "(control) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (size_t c = 0; c < configs.size(); ++c)
    for (size_t n = 0; n < nn; ++n) {
      const Summary& s = summary[c][n];
      std::printf("| %s | %.2f | %.3f / %.3f | %.3f / %.3f | %.2f / %.2f | %d | %d / %d | %.3f / %.3f | %d |\n",
                  configs[c].name.c_str(), noises[n], s.types ? s.coverage_sum / s.types : 1.0, s.coverage_min,
                  s.types ? s.precision_sum / s.types : 1.0, s.precision_min,
                  s.fragment_types ? s.fragments_sum / s.fragment_types : 0.0, s.fragments_max, s.spurious_valleys,
                  s.met, s.cases, s.offsets ? s.offset_sum / s.offsets : 0.0, s.offset_max, s.control_lines);
    }

  // The defaults per meshing: cases meeting the targets and offset mean / max.
  std::printf("\n| %s: meshing |", configs[0].name.c_str());
  for (double noise : noises) std::printf(" σ = %.2f: met, offset mean / max |", noise);
  std::printf("\n|---|");
  for (size_t n = 0; n < nn; ++n) std::printf("---|");
  std::printf("\n");
  for (size_t m = 0; m < meshings.size(); ++m) {
    std::printf("| %s |", triangulation_name(meshings[m]));
    for (const Summary& s : by_meshing[m])
      std::printf(" %d / %d, %.3f / %.3f |", s.met, s.cases, s.offsets ? s.offset_sum / s.offsets : 0.0, s.offset_max);
    std::printf("\n");
  }
  return 0;
}
