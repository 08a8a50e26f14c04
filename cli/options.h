#pragma once
// The command line of `crestline`, shared by both builds: the native CLI
// (main.cpp) and the WASM one (wasm/cli.mjs, through Session.parseArguments)
// parse, check and document their arguments with this one code, so they take
// the same options, print the same --help and refuse the same arguments with
// the same sentence. The pipeline and SVG options come from the parameter
// table (crestline/parameters.h); only the file and output choices are here.
#include <string>
#include <vector>

#include "crestline/parameters.h"

namespace crestline::cli {

enum class OutputFormat { Obj, Json, Svg, Glb };

struct CliOptions {
  std::string input;
  std::string output;
  OutputFormat format = OutputFormat::Obj;
  Settings settings;       // every table parameter
  std::string weights;     // per-vertex smoothing strength file, empty: none
  bool with_mesh = false;  // also write the welded surface (OBJ and GLB only)
  bool stats = false;
  bool quiet = false;
  bool repair_report = false;
  int threads = 0;  // 0: every core
};

/// Exit codes, the same in both builds.
constexpr int kExitOk = 0, kExitFailure = 1, kExitUsage = 2, kExitInterrupted = 130;

struct ParseOutcome {
  /// -1: go on and run; else the code to exit with (0 after --help, 2 after a
  /// usage error).
  int exit_code = -1;
  /// --help's text (for stdout) or the usage error's sentence (for stderr,
  /// starting "crestline: "), with a final newline; empty to go on.
  std::string text;
};

/// Parses the arguments after the program name. `program` is how --help
/// names the command ("crestline", "node wasm/cli.mjs").
ParseOutcome parse_arguments(const std::vector<std::string>& args, CliOptions& options,
                             const std::string& program = "crestline");

/// The --help text, generated from the parameter table.
std::string help_text(const std::string& program);

}  // namespace crestline::cli
