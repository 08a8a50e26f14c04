// crestline_bench: median per-stage seconds and peak memory of the whole
// pipeline, one child process per mesh so that each peak is its own.
//   crestline_bench [--runs N] [--smoke] [--only a,b] [--json FILE] [--export DIR]
//                   [--export-obj DIR] [--meshes DIR] [--smoothing-steps N] [--threads N]
#include <malloc.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "crestline/io/write_lines.h"
#include "crestline/mesh/repair.h"
#include "crestline/numerics/parallel.h"
#include "generate.h"
#include "memory.h"
#include "report.h"

namespace crestline::bench {
namespace {

struct MeshSpec {
  std::string name;
  std::string file;        // under the meshes folder
  int subdivisions = 0;    // > 0: generated from `file` by this many 1-to-4 subdivisions
  double noise = 0;        // > 0: generated from `file` with normal noise of this σ (mean edges)
  bool by_default = true;  // else only with --only
};

const std::vector<MeshSpec> kMeshes = {
    {"bunny", "classic/stanford-bunny.obj", 0},
    {"feline", "classic/feline.obj", 0},
    {"dragon", "large/dragon.glb", 0},
    {"bunny-sub2", "classic/stanford-bunny.obj", 2},
    {"bunny-sub3", "classic/stanford-bunny.obj", 3},
    // A noisy scan (photogrammetry): σ = 0.1 edge measures above the noise
    // level where the pipeline pre-smooths (3 steps) and filters the
    // crease normals (12 steps), both automatically.
    {"dragon-noisy", "large/dragon.glb", 0, 0.1, false},
};

struct Args {
  BenchSettings settings;
  std::string meshes = CRESTLINE_MESHES_DIR;
  std::string json, export_dir, export_obj_dir;
  std::vector<std::string> only;
};

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void copy_text(char* dest, size_t size, const std::string& text) { std::snprintf(dest, size, "%s", text.c_str()); }

// The soup as the WASM runner reads it: "CRSOUP1\0", uint64 vertex and
// triangle counts, float64 xyz, uint32 indices (little-endian).
void export_soup(const TriangleSoup& soup, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  const uint64_t counts[2] = {soup.vertex_count(), soup.triangle_count()};
  out.write("CRSOUP1", 8);
  out.write(reinterpret_cast<const char*>(counts), sizeof counts);
  out.write(reinterpret_cast<const char*>(soup.positions.data()), soup.positions.size() * sizeof(double));
  out.write(reinterpret_cast<const char*>(soup.indices.data()), soup.indices.size() * sizeof(uint32_t));
  if (!out) throw Error(ErrorKind::Io, path + ": cannot be written.");
}

// The soup as an OBJ file (v and f lines), so that the CLI's whole process
// (reading included) can be timed on the generated meshes. Coordinates in
// the shortest text that a correctly rounded parse (the OBJ reader's) reads
// back to the same double, so the CLI reads the benchmark's soup exactly.
void export_obj(const TriangleSoup& soup, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  std::string text;
  char number[32];
  auto flush = [&](bool force) {
    if (force || text.size() > (1u << 20)) out.write(text.data(), std::streamsize(text.size())), text.clear();
  };
  for (size_t v = 0; v < soup.vertex_count(); ++v) {
    text += 'v';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      text.append(number, std::to_chars(number, number + sizeof number, soup.positions[3 * v + size_t(k)]).ptr);
    }
    text += '\n';
    flush(false);
  }
  for (size_t t = 0; t < soup.triangle_count(); ++t) {
    text += 'f';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      text.append(number, std::to_chars(number, number + sizeof number, soup.indices[3 * t + size_t(k)] + 1).ptr);
    }
    text += '\n';
    flush(false);
  }
  flush(true);
  if (!out) throw Error(ErrorKind::Io, path + ": cannot be written.");
}

TriangleSoup generate(const MeshSpec& spec, const std::string& path) {
  TriangleSoup soup = io::read_mesh(path);
  for (int level = 0; level < spec.subdivisions; ++level) {
    const Mesh mesh = repair_mesh(soup).mesh;
    soup = subdivide(mesh);
  }
  if (spec.noise > 0) soup = add_normal_noise(repair_mesh(soup).mesh, spec.noise, 1);
  return soup;
}

MeshResult measure(const MeshSpec& spec, const Args& args) {
  MeshResult r;
  copy_text(r.name, sizeof r.name, spec.name);
  std::string source = spec.file;
  if (spec.subdivisions) source += " subdivided 1-to-4 " + std::to_string(spec.subdivisions) + "×";
  if (spec.noise > 0) {
    char sigma[32];
    std::snprintf(sigma, sizeof sigma, "%g", spec.noise);
    source += std::string(" + normal noise σ = ") + sigma + " edge";
  }
  copy_text(r.source, sizeof r.source, source);
  const BenchSettings& settings = args.settings;
  const std::string path = args.meshes + "/" + spec.file;
  const bool generated = spec.subdivisions > 0 || spec.noise > 0;
  TriangleSoup soup;
  if (generated) soup = generate(spec, path);

  std::vector<double> read, repair, topology, write, total, cpu, rethreshold, resmooth, stages[kStages];
  for (int run = 0; run < settings.runs; ++run) {
    if (!generated) {
      const double t = now();
      soup = io::read_mesh(path);
      read.push_back(now() - t);
    }
    if (run == 0) {
      r.input_rss = current_rss();
      if (!args.export_dir.empty()) {
        const std::string file = args.export_dir + "/" + spec.name + ".soup";
        export_soup(soup, file);
        copy_text(r.soup_file, sizeof r.soup_file, file);
      }
      if (!args.export_obj_dir.empty()) export_obj(soup, args.export_obj_dir + "/" + spec.name + ".obj");
    }
    reset_peak_rss();
    const double cpu_start = cpu_seconds();
    double t = now();
    RepairResult repaired = repair_mesh(soup);
    repair.push_back(now() - t);
    if (!generated) soup = TriangleSoup();  // read again next run
    t = now();
    Pipeline pipeline(std::move(repaired.mesh), std::move(repaired.topology), std::move(repaired.components));
    topology.push_back(now() - t);
    pipeline.set_options(settings.pipeline);
    double last_call = now();
    const auto gap_until = [&](int stage) {
      const double at = now();
      if (at - last_call > r.longest_gap) r.longest_gap = at - last_call, r.gap_stage = stage;
      last_call = at;
    };
    pipeline.run([&](Stage stage, double) {
      gap_until(static_cast<int>(stage));
      return true;
    });
    gap_until(kStages);
    const PipelineStats stats = pipeline.stats();
    double sum = repair.back() + topology.back();
    for (int s = 0; s < kStages; ++s) stages[s].push_back(stats.seconds[s]), sum += stats.seconds[s];
    total.push_back(sum);
    cpu.push_back(cpu_seconds() - cpu_start);
    {
      // The text is not kept: held through the re-runs below it would count
      // in their peak (≈ 10 bytes per triangle at 1.1M), which the CLI never holds.
      t = now();
      const std::string obj = io::write_lines_obj(pipeline.lines());
      write.push_back(now() - t);
    }

    // Interactive re-runs: a new threshold re-runs only the filter; new
    // smoothing re-runs from stage 6 (smoothing) on.
    PipelineOptions changed = settings.pipeline;
    changed.filter.threshold = 1.5 * stats.threshold;
    pipeline.set_options(changed);
    t = now();
    pipeline.run();
    rethreshold.push_back(now() - t);
    changed.smoothing.time_step *= 1.5;
    pipeline.set_options(changed);
    t = now();
    pipeline.run();
    resmooth.push_back(now() - t);
    r.peak_rss = std::max(r.peak_rss, peak_rss());

    r.vertices = stats.vertices, r.triangles = stats.triangles;
    r.smoothing_iterations = stats.smoothing_iterations;
    r.ridges = stats.ridges, r.valleys = stats.valleys;
    r.ridge_length = stats.ridge_length, r.valley_length = stats.valley_length;
  }
  r.runs = settings.runs;
  r.read = generated ? NAN : median(read);
  r.repair = median(repair), r.topology = median(topology), r.write = median(write), r.total = median(total),
  r.cpu = median(cpu);
  for (int s = 0; s < kStages; ++s) r.stages[s] = median(stages[s]);
  r.rethreshold = median(rethreshold), r.resmooth = median(resmooth);
  return r;
}

// Runs measure() in a child so that its peak RSS is that mesh's alone.
MeshResult measure_in_child(const MeshSpec& spec, const Args& args) {
  MeshResult r;
  copy_text(r.name, sizeof r.name, spec.name);
  int fd[2];
  if (pipe(fd) != 0) {
    copy_text(r.error, sizeof r.error, "pipe() failed");
    return r;
  }
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    MeshResult child;
    try {
      child = measure(spec, args);
    } catch (const std::exception& e) {
      copy_text(child.name, sizeof child.name, spec.name);
      copy_text(child.error, sizeof child.error, e.what());
    }
    const ssize_t written = write(fd[1], &child, sizeof child);
    _exit(written == static_cast<ssize_t>(sizeof child) ? 0 : 1);
  }
  close(fd[1]);
  size_t got = 0;
  char* bytes = reinterpret_cast<char*>(&r);
  MeshResult received;
  bytes = reinterpret_cast<char*>(&received);
  while (got < sizeof received) {
    const ssize_t n = read(fd[0], bytes + got, sizeof received - got);
    if (n <= 0) break;
    got += static_cast<size_t>(n);
  }
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got == sizeof received) return received;
  if (WIFSIGNALED(status))
    copy_text(r.error, sizeof r.error, std::string("crashed: ") + strsignal(WTERMSIG(status)));
  else
    copy_text(r.error, sizeof r.error, "the measuring process failed");
  return r;
}

int usage(const char* message) {
  if (message) std::fprintf(stderr, "crestline_bench: %s\n", message);
  std::fprintf(stderr,
               "usage: crestline_bench [--runs N] [--smoke] [--only NAME,...] [--json FILE] [--export DIR]\n"
               "                       [--export-obj DIR] [--meshes DIR] [--smoothing-steps N] [--threads N]\n"
               "  meshes: bunny feline dragon (from --meshes), bunny-sub2 bunny-sub3 (generated);\n"
               "          dragon-noisy (generated) only when named in --only\n"
               "  --smoke: bunny once, for CI (a few seconds)\n"
               "  --export DIR / --export-obj DIR: write each mesh's soup to DIR/NAME.soup / DIR/NAME.obj\n");
  return message ? 2 : 0;
}

}  // namespace
}  // namespace crestline::bench

int main(int argc, char** argv) {
  using namespace crestline::bench;
  Args args;
  args.settings.pipeline.smoothing.steps = 5;  // the paper's most, the benchmark setting
  args.settings.threads = 1;                   // the targets are single-threaded unless stated
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "-h" || a == "--help")
        return usage(nullptr);
      else if (a == "--runs")
        args.settings.runs = std::max(1, std::stoi(value()));
      else if (a == "--smoke")
        args.settings.runs = 1, args.only = {"bunny"};
      else if (a == "--json")
        args.json = value();
      else if (a == "--export")
        args.export_dir = value();
      else if (a == "--export-obj")
        args.export_obj_dir = value();
      else if (a == "--meshes")
        args.meshes = value();
      else if (a == "--smoothing-steps")
        args.settings.pipeline.smoothing.steps = std::stoi(value());
      else if (a == "--threads")
        args.settings.threads = std::max(1, std::stoi(value()));
      else if (a == "--only") {
        const std::string list = value();
        args.only.clear();
        for (size_t start = 0; start <= list.size();) {
          const size_t comma = std::min(list.find(',', start), list.size());
          args.only.push_back(list.substr(start, comma - start));
          start = comma + 1;
        }
      } else
        return usage(("unknown argument " + a).c_str());
    } catch (const std::exception& e) {
      return usage(e.what());
    }
  }
  crestline::set_max_threads(args.settings.threads);
  // Blocks of 1 MB and more are mapped and unmapped on their own, so RSS
  // (and the peak column) follows the live data: by default glibc raises
  // its mmap threshold after the first large free and keeps later large
  // blocks resident in the heap once freed, a high-water mark of the heap
  // rather than of what the pipeline holds.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 20);

  for (const std::string& name : args.only)
    if (std::none_of(kMeshes.begin(), kMeshes.end(), [&](const MeshSpec& spec) { return spec.name == name; }))
      return usage(("no benchmark mesh is called " + name).c_str());
  std::vector<MeshResult> results;
  for (const MeshSpec& spec : kMeshes) {
    const bool named = std::find(args.only.begin(), args.only.end(), spec.name) != args.only.end();
    if (args.only.empty() ? !spec.by_default : !named) continue;
    std::fprintf(stderr, "crestline_bench: %s …\n", spec.name.c_str());
    results.push_back(measure_in_child(spec, args));
  }
  std::printf("Seconds, median of %d run%s, %d thread%s, %d smoothing steps; total = repair + topology + stages\n",
              args.settings.runs, args.settings.runs == 1 ? "" : "s", args.settings.threads,
              args.settings.threads == 1 ? "" : "s", args.settings.pipeline.smoothing.steps);
  print_table(results);
  if (!args.json.empty()) {
    std::ofstream out(args.json);
    out << to_json(results, args.settings);
    if (!out) {
      std::fprintf(stderr, "crestline_bench: %s: cannot be written.\n", args.json.c_str());
      return 1;
    }
  }
  bool failed = false;
  for (const MeshResult& r : results) failed = failed || r.error[0];
  return failed ? 1 : 0;
}
