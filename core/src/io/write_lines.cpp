// Text writers for feature lines: the OBJ contract, JSON and the stats
// object. Hand-formatted (no JSON library) so the file compiles unchanged
// with em++; every coordinate is printed so that it parses back to the same
// double.
#include "crestline/io/write_lines.h"

#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "../mesh/parts.h"
#include "crestline/numerics/parallel.h"

namespace crestline::io {
namespace {

// `value` as printf's %.*g with `precision` writes it; returns the end.
// std::to_chars with a precision is defined as that printf format and is
// several times faster than glibc's printf; Emscripten's libc++ has no
// floating-point to_chars (no __cpp_lib_to_chars), so WASM uses snprintf.
// Both are exact (correctly rounded), so native and WASM files are the same
// bytes (tests/unit/io/write_lines_test.cpp checks to_chars against snprintf).
char* format_general(char* first, char* last, double value, int precision) {
#ifdef __cpp_lib_to_chars
  return std::to_chars(first, last, value, std::chars_format::general, precision).ptr;
#else
  const int n = std::snprintf(first, size_t(last - first), "%.*g", precision, value);
  return first + n;
#endif
}

// "00", "01", …, "99": two digits at a time.
struct DigitPairs {
  char text[200];
  constexpr DigitPairs() : text() {
    for (size_t i = 0; i < 100; ++i) text[2 * i] = char('0' + i / 10), text[2 * i + 1] = char('0' + i % 10);
  }
  // The two digits of n < 100.
  constexpr const char* of(size_t n) const { return text + 2 * n; }
};
constexpr DigitPairs kDigitPairs;

// Shortest of %.15g/%.16g/%.17g that reads back bit-identically: compact
// files for "nice" numbers, exact round trip for all.
void append_number(std::string& out, double value) {
  if (!std::isfinite(value)) {  // JSON has no NaN/inf; OBJ readers choke on them too
    out += "null";
    return;
  }
  char buffer[64];  // room for the fixed-size copies below
  char* end = buffer;
  // The shortest digits that read back, d of them, decide it: %.15g reads
  // back exactly when d ≤ 15, and otherwise %.{d}g is the first that does —
  // the correctly rounded d digits read back when any d digits do, because
  // the decimals that read back as a double lie in an interval centred on
  // it. Not so at a power of two (the next double down is half as far) nor
  // at zero or below the normal range (fewer digits read back there): the
  // loop below. The printed digits are the shortest digits themselves (with
  // d ≤ 15 because any decimal of at most DBL_DIG = 15 digits survives
  // decimal → double → 15 digits; with d = 16 or 17 both are the d digits
  // nearest the value, exact ties to even), so they are laid out as
  // %.{max(15, d)}g would lay them out instead of formatting again.
  // Neither a power of two nor below the normal range (nor zero): a
  // significand field not zero and an exponent field not zero.
  uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  if ((bits & ((uint64_t{1} << 52) - 1)) != 0 && (bits & (uint64_t{0x7ff} << 52)) != 0) {
    // The shortest digits by {fmt}'s Dragonbox (the digits std::to_chars's
    // shortest form writes: the nearest of the shortest, ties to even;
    // tests/unit/io/write_lines_test.cpp checks the bytes against printf): ≈ 110 instructions a number
    // against ≈ 600 for libstdc++'s to_chars, and the same code in WASM,
    // whose libc++ has no floating-point to_chars. An internal of {fmt} 9
    // (Debian bookworm's libfmt-dev, header-only), stable through 11.
    const auto decimal = fmt::detail::dragonbox::to_decimal(std::abs(value));
    // The digits end at digits + 20, followed by padding: the layout below
    // copies 17 bytes (constant-size copies, a few instructions) wherever up
    // to 17 digits or zeros go and then counts only those it needs.
    char digits[40] = {};
    char* const digits_end = digits + 20;
    char* first = digits_end;
    uint64_t significand = decimal.significand;  // below 10^17
    if (significand >= 100000000) {
      // The last 8 digits in 32-bit arithmetic, four independent pairs (most
      // coordinates have 16 or 17 digits).
      const auto low = uint32_t(significand % 100000000);
      significand /= 100000000;
      const uint32_t high4 = low / 10000, low4 = low % 10000;
      first -= 8;
      std::memcpy(first, kDigitPairs.of(high4 / 100), 2);
      std::memcpy(first + 2, kDigitPairs.of(high4 % 100), 2);
      std::memcpy(first + 4, kDigitPairs.of(low4 / 100), 2);
      std::memcpy(first + 6, kDigitPairs.of(low4 % 100), 2);
    }
    auto s = uint32_t(significand);  // below 10^9, not 0
    for (; s >= 100; s /= 100) first -= 2, std::memcpy(first, kDigitPairs.of(s % 100), 2);
    if (s >= 10)
      first -= 2, std::memcpy(first, kDigitPairs.of(s), 2);
    else
      *--first = char('0' + s);
    const int d = int(digits_end - first);
    const int x = decimal.exponent + d - 1;  // the decimal exponent of the first digit
    if (value < 0) *end++ = '-';
    constexpr size_t kCopy = 17;
    if (x < -4 || x >= std::max(15, d)) {  // %g's exponent form: d[.ddd]e±XX
      end[0] = first[0], end[1] = '.';
      std::memcpy(end + 2, first + 1, kCopy);
      end += d > 1 ? d + 1 : 1;
      *end++ = 'e', *end++ = x < 0 ? '-' : '+';
      const int magnitude = std::abs(x);
      if (magnitude >= 100) *end++ = char('0' + magnitude / 100);
      std::memcpy(end, kDigitPairs.of(magnitude % 100), 2);
      end += 2;
    } else if (x >= 0) {  // x < 17: the digits, then zeros or the point and the rest
      std::memcpy(end, first, kCopy);
      if (d <= x + 1) {
        std::memset(end + d, '0', kCopy);
        end += x + 1;
      } else {
        end += x + 1;
        *end = '.';
        std::memcpy(end + 1, first + x + 1, kCopy);
        end += d - x;
      }
    } else {  // −4 ≤ x < 0: 0.000ddd
      std::memcpy(end, "0.000", 5);
      end += 1 - x;
      std::memcpy(end, first, kCopy);
      end += d;
    }
    out.append(buffer, size_t(end - buffer));
    return;
  }
  // Read back by fast_float (correctly rounded, as strtod: the same test):
  // Emscripten's libc++ strtod costs ≈ 1 µs a number (25× fast_float; the
  // dragon's JSON took 1.1–1.5 s when every number came this way).
  for (int precision = 15; precision <= 17; ++precision) {
    end = format_general(buffer, buffer + sizeof buffer - 1, value, precision);
    double back = 0;
    if (precision == 17 || (fast_float::from_chars(buffer, end, back).ec == std::errc() && back == value)) break;
  }
  out.append(buffer, end);
}

void append_count(std::string& out, size_t value) {
  char buffer[24];
  out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

// Parts for formatting `count` items (lines of a few to thousands of
// numbers, or vertices) on every thread: they pay for themselves from a few
// hundred items.
size_t text_parts(size_t count) {
  constexpr size_t kItemsPerPart = 256;
  return std::min<size_t>({count / kItemsPerPart + 1, size_t(max_threads()), 8});
}

// The text being written: appended to `text` and, with a sink, handed to it
// and cleared after each batch of items that leaves it kFlushBytes or longer,
// so that a streamed file is never held whole (the 1.1M mesh's JSON is 23.6
// MB, the CLI's largest block at the end of a run).
constexpr size_t kFlushBytes = size_t{1} << 20;
// Items (or, weighted, their weight: a line's points) per batch with a sink:
// ≈ 2 MB of JSON or OBJ text.
constexpr size_t kBatchWeight = size_t{1} << 15;
struct Output {
  std::string text;
  const TextSink* sink = nullptr;
  void batch_done() {
    if (sink && text.size() >= kFlushBytes) (*sink)(text), text.clear();
  }
  void finish() {
    if (sink && !text.empty()) (*sink)(text), text.clear();
  }
};

// Appends format(i, text) for i in [first[0], first.back()) to out, in
// order: part p, items [first[p], first[p + 1]), formatted on its own thread
// into its own string, then the parts joined, so the text is the same for any
// thread count. Formatting the numbers is nearly all of a large file's
// writing (≈ 700 instructions a coordinate; 364 M for the 1.1M mesh's JSON at
// af4309a, all on the calling thread).
template <typename Format>
void append_parts(std::string& out, const std::vector<size_t>& first, const Format& format) {
  const size_t parts = first.size() - 1;
  if (parts == 1) {
    for (size_t i = first[0]; i < first[1]; ++i) format(i, out);
    return;
  }
  std::vector<std::string> text(parts);
  detail::for_each_part(parts, parts, [&](size_t p, size_t, size_t) {
    for (size_t i = first[p]; i < first[p + 1]; ++i) format(i, text[p]);
  });
  size_t size = out.size();
  for (const std::string& t : text) size += t.size();
  out.reserve(size);
  for (const std::string& t : text) out += t;
}

// append_parts over items [begin, end), in batches of about kBatchWeight
// weight (weight(i): a line's points; 1 an item without one) where the
// output streams, else in one; each batch in parts of about equal weight.
// Every item's text is its own, so the bytes do not depend on the batches.
template <typename Weight, typename Format>
void append_in_parts(Output& out, size_t count, const Weight& weight, const Format& format) {
  for (size_t begin = 0, end = 0; begin < count; begin = end) {
    size_t total = 0;
    for (end = begin; end < count && (!out.sink || end == begin || total < kBatchWeight); ++end) total += weight(end);
    const size_t parts = text_parts(end - begin);
    std::vector<size_t> first(parts + 1, end);
    first[0] = begin;
    for (size_t i = begin, p = 1, sum = 0; i < end && p < parts; sum += weight(i++))
      while (p < parts && sum >= total * p / parts) first[p++] = i;
    append_parts(out.text, first, format);
    out.batch_done();
  }
}

// append_in_parts with every item of weight 1.
template <typename Format>
void append_in_parts(Output& out, size_t count, const Format& format) {
  append_in_parts(
      out, count, [](size_t) { return size_t{1}; }, format);
}

// Ridges first, then valleys, then creases, each in input order: the OBJ
// and JSON contracts both group by type.
constexpr LineType kTypes[] = {LineType::Ridge, LineType::Valley, LineType::Crease};
const char* group_name(LineType type) {
  return type == LineType::Ridge ? "ridges" : type == LineType::Valley ? "valleys" : "creases";
}

void append_vertex(std::string& out, const Vec3& p) {
  out += "v ";
  append_number(out, p.x());
  out += ' ';
  append_number(out, p.y());
  out += ' ';
  append_number(out, p.z());
  out += '\n';
}

// The line part of the OBJ contract: `v` lines, then `o ridges` and
// `o valleys` with one `l` per polyline. `vertices_before` is how many `v`
// lines the file already holds (the line vertices are numbered after them).
void append_lines_obj(Output& out, const std::vector<Polyline>& lines, size_t vertices_before) {
  // Vertices in the order ridges-then-valleys so that indices grow along the file.
  std::vector<size_t> first_index(lines.size(), 0);
  std::vector<std::vector<size_t>> of_type(std::size(kTypes));  // each type's lines with a segment
  size_t next = vertices_before + 1;                            // OBJ indices are 1-based
  for (size_t k = 0; k < std::size(kTypes); ++k) {
    for (size_t i = 0; i < lines.size(); ++i) {
      if (lines[i].type != kTypes[k] || lines[i].points.size() < 2) continue;
      of_type[k].push_back(i);
      first_index[i] = next;
      next += lines[i].points.size();
    }
  }
  for (const std::vector<size_t>& chosen : of_type) {
    append_in_parts(
        out, chosen.size(), [&](size_t j) { return lines[chosen[j]].points.size(); },
        [&](size_t j, std::string& text) {
          for (const Vec3& p : lines[chosen[j]].points) append_vertex(text, p);
        });
  }
  for (size_t k = 0; k < std::size(kTypes); ++k) {
    // Ridges and valleys always have their object; creases only when there are any.
    if (kTypes[k] == LineType::Crease && of_type[k].empty()) continue;
    out.text += "o ";
    out.text += group_name(kTypes[k]);
    out.text += '\n';
    append_in_parts(
        out, of_type[k].size(), [&](size_t j) { return lines[of_type[k][j]].points.size(); },
        [&](size_t j, std::string& text) {
          const size_t i = of_type[k][j];
          text += 'l';
          for (size_t n = 0; n < lines[i].points.size(); ++n) {
            text += ' ';
            append_count(text, first_index[i] + n);
          }
          if (lines[i].closed) {
            text += ' ';
            append_count(text, first_index[i]);
          }
          text += '\n';
        });
  }
}

void lines_obj(Output& out, const std::vector<Polyline>& lines) {
  out.text += "# crestline feature lines: o ridges, o valleys (, o creases); one l per polyline\n";
  append_lines_obj(out, lines, 0);
}

void mesh_and_lines_obj(Output& out, const Mesh& mesh, const std::vector<Polyline>& lines) {
  out.text += "# crestline surface and feature lines: o surface, o ridges, o valleys\n";
  out.text += "o surface\n";
  append_in_parts(out, mesh.positions.size(),
                  [&](size_t v, std::string& text) { append_vertex(text, mesh.positions[v]); });
  append_in_parts(out, mesh.triangles.size(), [&](size_t t, std::string& text) {
    text += 'f';
    for (uint32_t v : mesh.triangles[t]) {
      text += ' ';
      append_count(text, size_t{v} + 1);
    }
    text += '\n';
  });
  append_lines_obj(out, lines, mesh.positions.size());
}

}  // namespace

std::string stats_json(const PipelineStats& stats) {
  const std::pair<const char*, size_t> counts[] = {{"vertices", stats.vertices},
                                                   {"triangles", stats.triangles},
                                                   {"singular_max", stats.singular_max},
                                                   {"singular_min", stats.singular_min},
                                                   {"ridges", stats.ridges},
                                                   {"valleys", stats.valleys},
                                                   {"creases", stats.creases},
                                                   {"components", stats.components},
                                                   {"presmooth_steps", static_cast<size_t>(stats.presmooth_steps)},
                                                   {"smoothing_iterations", stats.smoothing_iterations}};
  const std::pair<const char*, double> measures[] = {
      {"ridge_length", stats.ridge_length},   {"valley_length", stats.valley_length},
      {"crease_length", stats.crease_length}, {"crease_angle", stats.crease_angle},
      {"threshold", stats.threshold},         {"mean_edge_length", stats.mean_edge_length},
      {"noise_level", stats.noise_level}};
  std::string out = "{";
  auto key = [&out](const char* name) {
    if (out.size() > 1 && out.back() != '{') out += ',';
    out += '"';
    out += name;
    out += "\":";
  };
  for (const auto& [name, value] : counts) key(name), append_count(out, value);
  for (const auto& [name, value] : measures) key(name), append_number(out, value);
  key("seconds");
  out += '{';
  const std::pair<const char*, double> before[] = {
      {"read", stats.read_seconds}, {"repair", stats.repair_seconds}, {"topology", stats.topology_seconds}};
  for (const auto& [name, value] : before) key(name), append_number(out, value);
  for (int s = 0; s < static_cast<int>(Stage::Count); ++s) {
    key(stage_name(static_cast<Stage>(s)));
    append_number(out, stats.seconds[s]);
  }
  key("write");
  append_number(out, stats.write_seconds);
  out += "}}";
  return out;
}

namespace {

void lines_json(Output& out, const std::vector<Polyline>& lines, const PipelineStats& stats) {
  out.text += '{';
  for (LineType type : kTypes) {
    if (type != kTypes[0]) out.text += ",\n";
    out.text += '"';
    out.text += group_name(type);
    out.text += "\":[";
    std::vector<const Polyline*> of_type;
    for (const Polyline& line : lines)
      if (line.type == type) of_type.push_back(&line);
    append_in_parts(
        out, of_type.size(), [&](size_t j) { return of_type[j]->points.size(); },
        [&](size_t j, std::string& text) {
          const Polyline& line = *of_type[j];
          text += j ? ",\n" : "\n";
          text += "{\"points\":[";
          for (size_t k = 0; k < line.points.size(); ++k) {
            if (k) text += ',';
            text += '[';
            append_number(text, line.points[k].x());
            text += ',';
            append_number(text, line.points[k].y());
            text += ',';
            append_number(text, line.points[k].z());
            text += ']';
          }
          text += "],\"strength\":";
          append_number(text, line.strength);
          text += ",\"length\":";
          append_number(text, line.length);
          text += ",\"closed\":";
          text += line.closed ? "true" : "false";
          if (type == LineType::Crease) text += line.convex ? ",\"convex\":true" : ",\"convex\":false";
          text += '}';
        });
    out.text += ']';
  }
  out.text += ",\n\"stats\":";
  out.text += stats_json(stats);
  out.text += "}\n";
}

// The whole text as one string (no sink: one batch), or streamed to `sink`.
template <typename Write>
std::string whole_text(const Write& write) {
  Output out;
  write(out);
  return std::move(out.text);
}
template <typename Write>
void streamed_text(const TextSink& sink, const Write& write) {
  Output out{{}, &sink};
  write(out);
  out.finish();
}

}  // namespace

std::string write_lines_obj(const std::vector<Polyline>& lines) {
  return whole_text([&](Output& out) { lines_obj(out, lines); });
}
void write_lines_obj(const std::vector<Polyline>& lines, const TextSink& sink) {
  streamed_text(sink, [&](Output& out) { lines_obj(out, lines); });
}

std::string write_mesh_and_lines_obj(const Mesh& mesh, const std::vector<Polyline>& lines) {
  return whole_text([&](Output& out) { mesh_and_lines_obj(out, mesh, lines); });
}
void write_mesh_and_lines_obj(const Mesh& mesh, const std::vector<Polyline>& lines, const TextSink& sink) {
  streamed_text(sink, [&](Output& out) { mesh_and_lines_obj(out, mesh, lines); });
}

std::string write_lines_json(const std::vector<Polyline>& lines, const PipelineStats& stats) {
  return whole_text([&](Output& out) { lines_json(out, lines, stats); });
}
void write_lines_json(const std::vector<Polyline>& lines, const PipelineStats& stats, const TextSink& sink) {
  streamed_text(sink, [&](Output& out) { lines_json(out, lines, stats); });
}

}  // namespace crestline::io
