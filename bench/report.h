#pragma once
// What one benchmark mesh measured, and its rendering as a text table and JSON.
#include <cstddef>
#include <string>
#include <vector>

#include "crestline/pipeline.h"

namespace crestline::bench {

constexpr int kStages = static_cast<int>(Stage::Count);

/// Plain data so that a child process can send it back through a pipe.
struct MeshResult {
  char name[48] = {};
  char source[160] = {};
  char soup_file[512] = {};  // the exported soup (--export), for the WASM runner
  char error[256] = {};
  size_t vertices = 0, triangles = 0;  // after repair
  int runs = 0;
  // Medians over the runs, in seconds: the same split as the CLI's --stats.
  // read is NaN for generated meshes; write renders the kept lines as OBJ
  // text (no file).
  double read = 0, repair = 0, topology = 0, stages[kStages] = {}, write = 0, total = 0;
  double rethreshold = 0, resmooth = 0;  // re-runs after changing only the threshold / the smoothing
  double cpu = 0;  // CPU seconds (user + system, all threads) of `total`: less sensitive to a busy machine
  // The longest time in a run without a progress call (from run() to the
  // first, between two, from the last to the return; largest over the
  // runs): how long a cancel can wait. gap_stage: the stage of the call
  // that ended it (Stage::Count for the return).
  double longest_gap = 0;
  int gap_stage = 0;
  size_t input_rss = 0;             // bytes resident with the reader's soup in memory
  size_t peak_rss = 0;              // highest resident bytes from repair to the last re-run
  size_t smoothing_iterations = 0;  // the smoothing's solver iterations, all steps (the same every run)
  size_t ridges = 0, valleys = 0;
  double ridge_length = 0, valley_length = 0;
};

struct BenchSettings {
  int runs = 5;
  int threads = 1;
  PipelineOptions pipeline;
};

void print_table(const std::vector<MeshResult>& results);
std::string to_json(const std::vector<MeshResult>& results, const BenchSettings& settings);

}  // namespace crestline::bench
