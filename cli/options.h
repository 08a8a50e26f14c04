#pragma once
// Command-line options of `crestline`: every PipelineOptions field plus the
// output choices. Defaults come from the option structs themselves.
#include <string>

#include "crestline/io/write_lines.h"
#include "crestline/pipeline.h"

namespace crestline::cli {

enum class OutputFormat { Obj, Json, Svg, Glb };

struct CliOptions {
  std::string input;
  std::string output;
  OutputFormat format = OutputFormat::Obj;
  PipelineOptions pipeline;
  io::SvgOptions svg;
  std::string weights;     // per-vertex smoothing strength file, empty: none
  bool with_mesh = false;  // also write the welded surface (OBJ and GLB only)
  bool stats = false;
  bool quiet = false;
  bool repair_report = false;
  int threads = 0;  // 0: every core
};

/// Parses argv. Returns -1 to go on, or the exit code to stop with (0 after
/// --help, 2 after a usage error, whose message is already printed).
int parse_options(int argc, char** argv, CliOptions& options);

}  // namespace crestline::cli
