#include "options.h"

#include <CLI/App.hpp>
#include <CLI/Config.hpp>
#include <CLI/Formatter.hpp>
#include <algorithm>
#include <cctype>
#include <map>

namespace crestline::cli {
namespace {

/// The command's own options: files and output choices. Everything else is
/// a parameter of the table.
enum class Own { Help, Output, Weights, WithMesh, Stats, RepairReport, Threads, Quiet };
struct OwnOption {
  Own id;
  const char* short_name;  // "" for none
  const char* name;
  const char* value;  // "" for a flag without value
  const char* help;
};
const OwnOption kOwn[] = {
    {Own::Help, "-h", "--help", "", "Print this help and exit"},
    {Own::Output, "-o", "--output", "FILE",
     "Output lines (required); the format follows the extension: .obj, .json, .svg or .glb"},
    {Own::Weights, "", "--weights", "FILE",
     "Per-vertex smoothing strength for inhomogeneous smoothing: a text file with one number per line for "
     "each vertex of the input file, in its order, or of the welded surface --with-mesh writes (0 freezes a "
     "vertex, 1 is the global time step)"},
    {Own::WithMesh, "", "--with-mesh", "",
     "Also write the welded surface into the output, so it opens in any viewer (.obj and .glb only)"},
    {Own::Stats, "", "--stats", "", "Print one JSON object of statistics and per-stage seconds on stdout"},
    {Own::RepairReport, "", "--repair-report", "", "Print every count of the mesh repair on stderr, including zeros"},
    {Own::Threads, "", "--threads", "N",
     "Threads for the stages that are linear in the mesh; 0: every core; the lines are the same for any count "
     "(0 to 1024; default 0)"},
    {Own::Quiet, "-q", "--quiet", "", "No notes and no progress on stderr; errors only"},
};

std::string lowercase_extension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// "  --smoothing-steps N" padded to the help column, then the text wrapped
/// at 100 columns.
void add_row(std::string& out, const std::string& left, const std::string& text) {
  constexpr size_t kColumn = 32, kWidth = 100;
  const std::string indent(kColumn, ' ');
  std::string line = "  " + left;
  line += line.size() < kColumn ? std::string(kColumn - line.size(), ' ') : "\n" + indent;
  size_t column = line.size() - (line.rfind('\n') == std::string::npos ? 0 : line.rfind('\n') + 1);
  out += line;
  size_t start = 0;
  bool first = true;
  while (start < text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!first && column + 1 + word.size() > kWidth) {
      out += "\n" + indent;
      column = kColumn;
    } else if (!first) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    first = false;
    start = end + 1;
  }
  out += "\n";
}

std::string value_name(const Parameter& p) {
  switch (p.kind) {
    case ParameterKind::Integer:
      return " N";
    case ParameterKind::Number:
      return " X";
    case ParameterKind::Choice:
      return " NAME";
    default:
      return "";
  }
}

/// "… (mean edge lengths; 0 to 10; default 0.25)".
std::string parameter_help(const Parameter& p) {
  std::string details;
  if (*p.unit) details += std::string(p.unit) + "; ";
  const std::string range = describe_range(p);
  if (!range.empty()) details += range + "; ";
  details += "default " + format_parameter(p, p.get(Settings{}));
  return std::string(p.help) + " (" + details + ")";
}

struct UsageFailure {
  std::string sentence;
};

[[noreturn]] void fail(std::string sentence) { throw UsageFailure{std::move(sentence)}; }

/// --threads is no parameter of the pipeline (nothing re-runs when it
/// changes), but its value is checked like one. Its get/set are unused.
const Parameter kThreads{"threads", "--threads", "run", ParameterKind::Integer, false,   0,      1024,
                         {},        "",          "",    Stage::Count,           nullptr, nullptr};

ParameterValue checked(const Parameter& p, const std::string& text) {
  try {
    return parse_parameter(p, text);
  } catch (const UsageError& e) {
    fail(e.what());
  }
}

/// CLI11's sentence for a parse error, in ours: the option or word it is
/// about, then what is wrong with it.
[[noreturn]] void fail_with(const CLI::ParseError& error, const CLI::App& app, const std::string& hint) {
  if (dynamic_cast<const CLI::ExtrasError*>(&error)) {
    const std::string word = app.remaining().empty() ? "" : app.remaining().front();
    if (word.size() > 1 && word[0] == '-') fail("unknown option " + word + hint);
    fail("unexpected argument \"" + word + "\"; give one input mesh" + hint);
  }
  const std::string what = error.what();
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&error)) {
    // "stats was given a disallowed flag override": --stats=1
    const std::string override = " was given a disallowed flag override";
    if (const size_t at = what.find(override); at != std::string::npos)
      fail("--" + what.substr(0, at) + " takes no value" + hint);
    // "--smoothing-steps: 1 required TEXT missing"
    if (const size_t colon = what.find(": "); colon != std::string::npos)
      fail(what.substr(0, colon) + " needs a value" + hint);
  }
  fail(what + hint);
}

}  // namespace

std::string help_text(const std::string& program) {
  std::string out =
      "crestline: smooth feature lines (ridges and valleys) on a triangle mesh, after\n"
      "Hildebrandt, Polthier and Wardetzky, Smooth Feature Lines on Surface Meshes (SGP 2005).\n"
      "Lengths and times are unitless: relative to the mesh's mean edge length.\n\n"
      "Usage: " +
      program + " INPUT -o OUTPUT [options]\n\n";
  add_row(out, "INPUT", "Input mesh: .obj, .ply, .stl, .off, .gltf or .glb");
  for (const OwnOption& o : kOwn) {
    std::string left = *o.short_name ? std::string(o.short_name) + "," + o.name : std::string(o.name);
    if (*o.value) left += std::string(" ") + o.value;
    add_row(out, left, o.help);
  }
  for (const char* group : {"pipeline", "svg"}) {
    out += std::string("\n") + (std::string(group) == "svg" ? "SVG" : "Pipeline") + ":\n";
    for (const Parameter& p : parameters())
      if (std::string(p.group) == group) add_row(out, p.flag + value_name(p), parameter_help(p));
  }
  return out;
}

ParseOutcome parse_arguments(const std::vector<std::string>& args, CliOptions& o, const std::string& program) {
  const std::string hint = " (see " + program + " --help).";
  try {
    // CLI11 splits the words; every value is then checked by the parameter
    // table, so both builds refuse the same values with the same sentence.
    CLI::App app;
    app.set_help_flag();  // the help text comes from the table (help_text)
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    // The command's own options, named once in kOwn (which --help lists).
    std::map<Own, std::string> own_words;
    std::map<Own, CLI::Option*> own_given;
    for (const OwnOption& own : kOwn) {
      const std::string names = *own.short_name ? std::string(own.short_name) + "," + own.name : own.name;
      own_given[own.id] =
          *own.value ? app.add_option(names, own_words[own.id]) : app.add_flag(names)->disable_flag_override();
    }
    app.add_option("INPUT", o.input);
    // A table Boolean is on when given bare; "--silhouette=false" turns it off.
    std::vector<std::string> words(parameters().size());
    std::vector<CLI::Option*> given(parameters().size());
    for (size_t i = 0; i < parameters().size(); ++i) {
      const Parameter& p = parameters()[i];
      given[i] = p.kind == ParameterKind::Boolean ? app.add_flag(std::string(p.flag) + "{true}", words[i])
                                                  : app.add_option(p.flag, words[i]);
    }
    auto given_own = [&](Own id) { return own_given[id]->count() > 0; };
    try {
      // CLI11 takes the words last to first.
      std::vector<std::string> reversed(args.rbegin(), args.rend());
      app.parse(reversed);
    } catch (const CLI::ParseError& error) {
      if (given_own(Own::Help)) return {kExitOk, help_text(program)};
      fail_with(error, app, hint);
    }
    if (given_own(Own::Help)) return {kExitOk, help_text(program)};
    o.output = own_words[Own::Output];
    o.weights = own_words[Own::Weights];
    o.with_mesh = given_own(Own::WithMesh);
    o.stats = given_own(Own::Stats);
    o.repair_report = given_own(Own::RepairReport);
    o.quiet = given_own(Own::Quiet);
    if (given_own(Own::Threads)) o.threads = static_cast<int>(checked(kThreads, own_words[Own::Threads]).number);
    for (size_t i = 0; i < parameters().size(); ++i)
      if (given[i]->count() > 0) parameters()[i].set(o.settings, checked(parameters()[i], words[i]));

    if (o.input.empty() || o.output.empty()) fail("an INPUT mesh and -o OUTPUT are required" + hint);

    const std::string ext = lowercase_extension(o.output);
    if (ext == ".obj")
      o.format = OutputFormat::Obj;
    else if (ext == ".json")
      o.format = OutputFormat::Json;
    else if (ext == ".svg")
      o.format = OutputFormat::Svg;
    else if (ext == ".glb")
      o.format = OutputFormat::Glb;
    else
      fail(o.output + ": unsupported output format; use an output name ending in .obj, .json, .svg or .glb.");
    if (o.with_mesh && o.format != OutputFormat::Obj && o.format != OutputFormat::Glb)
      fail(o.output + ": --with-mesh needs an .obj or .glb output.");
  } catch (const UsageFailure& failure) {
    return {kExitUsage, "crestline: " + failure.sentence + "\n"};
  }
  return {};
}

}  // namespace crestline::cli
