// Limits (issue 8): lying headers are refused before anything is allocated
// for them, configured size limits refuse with one clear sentence, and
// pathological meshes (thousands of components, one vertex of degree
// 10,000) cost time in proportion to their size, and the pipeline's peak
// memory per triangle stays where it was measured (issue 14).
#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <string>
#include <utility>

#include "analytic_meshes.h"
#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "crestline/numerics/parallel.h"
#include "run_pipeline.h"

using namespace crestline;
using crestline::testing::add_triangle;
using crestline::testing::add_vertex;

// --- the largest single allocation ------------------------------------------
// Replacing the global operator new is the only portable way to see what a
// reader allocates before it refuses. It forwards to malloc (which ASan
// still checks) and records sizes only inside an AllocationWatch.
namespace {
thread_local bool watching = false;
thread_local size_t largest_allocation = 0;
// Every thread's allocations, while `counting` (the complexity guards).
std::atomic<bool> counting{false};
std::atomic<uint64_t> allocated_bytes{0}, allocations{0};
// Bytes allocated and not yet freed, in every thread, and their highest
// value since it was last reset (the memory guard). Each block starts with
// a header that holds its size, for the delete that has none.
std::atomic<int64_t> live_bytes{0}, peak_live_bytes{0};
constexpr size_t kHeader = alignof(std::max_align_t);
}  // namespace

// Every unaligned form is replaced, so each delete meets the new it belongs
// to (the aligned forms stay the library's, in pairs of their own).
namespace {
void* watched_malloc(size_t size) noexcept {
  if (watching && size > largest_allocation) largest_allocation = size;
  if (counting.load(std::memory_order_relaxed)) {
    allocated_bytes.fetch_add(size, std::memory_order_relaxed);
    allocations.fetch_add(1, std::memory_order_relaxed);
  }
  if (size > std::numeric_limits<size_t>::max() - kHeader) return nullptr;
  auto* block = static_cast<unsigned char*>(std::malloc(kHeader + size));
  if (!block) return nullptr;
  std::memcpy(block, &size, sizeof size);
  const int64_t live = live_bytes.fetch_add(int64_t(size), std::memory_order_relaxed) + int64_t(size);
  int64_t peak = peak_live_bytes.load(std::memory_order_relaxed);
  while (live > peak && !peak_live_bytes.compare_exchange_weak(peak, live, std::memory_order_relaxed)) {
  }
  return block + kHeader;
}
void* watched_new(size_t size) {
  if (void* p = watched_malloc(size)) return p;
  throw std::bad_alloc();
}
void watched_free(void* p) noexcept {
  if (!p) return;
  auto* block = static_cast<unsigned char*>(p) - kHeader;
  size_t size = 0;
  std::memcpy(&size, block, sizeof size);
  live_bytes.fetch_sub(int64_t(size), std::memory_order_relaxed);
  std::free(block);
}
}  // namespace

void* operator new(size_t size) { return watched_new(size); }
void* operator new[](size_t size) { return watched_new(size); }
void* operator new(size_t size, const std::nothrow_t&) noexcept { return watched_malloc(size); }
void* operator new[](size_t size, const std::nothrow_t&) noexcept { return watched_malloc(size); }
void operator delete(void* p) noexcept { watched_free(p); }
void operator delete[](void* p) noexcept { watched_free(p); }
void operator delete(void* p, size_t) noexcept { watched_free(p); }
void operator delete[](void* p, size_t) noexcept { watched_free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { watched_free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { watched_free(p); }

namespace {

struct AllocationWatch {
  AllocationWatch() { watching = true, largest_allocation = 0; }
  ~AllocationWatch() { watching = false; }
  size_t largest() const { return largest_allocation; }
};

constexpr size_t kSmallAllocation = size_t(16) << 20;  // far below any claim here

std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

// Reads `bytes` as `name`; returns the error kind (fails when there is none)
// and checks that no single allocation came near the claimed size.
ErrorKind refusal(const std::string& name, const std::vector<uint8_t>& bytes, const io::ReadOptions& options = {}) {
  INFO(name);
  AllocationWatch watch;
  try {
    io::read_mesh_bytes(name, bytes, {}, options);
  } catch (const Error& e) {
    const size_t largest = watch.largest();
    INFO(e.what());
    CHECK(largest < kSmallAllocation);
    CHECK(std::string(e.what()).rfind(name + ": ", 0) == 0);
    return e.kind();
  }
  FAIL("read without an error");
  return ErrorKind::Io;
}

// A glTF whose buffer holds `bytes` zero bytes (a multiple of 3) in a data
// URI but declares `byte_length`, with a POSITION accessor of `count`.
std::string gltf_with_accessor(const std::string& count, const std::string& byte_length, size_t bytes = 12) {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "buffers":[{"byteLength":)" +
         byte_length + R"(,"uri":"data:application/octet-stream;base64,)" + std::string(bytes / 3 * 4, 'A') + R"("}],
    "bufferViews":[{"buffer":0,"byteLength":)" +
         std::to_string(bytes) + R"(}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":)" +
         count + R"(,"type":"VEC3"}]})";
}

}  // namespace

TEST_CASE("headers claiming gigabytes are refused before allocating", "[hardening][limits]") {
  const std::string ply_vertices = "ply\nformat binary_little_endian 1.0\nelement vertex ";
  const std::string ply_rest =
      "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  // Beyond the limit of 50M triangles: TooLarge. Below it but more than the
  // bytes that follow: InvalidInput. Either way nothing is allocated for it.
  CHECK(refusal("huge.ply", bytes_of(ply_vertices + "4000000000" + ply_rest)) == ErrorKind::TooLarge);
  CHECK(refusal("lying.ply", bytes_of(ply_vertices + "40000000" + ply_rest + std::string(64, '\0'))) ==
        ErrorKind::InvalidInput);
  CHECK(refusal("faces.ply", bytes_of("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nelement face 45000000\nproperty list uint int vertex_indices\n"
                                      "end_header\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n")) ==
        ErrorKind::InvalidInput);

  std::vector<uint8_t> stl(84 + 50, 0);
  const uint32_t claimed = 0xFFFFFFFFu;  // 214 GB of facets
  std::memcpy(&stl[80], &claimed, 4);
  CHECK(refusal("huge.stl", stl) == ErrorKind::InvalidInput);

  CHECK(refusal("huge.off", bytes_of("OFF\n2000000000 1 0\n0 0 0\n")) == ErrorKind::TooLarge);
  CHECK(refusal("lying.off", bytes_of("OFF\n40000000 40000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")) ==
        ErrorKind::InvalidInput);
  CHECK(refusal("polygon.off", bytes_of("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n")) ==
        ErrorKind::InvalidInput);

  // OBJ has no header: its claims are indices far beyond the vertices read.
  CHECK(refusal("index.obj", bytes_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n")) == ErrorKind::InvalidInput);
  CHECK(refusal("negative.obj", bytes_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4000000000\n")) == ErrorKind::InvalidInput);

  CHECK(refusal("count.gltf", bytes_of(gltf_with_accessor("1000000000", "12"))) == ErrorKind::TooLarge);
  CHECK(refusal("lying.gltf", bytes_of(gltf_with_accessor("40000000", "12"))) == ErrorKind::InvalidInput);
  CHECK(refusal("buffer.gltf", bytes_of(gltf_with_accessor("1", "4000000000"))) == ErrorKind::InvalidInput);
  std::vector<uint8_t> glb = bytes_of(std::string("glTF") + std::string(16, '\0'));
  const uint32_t header[4] = {2, 0xFFFFFFF0u, 0xFFFFFF00u, 0x4E4F534Au};  // version, length, JSON length, "JSON"
  std::memcpy(&glb[4], header, sizeof header);
  CHECK(refusal("huge.glb", glb) == ErrorKind::InvalidInput);
}

// A mesh of `triangles` zero-area triangles (a POSITION accessor without a
// bufferView: zeros) placed `placements` times, by nodes or by one node's
// EXT_mesh_gpu_instancing (a TRANSLATION accessor of zeros); padded so the
// accessors' counts stay below one element per byte of the file.
std::string amplifying_gltf(size_t placements, bool gpu, size_t triangles = 10'000) {
  std::string nodes;
  if (gpu) {
    nodes = R"({"mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1}}}})";
  } else {
    for (size_t i = 0; i < placements; ++i) nodes += std::string(i ? "," : "") + R"({"mesh":0})";
  }
  const std::string text = R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_mesh_gpu_instancing"],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"componentType":5126,"count":)" +
                           std::to_string(3 * triangles) + R"(,"type":"VEC3"},
                 {"componentType":5126,"count":)" +
                           std::to_string(placements) + R"(,"type":"VEC3"}],
    "nodes":[)" + nodes + "]";
  return text + R"(,"extras":")" + std::string(std::max<size_t>(placements, 3 * triangles), ' ') + "\"}";
}

TEST_CASE("instances are counted before they are expanded", "[hardening][limits]") {
  // 6000 placements of 10^4 triangles: 6·10^7, past the limit of 5·10^7.
  // Expanding first took 4 GB before the limit was reached.
  for (const bool gpu : {false, true}) {
    INFO((gpu ? "EXT_mesh_gpu_instancing" : "nodes"));
    CHECK(refusal("forest.gltf", bytes_of(amplifying_gltf(6000, gpu))) == ErrorKind::TooLarge);
    try {
      io::read_mesh_bytes("forest.gltf", bytes_of(amplifying_gltf(6000, gpu)));
    } catch (const Error& e) {
      CHECK(std::string(e.what()) ==
            "forest.gltf: the scene places its meshes 6000 times, which expands to 60000000 triangles, more than "
            "the limit of 50000000.");
    }
    // Within the limit the same file is read, every instance expanded.
    io::ReadOptions small;
    small.max_triangles = 50'000;
    CHECK(refusal("grove.gltf", bytes_of(amplifying_gltf(6, gpu)), small) == ErrorKind::TooLarge);
    small.max_triangles = 60'000;
    CHECK(io::read_mesh_bytes("grove.gltf", bytes_of(amplifying_gltf(6, gpu)), {}, small).triangle_count() == 60'000);
  }
}

// Issue 18, item 4: a 1 MB glTF placing a 48-triangle mesh 10^6 times
// (48·10^6 triangles, under the triangle limit) took 4 GB and 18 s. The
// expansion may not exceed the larger of 4·10^6 triangles and 16 times the
// triangles stored; it is refused before anything is expanded (no large
// allocation), and scenes within either bound are read in full.
TEST_CASE("instances may not amplify a small file", "[hardening][limits]") {
  const std::vector<uint8_t> example = bytes_of(amplifying_gltf(1'000'000, true, 48));
  CHECK(example.size() < 1'100'000);
  CHECK(refusal("amplified.gltf", example) == ErrorKind::TooLarge);
  try {
    io::read_mesh_bytes("amplified.gltf", example);
  } catch (const Error& e) {
    CHECK(std::string(e.what()) ==
          "amplified.gltf: the scene places its meshes 1000000 times, which expands their 48 triangles to 48000000, "
          "more than the limit of 4000000 (16 times the triangles stored, or 4000000 if that is more).");
  }
  // By nodes: 1000 of them placing 4800 triangles, 4.8·10^6, just past the floor.
  CHECK(refusal("nodes.gltf", bytes_of(amplifying_gltf(1000, false, 4800))) == ErrorKind::TooLarge);

  // Both bounds, scaled down: 16 placements of 48 triangles stay within 16
  // times the stored triangles, 17 do not unless the floor allows them.
  io::ReadOptions options;
  options.max_expanded_triangles = 100;
  for (const bool gpu : {false, true}) {
    INFO((gpu ? "EXT_mesh_gpu_instancing" : "nodes"));
    CHECK(io::read_mesh_bytes("sixteen.gltf", bytes_of(amplifying_gltf(16, gpu, 48)), {}, options).triangle_count() ==
          16 * 48);
    CHECK(refusal("seventeen.gltf", bytes_of(amplifying_gltf(17, gpu, 48)), options) == ErrorKind::TooLarge);
    io::ReadOptions floor = options;
    floor.max_expanded_triangles = 17 * 48;
    CHECK(io::read_mesh_bytes("seventeen.gltf", bytes_of(amplifying_gltf(17, gpu, 48)), {}, floor).triangle_count() ==
          17 * 48);
  }
}

TEST_CASE("configured size limits refuse with one sentence", "[hardening][limits]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 10;  // 200 triangles
  const TriangleSoup soup = testing::height_field([](double x, double y) { return x * y; }, 1, 1, grid);
  RepairOptions repair;
  repair.max_triangles = 199;
  try {
    repair_mesh(soup, repair);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::TooLarge);
    CHECK(std::string(e.what()) == "the mesh has 200 triangles, more than the limit of 199.");
  }
  io::ReadOptions read;
  read.max_triangles = 2;
  CHECK(refusal("many.gltf", bytes_of(gltf_with_accessor("9", "108", 108)), read) == ErrorKind::TooLarge);
  CHECK(refusal("many.off", bytes_of("OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n3 0 1 3\n"), read) ==
        ErrorKind::TooLarge);
}

// --- complexity ---------------------------------------------------------------
// No stage may be super-linear in a pathological input. The guard compares
// the pathological mesh with an ordinary grid of the same triangle count in
// what the whole pipeline allocates, counted in every thread: the number of
// allocations and their bytes. Unlike a timing, the count is the same in a
// sanitized build and on a loaded machine, so the guard asserts structure,
// not speed (the project checks speed with benchmarks). A stage that keeps
// per-component or per-neighbour scratch sized by the whole mesh allocates
// hundreds of times more here (3,000 components × 24,000 triangles, or
// 10,000² neighbour pairs around the hub); the 10× margin allows honest
// constant-factor differences (many tiny solves, the hub's long slivers).
namespace {

struct Allocated {
  uint64_t bytes = 0, count = 0;
  uint64_t lines = 0;  // ridges, valleys and creases the run found
};

Allocated allocated_by_pipeline(const TriangleSoup& soup) {
  allocated_bytes = 0, allocations = 0;
  counting = true;
  const Pipeline p = testing::run_pipeline(soup);
  counting = false;
  return {allocated_bytes.load(), allocations.load(), p.all_kinds().size()};
}

// A wavy grid with about `triangles` triangles: the linear baseline.
TriangleSoup baseline(size_t triangles) {
  testing::GridOptions grid;
  grid.nu = grid.nv = int(std::ceil(std::sqrt(double(triangles) / 2)));
  grid.jitter = 0.2;
  grid.random_diagonals = true;
  return testing::height_field([](double x, double y) { return 0.1 * std::sin(9 * x) * std::cos(7 * y); }, 1, 1, grid);
}

void check_linear(const TriangleSoup& pathological, const char* what) {
  const Allocated base = allocated_by_pipeline(baseline(pathological.triangle_count()));
  const Allocated work = allocated_by_pipeline(pathological);
  INFO(what << ": " << pathological.triangle_count() << " triangles: " << work.count << " allocations of " << work.bytes
            << " bytes, " << work.lines << " lines; a grid of the same size " << base.count << " of " << base.bytes);
  CHECK(work.bytes < 10 * base.bytes);
  // Each line found costs a few allocations of its own (its chain, points,
  // curvatures): the octahedra's 36,000 crease edges are 36,000 lines.
  constexpr uint64_t kAllocationsPerLine = 16;
  CHECK(work.count < 10 * base.count + kAllocationsPerLine * work.lines);
}

}  // namespace

TEST_CASE("thousands of tiny components cost linear time", "[hardening][limits][complexity]") {
  // 3,000 slightly bumpy octahedra, each its own component: 24,000 triangles.
  TriangleSoup s;
  for (int c = 0; c < 3000; ++c) {
    const Vec3 centre(3.0 * (c % 70), 3.0 * (c / 70), 0.1 * (c % 7));
    const uint32_t base = uint32_t(s.vertex_count());
    const Vec3 corners[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1.0 + 0.01 * (c % 5)}, {0, 0, -1}};
    for (const Vec3& p : corners) add_vertex(s, centre + p);
    const uint32_t faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                  {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (const auto& f : faces) add_triangle(s, base + f[0], base + f[1], base + f[2]);
  }
  const RepairResult repaired = repair_mesh(s);
  CHECK(repaired.report.components == 3000);
  check_linear(s, "components");
}

TEST_CASE("a vertex of degree 10,000 costs linear time", "[hardening][limits][complexity]") {
  // A wavy disc: the centre joined to 10,000 spokes, two rings around it
  // (30,000 triangles).
  TriangleSoup s;
  const uint32_t spokes = 10000, rings = 2;
  add_vertex(s, Vec3(0, 0, 0.2));
  for (uint32_t r = 1; r <= rings; ++r)
    for (uint32_t i = 0; i < spokes; ++i) {
      const double a = 2 * testing::kPi * i / spokes;
      add_vertex(s, Vec3(r * std::cos(a), r * std::sin(a), 0.05 * r * std::sin(6 * a)));
    }
  auto ring = [&](uint32_t r, uint32_t i) { return 1 + (r - 1) * spokes + i % spokes; };
  for (uint32_t i = 0; i < spokes; ++i) add_triangle(s, 0, ring(1, i), ring(1, i + 1));
  for (uint32_t r = 1; r < rings; ++r)
    for (uint32_t i = 0; i < spokes; ++i) {
      add_triangle(s, ring(r, i), ring(r + 1, i), ring(r + 1, i + 1));
      add_triangle(s, ring(r, i), ring(r + 1, i + 1), ring(r, i + 1));
    }
  const Pipeline p = testing::run_pipeline(s);
  CHECK(p.input_mesh().vertex_count() == 1 + spokes * rings);
  check_linear(s, "hub");
}

// --- memory ---------------------------------------------------------------------
// The pipeline's peak memory per triangle (issue 14), counted as massif
// counts it: the live bytes of every thread, above what is live once the
// repaired mesh exists (the Pipeline then takes it over), for the first run
// and a re-smoothing; one thread, as the benchmark's peak column. The mesh:
// the cut test's bumpy field (57,800 triangles) with its 44° fold, so that
// a crease cut serves the smooth stages (as on the benchmark's bunny,
// dragon and 1.1M), and without it (the feline). Measured, first run and
// re-smoothing: fold 203.9 and 203.9, no fold 198.8 and 198.8 (2dd3268:
// 208.0 and 202.8, before the smoothing freed its frozen band's vertex
// weights ahead of the solves; 294cb6c: 236.3 / 240.3 and 255.1 / 259.8,
// before the normals and star areas were freed for real, the input's
// triangles released, the lines released before a run that remakes them
// and the uncut crease angles compacted). The limits leave 1 %.
namespace {

void reset_peak() { peak_live_bytes = live_bytes.load(); }

double peak_per_triangle(int64_t base, size_t triangles) {
  return double(peak_live_bytes.load() - base) / double(triangles);
}

// Peak bytes per triangle above the repaired mesh: the first run's, then a
// re-smoothing's.
std::pair<double, double> pipeline_peaks(Mesh mesh, bool cut) {
  const int threads = max_threads();
  set_max_threads(1);
  const size_t triangles = mesh.triangle_count();
  const int64_t base = live_bytes.load();
  reset_peak();
  Pipeline p(std::move(mesh));
  PipelineOptions o;
  o.smoothing.steps = 5;  // the benchmark's setting
  p.set_options(o);
  p.run();
  const double run = peak_per_triangle(base, triangles);
  CHECK(p.working_cut().copy_of.empty() == !cut);
  CHECK(!p.lines().empty());
  o.smoothing.time_step *= 1.5;
  p.set_options(o);
  reset_peak();
  p.run();
  set_max_threads(threads);
  return {run, peak_per_triangle(base, triangles)};
}

}  // namespace

TEST_CASE("the pipeline's peak memory per triangle stays as measured", "[hardening][limits][memory]") {
  testing::GridOptions grid;
  grid.nu = grid.nv = 170;
  for (const bool fold : {true, false}) {
    const Mesh mesh =
        repair_mesh(testing::height_field(
                        [fold](double x, double y) {
                          return 0.1 * std::cos(5 * x) * std::cos(4 * y) + (fold ? 0.4 * std::abs(x - 1) : 0);
                        },
                        2, 2, grid))
            .mesh;
    const auto [run, rerun] = pipeline_peaks(mesh, fold);
    INFO((fold ? "fold" : "no fold") << ", " << mesh.triangle_count() << " triangles: first run " << run
                                     << " bytes per triangle, re-smoothing " << rerun);
    CHECK(run < (fold ? 206.0 : 201.0));
    CHECK(rerun < (fold ? 206.0 : 201.0));
  }
}
