#pragma once
// What the fuzz targets do with one input, shared with the regression test
// that replays every input they ever crashed on
// (tests/unit/hardening/replay_test.cpp). Each check returns "" when the
// input was handled (read, or refused with a crestline::Error) and a short
// description of the broken contract otherwise; sanitizers, crashes and
// exceptions of other types propagate.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "crestline/mesh/repair.h"
#include "crestline/pipeline.h"

namespace crestline::fuzz {

// --- readers -----------------------------------------------------------------

inline const char* file_name_for(io::MeshFormat format) {
  switch (format) {
    case io::MeshFormat::Obj:
      return "fuzz.obj";
    case io::MeshFormat::Gltf:
      return "fuzz.gltf";  // also serves GLB: the reader checks the magic
    case io::MeshFormat::Glb:
      return "fuzz.glb";
    case io::MeshFormat::Ply:
      return "fuzz.ply";
    case io::MeshFormat::Stl:
      return "fuzz.stl";
    case io::MeshFormat::Off:
      return "fuzz.off";
    case io::MeshFormat::Auto:
      break;
  }
  return "fuzz";
}

/// One reader on arbitrary bytes, its format forced so detection never
/// routes the input elsewhere. An accepted soup must keep the readers'
/// contract: whole triangles, at least one, every index in range.
inline std::string check_read(io::MeshFormat format, const uint8_t* data, size_t size) {
  io::ReadOptions options;
  options.format = format;
  // Small enough that a lying header is refused rather than exhausting the
  // fuzzer's memory limit, large enough for every seed.
  options.max_triangles = 1'000'000;
  const std::vector<uint8_t> bytes(data, data + size);
  try {
    const TriangleSoup soup = io::read_mesh_bytes(file_name_for(format), bytes, {}, options);
    if (soup.positions.size() % 3 != 0 || soup.indices.size() % 3 != 0) return "partial vertex or triangle";
    if (soup.indices.empty()) return "accepted without triangles";
    for (uint32_t index : soup.indices) {
      if (index >= soup.vertex_count()) return "index out of range";
    }
  } catch (const Error&) {
    // A refusal with a message: the expected outcome for most inputs.
  }
  return "";
}

// --- whole pipeline ----------------------------------------------------------

/// A small mesh and options decoded from fuzzer bytes. Two shapes, chosen by
/// the first byte:
///   - a free soup: up to 64 vertices on a coarse lattice (so coincident
///     vertices, collinear corners, slivers and zero-area triangles are
///     common) with arbitrary index triples (non-manifold edges and
///     vertices, duplicates, flips);
///   - a height field on an n×n grid with heights from the bytes (a valid
///     surface that has lines, so tracing, singular triangles, joining and
///     fairing all run), plus arbitrary triangles glued on.
/// Either is then scaled (1e-300 … 1e300) and translated (up to 1e12); some
/// coordinates may be NaN, infinite or subnormal.
struct PipelineInput {
  TriangleSoup soup;
  RepairOptions repair;
  PipelineOptions options;
};

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : p_(data), end_(data + size) {}
  size_t left() const { return size_t(end_ - p_); }
  uint8_t next() { return p_ < end_ ? *p_++ : 0; }

 private:
  const uint8_t* p_;
  const uint8_t* end_;
};

// A coordinate: mostly a small lattice value, sometimes a special one.
inline double lattice_coordinate(uint8_t b) {
  switch (b) {
    case 250:
      return std::numeric_limits<double>::quiet_NaN();
    case 251:
      return std::numeric_limits<double>::infinity();
    case 252:
      return 1e-300;
    case 253:
      return 1e300;
    case 254:
      return std::numeric_limits<double>::denorm_min();
    case 255:
      return -std::numeric_limits<double>::max();
    default:
      return (double(b % 25) - 12.0) / 4.0 + double(b / 25) * 1e-9;
  }
}

inline void add_random_triangles(ByteReader& in, TriangleSoup& soup, uint32_t nv, size_t max_triangles) {
  while (in.left() >= 3 && soup.indices.size() < 3 * max_triangles) {
    for (int k = 0; k < 3; ++k) soup.indices.push_back(in.next() % nv);
  }
}

inline void decode_soup(ByteReader& in, TriangleSoup& soup) {
  const uint32_t nv = 3 + in.next() % 62;
  for (uint32_t k = 0; k < 3 * nv; ++k) soup.positions.push_back(lattice_coordinate(in.next()));
  add_random_triangles(in, soup, nv, 256);
}

inline void decode_grid(ByteReader& in, TriangleSoup& soup) {
  const uint32_t n = 3 + in.next() % 10;  // vertices per side
  const double amplitude = double(in.next()) / 64.0;
  for (uint32_t j = 0; j < n; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      const double h = amplitude * (double(int8_t(in.next())) / 128.0);
      soup.positions.insert(soup.positions.end(), {double(i), double(j), h});
    }
  }
  const uint8_t diagonals = in.next();
  for (uint32_t j = 0; j + 1 < n; ++j) {
    for (uint32_t i = 0; i + 1 < n; ++i) {
      const uint32_t a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      if ((diagonals >> ((i + j) % 8)) & 1) {
        soup.indices.insert(soup.indices.end(), {a, b, c, a, c, d});
      } else {
        soup.indices.insert(soup.indices.end(), {a, b, d, b, c, d});
      }
    }
  }
  add_random_triangles(in, soup, n * n, 512);
}

inline PipelineInput decode_pipeline_input(const uint8_t* data, size_t size) {
  static const double scales[] = {1, 1e-8, 1e8, 1e-300, 1e300, 1e-150, 1e150, -1, 1e-3, 1e3, 1e-20, 1e20};
  static const double shifts[] = {0, 1e6, -1e6, 1e12, 0.5, 1e-6};
  ByteReader in(data, size);
  const uint8_t shape = in.next(), transform = in.next(), option_bits = in.next();
  PipelineInput out;
  if (shape & 1)
    decode_grid(in, out.soup);
  else
    decode_soup(in, out.soup);
  const double scale = scales[(transform & 15) % (sizeof scales / sizeof scales[0])];
  const double shift = shifts[(transform >> 4) % (sizeof shifts / sizeof shifts[0])];
  for (double& c : out.soup.positions) c = c * scale + shift;
  out.options.presmooth.steps = static_cast<int>(option_bits & 1);
  out.options.smoothing.steps = (option_bits >> 1) & 3;
  out.options.trace.boundary_rings = (option_bits >> 3) & 3;
  out.options.fairing.iterations = (option_bits >> 5) & 1 ? 5 : 30;
  if ((option_bits >> 6) & 1) out.options.filter.threshold = 0.0;  // else automatic
  out.repair.weld_tolerance = (option_bits >> 7) & 1 ? 0.0 : 1e-7;
  return out;
}

/// repair_mesh + Pipeline::run; every line that comes out must be finite.
inline std::string check_pipeline(const uint8_t* data, size_t size) {
  const PipelineInput input = decode_pipeline_input(data, size);
  try {
    Pipeline pipeline(repair_mesh(input.soup, input.repair).mesh);
    pipeline.set_options(input.options);
    pipeline.run();
    for (const Polyline& line : pipeline.all_lines()) {
      if (!std::isfinite(line.strength) || !std::isfinite(line.length)) return "non-finite strength or length";
      for (const Vec3& p : line.points) {
        if (!p.allFinite()) return "non-finite line point";
      }
    }
  } catch (const Error&) {
    // Refused with a message (no usable triangle, overflow, solver failure).
  }
  return "";
}

}  // namespace crestline::fuzz
