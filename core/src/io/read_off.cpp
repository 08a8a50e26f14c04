// Object File Format: "OFF" (optionally with the C/N/ST prefixes of colour,
// normal and texture variants), then "nv nf ne", nv vertex lines and nf face
// lines "n i0 .. i(n-1)". '#' starts a comment. Values after the first three
// coordinates or after a face's indices (colours, normals) are ignored.
#include "readers.h"

namespace crestline::io::detail {

TriangleSoup read_off(const Input& in, const ReadOptions& options) {
  TextScanner text(in.data, in.size, true);
  std::string_view keyword;
  if (!text.next_line() || !text.word(keyword) || keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") {
    fail(ErrorKind::InvalidInput, in, "the file does not start with the OFF keyword.");
  }
  if (keyword.find('4') != std::string_view::npos || keyword.find('n') != std::string_view::npos) {
    fail(ErrorKind::Unsupported, in, "only 3D OFF files are supported, not " + std::string(keyword) + ".");
  }
  TextScanner probe = text;
  std::string_view next;
  if (probe.word(next) && next == "BINARY") {
    fail(ErrorKind::Unsupported, in, "binary OFF files are not supported.");
  }
  // "nv nf [ne]" follow the keyword on its line or start the next one.
  int64_t counts[3] = {0, 0, 0};
  int found = 0;
  while (found < 3 && text.integer(counts[found])) ++found;
  if (found == 0 && text.next_line()) {
    while (found < 3 && text.integer(counts[found])) ++found;
  }
  if (found < 2 || counts[0] < 0 || counts[1] < 0) {
    fail(ErrorKind::InvalidInput, in, "the header does not give the vertex and face counts.");
  }
  // Each vertex line holds at least "x y z" (6 bytes), each face line "3 a b c".
  check_claim(in, options, uint64_t(counts[0]), 6, text.bytes_left(), "vertices");
  check_claim(in, options, uint64_t(counts[1]), 8, text.bytes_left(), "faces");

  TriangleSoup soup;
  const size_t vertices = size_t(counts[0]);
  soup.positions.reserve(3 * vertices);
  for (size_t v = 0; v < vertices; ++v) {
    double xyz[3];
    if (!text.next_line() || !text.number(xyz[0]) || !text.number(xyz[1]) || !text.number(xyz[2])) {
      fail(ErrorKind::InvalidInput, in,
           "vertex " + std::to_string(v) + " (line " + std::to_string(text.line_number()) +
               ") does not have three coordinates.");
    }
    soup.positions.insert(soup.positions.end(), xyz, xyz + 3);
  }
  std::vector<uint32_t> polygon;
  size_t short_faces = 0;
  for (int64_t f = 0; f < counts[1]; ++f) {
    int64_t n = 0;
    if (!text.next_line() || !text.integer(n) || n < 0 || uint64_t(n) > text.bytes_left() + 4096) {
      fail(ErrorKind::InvalidInput, in,
           "face " + std::to_string(f) + " (line " + std::to_string(text.line_number()) +
               ") does not start with its vertex count.");
    }
    polygon.clear();
    for (int64_t k = 0; k < n; ++k) {
      int64_t index = -1;
      if (!text.integer(index)) {
        fail(ErrorKind::InvalidInput, in,
             "face " + std::to_string(f) + " (line " + std::to_string(text.line_number()) + ") lists fewer than " +
                 std::to_string(n) + " vertex indices.");
      }
      if (index < 0 || uint64_t(index) >= vertices) {
        fail(ErrorKind::InvalidInput, in,
             "face " + std::to_string(f) + " refers to vertex " + std::to_string(index) + " but the file has " +
                 std::to_string(vertices) + " vertices.");
      }
      polygon.push_back(uint32_t(index));
    }
    if (n < 3) {
      ++short_faces;
      continue;
    }
    add_polygon(soup, polygon.data(), polygon.size());
    if (soup.triangle_count() > options.max_triangles) {
      fail(ErrorKind::TooLarge, in, "the file has more than " + std::to_string(options.max_triangles) + " triangles.");
    }
  }
  if (short_faces > 0) {
    soup.notes.push_back(std::to_string(short_faces) + " faces with fewer than 3 vertices were skipped.");
  }
  finish_soup(soup, in);
  return soup;
}

}  // namespace crestline::io::detail
