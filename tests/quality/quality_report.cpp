// crestline_quality_report: line quality on the analytic surfaces (issue 9),
// for Crestline's defaults, with two pre-smoothing steps added, and without
// extremality smoothing, at every noise level. Prints Markdown tables: one row per case, then a summary.
//
//   crestline_quality_report [--summary] [--steps N] [--time-step T]
//                            [--threshold S] [--presmooth N] [--cells N] [--seeds N] [--surface NAME]...
//                            [--presmooth-time-step T]
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
  void add(const Score& s) {
    if (s.control) {
      control_lines += s.ridge.lines + s.valley.lines;
      return;
    }
    ++cases;
    met += target_failures(s).empty();
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
               "usage: crestline_quality_report [--summary] [--steps N] [--time-step T] [--threshold S]\n"
               "                                [--presmooth N] [--presmooth-time-step T]\n"
               "                                [--cells N] [--seeds N] [--surface NAME]...\n");
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  PipelineOptions tuned;
  bool summary_only = false;
  int cells = 32, seeds = 1;
  std::vector<std::string> surfaces;
  for (int i = 1; i < argc; ++i) {
    auto value = [&] {
      if (i + 1 >= argc) usage();
      return argv[++i];
    };
    if (!std::strcmp(argv[i], "--summary"))
      summary_only = true;
    else if (!std::strcmp(argv[i], "--steps"))
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
  PipelineOptions unsmoothed = tuned;
  unsmoothed.smoothing.steps = 0;
  std::vector<Config> configs = {{"defaults", tuned}, {"no smoothing", unsmoothed}};
  if (tuned.presmooth.steps == 0) {
    configs.insert(configs.begin() + 1, {"defaults + presmooth 2", with_presmoothing(tuned)});
    PipelineOptions averaged = with_presmoothing(tuned);
    averaged.averaging.rings = 1;
    configs.insert(configs.begin() + 2, {"defaults + presmooth 2 + S averaged over 1 ring", averaged});
  }
  const double noises[] = {0.0, 0.1, 0.25};
  const Triangulation triangulations[] = {Triangulation::Uniform, Triangulation::Alternating, Triangulation::Irregular};

  std::vector<std::vector<Summary>> summary(configs.size(), std::vector<Summary>(3));
  if (!summary_only) {
    std::printf(
        "| surface | mesh | seed | noise | config | ridge cov | prec | frag | valley cov | prec | frag | "
        "spurious valleys | s |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  auto cell = [](double v, bool vacuous) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return vacuous ? std::string("–") : std::string(buf);
  };
  for (const std::string& name : surfaces)
    for (Triangulation tri : triangulations)
      for (int seed = 1; seed <= seeds; ++seed) {
        SurfaceParams params;
        params.cells_per_unit = cells;
        params.triangulation = tri;
        params.seed = static_cast<unsigned>(seed);
        const Surface surface = make_surface(name, params);
        for (int n = 0; n < 3; ++n)
          for (size_t c = 0; c < configs.size(); ++c) {
            const unsigned noise_seed = 100u + static_cast<unsigned>(seed);
            const Config& config = configs[c];
            const Score s = run_case(surface, noises[n], noise_seed, config.options);
            summary[c][n].add(s);
            if (summary_only) continue;
            std::printf("| %s | %s | %d | %.2f | %s | %s | %s | %s | %s | %s | %s | %d | %.2f |\n", name.c_str(),
                        triangulation_name(tri), seed, noises[n], configs[c].name.c_str(),
                        cell(s.ridge.coverage, s.ridge.true_curves == 0).c_str(),
                        cell(s.ridge.precision, s.ridge.lines == 0).c_str(),
                        cell(s.ridge.fragments, s.ridge.true_curves == 0).c_str(),
                        cell(s.valley.coverage, s.valley.true_curves == 0).c_str(),
                        cell(s.valley.precision, s.valley.lines == 0).c_str(),
                        cell(s.valley.fragments, s.valley.true_curves == 0).c_str(), s.spurious_valleys(), s.seconds);
          }
      }

  std::printf(
      "\n| config | noise (mean edges) | coverage mean / min | precision mean / min | fragments mean / max | "
      "spurious valleys (convex) | cases meeting all targets | lines on the torus (control) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (size_t c = 0; c < configs.size(); ++c)
    for (int n = 0; n < 3; ++n) {
      const Summary& s = summary[c][n];
      std::printf("| %s | %.2f | %.3f / %.3f | %.3f / %.3f | %.2f / %.2f | %d | %d / %d | %d |\n",
                  configs[c].name.c_str(), noises[n], s.types ? s.coverage_sum / s.types : 1.0, s.coverage_min,
                  s.types ? s.precision_sum / s.types : 1.0, s.precision_min,
                  s.fragment_types ? s.fragments_sum / s.fragment_types : 0.0, s.fragments_max, s.spurious_valleys,
                  s.met, s.cases, s.control_lines);
    }
  return 0;
}
