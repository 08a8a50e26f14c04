// crestline INPUT -o OUT.{obj,json,svg,glb}: read → repair → pipeline → write.
// Exit codes: 0 success, 1 a problem with a file or the computation, 2 a
// usage error, 130 interrupted. On failure no output file is left behind.
// The same program is built natively (build/cli/crestline) and to WASM for
// node (wasm/dist/crestline-cli.*, run by wasm/cli.mjs), where it reaches the
// real filesystem through Emscripten's NODERAWFS.
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "crestline/io/write_lines.h"
#include "crestline/mesh/repair.h"
#include "crestline/numerics/parallel.h"
#include "crestline/pipeline.h"
#include "files.h"
#include "options.h"
#include "progress.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

#ifdef __EMSCRIPTEN__
#include <emscripten.h>

// The WASM build has neither Draco nor meshoptimizer compiled in: wasm/cli.mjs
// rewrites a compressed glTF into a plain GLB with the npm decoders
// (wasm/gltf-decompress.mjs) and hands it over in two calls: the size (or,
// negative, the length of an error sentence), then the bytes.
// clang-format off
EM_JS(int, crestline_decompress_gltf, (const char* path), {
  return Module.decompressGltf(UTF8ToString(path));
});
EM_JS(void, crestline_take_decompressed, (uint8_t* out), {
  HEAPU8.set(Module.takeDecompressed(), out);
});
// clang-format on
#endif

namespace crestline::cli {
namespace {

// Seconds since the previous lap (or construction), for --stats.
class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

/// io::read_mesh, and in the WASM build the JavaScript decoders for
/// compressed glTF: one file, one outcome in both builds.
TriangleSoup read_input(const std::string& path) {
#ifdef __EMSCRIPTEN__
  try {
    return io::read_mesh(path);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Unsupported || std::string(e.what()).find("is compressed with") == std::string::npos)
      throw;
  }
  const int size = crestline_decompress_gltf(path.c_str());
  std::vector<uint8_t> bytes(static_cast<size_t>(size < 0 ? -size : size));
  crestline_take_decompressed(bytes.data());
  if (size < 0) throw Error(ErrorKind::InvalidInput, std::string(bytes.begin(), bytes.end()));
  return io::read_mesh_bytes(std::filesystem::path(path).filename().string(), bytes);
#else
  return io::read_mesh(path);
#endif
}

/// "crestline: FILE: problem". Messages that already start with the file
/// (io::read_mesh names it by its full path or its base name) are not
/// prefixed twice.
std::string message_for(const std::string& file, std::string message) {
  const std::string base = std::filesystem::path(file).filename().string();
  for (const std::string& name : {file, base})
    if (!name.empty() && message.rfind(name + ": ", 0) == 0) {
      message.erase(0, name.size() + 2);
      break;
    }
  return "crestline: " + file + ": " + message;
}

void report_error(const std::string& file, const std::string& message) {
  std::cerr << message_for(file, message) << '\n';
}

void print_repair_report(const std::string& input, const RepairReport& r, Progress& out) {
  const std::pair<const char*, size_t> counts[] = {{"input_vertices", r.input_vertices},
                                                   {"input_triangles", r.input_triangles},
                                                   {"welded_vertices", r.welded_vertices},
                                                   {"nonfinite_triangles", r.nonfinite_triangles},
                                                   {"degenerate_triangles", r.degenerate_triangles},
                                                   {"duplicate_triangles", r.duplicate_triangles},
                                                   {"unreferenced_vertices", r.unreferenced_vertices},
                                                   {"nonmanifold_edges", r.nonmanifold_edges},
                                                   {"nonmanifold_vertices", r.nonmanifold_vertices},
                                                   {"flipped_triangles", r.flipped_triangles},
                                                   {"components", r.components},
                                                   {"boundary_edges", r.boundary_edges}};
  out.print("crestline: " + input + ": repair report");
  for (const auto& [name, value] : counts) out.print("  " + std::string(name) + ": " + std::to_string(value));
}

// The output file's text, handed to `sink`: the JSON and OBJ writers in
// pieces as they make them (the 1.1M mesh's JSON, 23.6 MB, was the CLI's
// largest block), the SVG and GLB whole.
void render(const CliOptions& options, const Pipeline& pipeline, const io::TextSink& sink) {
  const std::vector<Polyline> lines = pipeline.all_kinds();  // ridges, valleys, creases
  switch (options.format) {
    case OutputFormat::Json:
      return io::write_lines_json(lines, pipeline.stats(), sink);
    case OutputFormat::Svg:
      return sink(io::write_lines_svg(lines, pipeline.input_mesh(), pipeline.topology(), options.settings.svg));
    case OutputFormat::Glb: {
      const std::vector<uint8_t> bytes = io::write_glb(options.with_mesh ? &pipeline.input_mesh() : nullptr, lines);
      return sink(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    }
    case OutputFormat::Obj:
    default:
      if (options.with_mesh) return io::write_mesh_and_lines_obj(pipeline.input_mesh(), lines, sink);
      return io::write_lines_obj(lines, sink);
  }
}

int run(const CliOptions& options) {
  // The file the current step is about, for error messages.
  std::string file = options.input;
  try {
    const auto directory = std::filesystem::path(options.output).parent_path();
    if (!directory.empty() && !std::filesystem::is_directory(directory)) {
      report_error(options.output, "the folder " + directory.string() + " does not exist.");
      return 1;
    }
    std::error_code same_error;
    if (std::filesystem::equivalent(options.input, options.output, same_error)) {
      report_error(options.output, "this is the input mesh; choose another output name.");
      return 2;
    }
    if (options.threads > 0) set_max_threads(options.threads);
    Progress progress(!options.quiet);
    Stopwatch clock;
    TriangleSoup soup = read_input(options.input);
    const double read_seconds = clock.lap();
    progress.phase("repairing");
    RepairResult repaired = repair_mesh(soup);
    const double repair_seconds = clock.lap();
    if (!options.quiet) {
      for (const std::string& note : soup.notes) progress.print(message_for(options.input, note));
      for (const std::string& note : repaired.report.notes()) progress.print(message_for(options.input, note));
    }
    if (options.repair_report) print_repair_report(options.input, repaired.report, progress);

    PipelineOptions pipeline_options = options.settings.pipeline;
    if (!options.weights.empty()) {
      file = options.weights;
      pipeline_options.smoothing.vertex_weights = read_vertex_weights(options.weights, soup, repaired.mesh);
      file = options.input;
    }
    soup = TriangleSoup();  // not needed any more: ~45 bytes per triangle less at the peak

    Pipeline pipeline(std::move(repaired.mesh), std::move(repaired.topology), std::move(repaired.components));
    pipeline.set_options(pipeline_options);
    pipeline.run([&progress](Stage stage, double fraction) { return progress(stage, fraction); });

    progress.phase("writing");
    clock.lap();
    // A problem while the text is made is about the input, one creating or
    // writing the file about the output.
    file = options.output;
    write_file_atomically(options.output, [&](const io::TextSink& sink) {
      file = options.input;
      render(options, pipeline, sink);
      file = options.output;
    });
    progress.stop();
    if (options.stats) {
      PipelineStats stats = pipeline.stats();
      stats.read_seconds = read_seconds, stats.repair_seconds = repair_seconds, stats.write_seconds = clock.lap();
      std::cout << io::stats_json(stats) << std::endl;
    }
    return 0;
  } catch (const Cancelled&) {
    report_error(file, "interrupted; nothing was written.");
    return 130;
  } catch (const std::exception& e) {  // crestline::Error and everything else
    report_error(file, e.what());
    return 1;
  }
}

}  // namespace
}  // namespace crestline::cli

int main(int argc, char** argv) {
  using namespace crestline::cli;
  CliOptions options;
  const ParseOutcome parsed = parse_arguments(std::vector<std::string>(argv + 1, argv + argc), options);
  if (parsed.exit_code >= 0) {
    (parsed.exit_code == kExitOk ? std::cout : std::cerr) << parsed.text;
    return parsed.exit_code;
  }
  Progress::catch_interrupt();
#ifdef __GLIBC__
  // Freed blocks under 32 MB (glibc's largest mmap threshold) go back to
  // the heap for the next stage's arrays instead of being unmapped and their
  // pages faulted in afresh; glibc's dynamic threshold gets there only after
  // the first large free. 1.1M triangles, 1 thread: page faults 144k → 92k,
  // system time ≈ −0.1 s, peak RSS +5 MB (at 2 threads −8 MB).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
  return run(options);
}
