#pragma once
// Every parameter a user can set, declared once: its JavaScript key, its
// command-line flag, kind, default, range, unit, help text and the first
// pipeline stage a change re-runs. The CLI's options and --help (native and
// WASM), Pipeline::set_options, the WASM Session's setOptions/options and
// Session.describe() (the page's panel and the widget's attributes) are all
// generated from this table.
//
// "Automatic" is its own mode, never a magic number: a parameter that may be
// automatic holds std::nullopt in C++, the string "auto" on the command line
// and in JavaScript.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "crestline/io/write_lines.h"
#include "crestline/pipeline.h"

namespace crestline {

/// Everything the table sets: the pipeline's options and the SVG writer's.
struct Settings {
  PipelineOptions pipeline;
  io::SvgOptions svg;
};

enum class ParameterKind { Integer, Number, Boolean, Choice };

/// One parameter's value. `automatic` only for parameters that allow it;
/// Boolean is 0 or 1 in `number`; Choice is the name in `choice`.
struct ParameterValue {
  bool automatic = false;
  double number = 0;
  std::string choice;
  bool operator==(const ParameterValue& o) const {
    return automatic == o.automatic && choice == o.choice && (automatic || number == o.number);
  }
  bool operator!=(const ParameterValue& o) const { return !(*this == o); }
};

struct Parameter {
  const char* key;    // camelCase, for JavaScript: "smoothingSteps"
  const char* flag;   // "--smoothing-steps"
  const char* group;  // "pipeline" or "svg": where --help and the panel list it
  ParameterKind kind;
  bool may_be_automatic;
  double min, max;                   // inclusive; Integer and Number only
  std::vector<std::string> choices;  // Choice only
  const char* unit;                  // "mean edge lengths", "", …
  const char* help;                  // one sentence, without the default or the range
  /// The first stage a change re-runs; Stage::Count: none (output only).
  Stage stage;
  ParameterValue (*get)(const Settings&);
  void (*set)(Settings&, const ParameterValue&);
};

/// A value outside a parameter's range, a word that is no number, an unknown
/// key: a usage error (the CLI exits with 2). The message is one sentence
/// naming the option.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// The table, in the order --help and the panel show it.
const std::vector<Parameter>& parameters();
const Parameter* find_parameter_by_key(const std::string& key);

/// Parses a command-line word ("3", "0.5", "auto", "front"); throws
/// UsageError naming `name` (p.flag when empty) when it is no value of p or
/// outside its range.
ParameterValue parse_parameter(const Parameter& p, const std::string& text, const std::string& name = "");
/// Throws UsageError naming `name` (the flag or the key) when `value` is
/// outside p's range or not a whole number where one is needed.
void check_parameter(const Parameter& p, const ParameterValue& value, const std::string& name);
/// "3", "0.25", "auto", "front", "true": as --help and the panel show it.
std::string format_parameter(const Parameter& p, const ParameterValue& value);
/// "0 to 50", "auto or 0 to inf", "front, back, …", "" for Boolean.
std::string describe_range(const Parameter& p);

/// The stages to re-run after changing `before` into `after`: the earliest
/// stage whose parameters changed (Stage::Count when none did). Vertex
/// weights are data, not a table parameter: a change re-runs smoothing;
/// shape-operator averaging is no user option: a change re-runs curvature.
Stage first_changed_stage(const PipelineOptions& before, const PipelineOptions& after);

}  // namespace crestline
