// Wavefront OBJ through tinyobjloader's streaming (callback) API: it hands
// over every `f` line whole, with its raw 1-based or negative indices and no
// limit on the polygon size (its shape API truncates polygons to 255
// vertices and fans them). Polygons are ear-clipped here (add_polygon).
// Materials are never needed, so a missing .mtl is irrelevant.
#define TINYOBJLOADER_IMPLEMENTATION
#define TINYOBJLOADER_USE_DOUBLE
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <streambuf>

#include "readers.h"

namespace crestline::io::detail {
namespace {

// An istream over bytes we already hold, without copying them.
struct MemoryBuffer : std::streambuf {
  MemoryBuffer(const char* begin, size_t size) {
    char* b = const_cast<char*>(begin);
    setg(b, b, b + size);
  }
};

// UTF-16 text (with byte-order mark) as 8-bit text; non-ASCII characters,
// which can only occur in comments and names, become '?'.
bool decode_utf16(const Input& in, std::string& text) {
  if (in.size < 2) return false;
  const bool big = in.data[0] == 0xFE && in.data[1] == 0xFF;
  const bool little = in.data[0] == 0xFF && in.data[1] == 0xFE;
  if (!big && !little) return false;
  text.reserve(in.size / 2);
  for (size_t i = 2; i + 1 < in.size; i += 2) {
    const unsigned unit = big ? (in.data[i] << 8 | in.data[i + 1]) : (in.data[i + 1] << 8 | in.data[i]);
    text += unit < 128 ? char(unit) : '?';
  }
  return true;
}

struct ObjState {
  const Input* in = nullptr;
  const ReadOptions* options = nullptr;
  TriangleSoup soup;
  std::vector<uint32_t> polygon;
  size_t faces = 0;
  size_t short_faces = 0;
  int64_t largest_index = -1;  // validated once all vertices are known
  size_t largest_index_face = 0;
};

void on_vertex(void* user, double x, double y, double z, double) {
  auto& state = *static_cast<ObjState*>(user);
  state.soup.positions.insert(state.soup.positions.end(), {x, y, z});
}

void on_face(void* user, tinyobj::index_t* indices, int count) {
  auto& state = *static_cast<ObjState*>(user);
  const size_t face = ++state.faces;
  if (count < 3) {
    ++state.short_faces;
    return;
  }
  const int64_t known = int64_t(state.soup.vertex_count());
  state.polygon.clear();
  for (int k = 0; k < count; ++k) {
    const int64_t raw = indices[k].vertex_index;
    // Negative indices count back from the last vertex read so far.
    const int64_t index = raw > 0 ? raw - 1 : known + raw;
    if (raw == 0 || index < 0) {
      fail(ErrorKind::InvalidInput, *state.in,
           "face " + std::to_string(face) + " uses vertex index " + std::to_string(raw) +
               ", which does not exist (OBJ indices start at 1, negative ones count back from " +
               std::to_string(known) + ").");
    }
    if (index > state.largest_index) {
      state.largest_index = index;
      state.largest_index_face = face;
    }
    state.polygon.push_back(uint32_t(std::min<int64_t>(index, UINT32_MAX)));
  }
  if (state.soup.triangle_count() + state.polygon.size() - 2 > state.options->max_triangles) {
    fail(ErrorKind::TooLarge, *state.in,
         "the file has more than " + std::to_string(state.options->max_triangles) + " triangles.");
  }
  if (state.largest_index < known) {
    add_polygon(state.soup, state.polygon.data(), state.polygon.size());
  } else {
    // Refers ahead to a vertex not read yet: legal only if it comes later.
    // Fanned now, checked at the end (rare enough not to ear-clip).
    for (size_t i = 1; i + 1 < state.polygon.size(); ++i) {
      state.soup.indices.insert(state.soup.indices.end(), {state.polygon[0], state.polygon[i], state.polygon[i + 1]});
    }
  }
}

// tinyobjloader reads "nan" and "inf" as 0, which would turn a broken vertex
// into a plausible one. Re-read the coordinates of `v` lines that contain
// such words so they stay non-finite and repair can drop their triangles.
void restore_non_finite(const std::string_view text, std::vector<double>& positions) {
  size_t vertex = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    size_t i = pos;
    while (i < end && (text[i] == ' ' || text[i] == '\t')) ++i;
    if (i + 1 < end && text[i] == 'v' && (text[i + 1] == ' ' || text[i + 1] == '\t')) {
      const std::string line(text.substr(i + 2, end - i - 2));
      const char* p = line.c_str();
      for (int c = 0; c < 3 && 3 * vertex + c < positions.size(); ++c) {
        char* next = nullptr;
        const double value = std::strtod(p, &next);
        if (next == p) break;
        if (!std::isfinite(value)) positions[3 * vertex + c] = value;
        p = next;
      }
      ++vertex;
    }
    pos = end + 1;
  }
}

// The text tinyobjloader is given: without a UTF-8 byte-order mark (which
// hid the first keyword) and with `\` line continuations joined (backslash
// and line break become spaces, so every byte keeps its offset).
std::string_view prepare_text(std::string_view text, std::string& storage) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  if (text.find("\\\n") == std::string_view::npos && text.find("\\\r\n") == std::string_view::npos) return text;
  storage.assign(text);
  for (size_t i = 0; i + 1 < storage.size(); ++i) {
    if (storage[i] != '\\') continue;
    if (storage[i + 1] == '\n') {
      storage[i] = storage[i + 1] = ' ';
    } else if (storage[i + 1] == '\r' && i + 2 < storage.size() && storage[i + 2] == '\n') {
      storage[i] = storage[i + 1] = storage[i + 2] = ' ';
    }
  }
  return storage;
}

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// tinyobjloader accumulates a number's exponent in an int and overflows
// (undefined behaviour) on ten digits; no double needs more than four.
bool has_huge_exponent(std::string_view word) {
  // A plain loop: find_first_of("eE") calls memchr once per character.
  size_t e = 0;
  while (e < word.size() && (word[e] | 0x20) != 'e') ++e;
  if (e == word.size()) return false;
  size_t k = e + 1;
  if (k < word.size() && (word[k] == '+' || word[k] == '-')) ++k;
  while (k < word.size() && word[k] == '0') ++k;
  size_t digits = 0;
  for (; k < word.size() && word[k] >= '0' && word[k] <= '9'; ++k) ++digits;
  return digits > 9;
}

// tinyobjloader reads indices with atoi, which wraps ("4294967299" became
// 3, a 20-digit index anything), and takes a hexadecimal coordinate for 0.
// Both are refused here, on the text it is given; `line_of` turns a byte
// offset into the line number of the file.
template <typename LineOf>
void check_numbers(const Input& in, std::string_view text, const LineOf& line_of) {
  for (size_t pos = 0; pos < text.size();) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    size_t i = pos;
    while (i < end && is_blank(text[i])) ++i;
    const bool face = i + 1 < end && text[i] == 'f' && is_blank(text[i + 1]);
    const bool vertex = i + 1 < end && text[i] == 'v' && is_blank(text[i + 1]);
    // Normals and texture coordinates are parsed (and dropped) too.
    const bool attribute =
        i + 2 < end && text[i] == 'v' && (text[i + 1] == 'n' || text[i + 1] == 't') && is_blank(text[i + 2]);
    for (i += attribute ? 2 : 1; (face || vertex || attribute) && i < end;) {
      while (i < end && is_blank(text[i])) ++i;
      const size_t start = i;
      while (i < end && !is_blank(text[i])) ++i;
      const std::string_view word = text.substr(start, i - start);
      if (word.empty() || word[0] == '#') break;
      const size_t sign = word[0] == '-' || word[0] == '+' ? 1 : 0;
      if (vertex && word.size() > sign + 1 && word[sign] == '0' && (word[sign + 1] | 0x20) == 'x') {
        fail(ErrorKind::InvalidInput, in,
             "the vertex on line " + std::to_string(line_of(start)) + " has the hexadecimal number " + quote(word) +
                 ", which OBJ does not allow.");
      }
      if (!face && has_huge_exponent(word)) {
        fail(ErrorKind::InvalidInput, in,
             "line " + std::to_string(line_of(start)) + " has the number " + quote(word) +
                 ", whose exponent is out of range.");
      }
      if (!face) continue;
      const std::string_view index = word.substr(0, word.find('/'));
      uint64_t value = 0;
      size_t k = sign;
      for (; k < index.size() && index[k] >= '0' && index[k] <= '9' && value <= kMaxGltfInteger; ++k) {
        value = value * 10 + uint64_t(index[k] - '0');
      }
      // atoi would read "1e300" or "2.5" as a smaller index without a word.
      if (k == sign || (k < index.size() && value <= uint64_t(INT32_MAX))) {
        fail(ErrorKind::InvalidInput, in,
             "the face on line " + std::to_string(line_of(start)) + " has the vertex index " + quote(index) +
                 ", which is not a whole number.");
      }
      if (value > uint64_t(INT32_MAX)) {
        fail(ErrorKind::InvalidInput, in,
             "the face on line " + std::to_string(line_of(start)) + " uses vertex index " + quote(index) +
                 ", which is out of range (at most " + std::to_string(INT32_MAX) + ").");
      }
    }
    pos = end + 1;
  }
}

// "nan" or "inf" in any case anywhere in the text. Numbers and keywords
// rarely hold an 'a' or an 'i', so memchr finds the few places to look.
bool mentions_non_finite(std::string_view text) {
  if (text.size() < 3) return false;  // (an empty view may hold no pointer for memchr)
  auto lower = [&](size_t i) { return char(text[i] | 0x20); };
  for (const char key : {'a', 'A', 'i', 'I'}) {
    const bool inf = (key | 0x20) == 'i';
    for (const char* p = text.data();
         (p = static_cast<const char*>(std::memchr(p, key, size_t(text.data() + text.size() - p)))) != nullptr; ++p) {
      const size_t i = size_t(p - text.data()) - (inf ? 0 : 1);  // where the word would start
      if (!inf && p == text.data()) continue;
      if (i + 2 >= text.size()) break;
      if (inf ? lower(i + 1) == 'n' && lower(i + 2) == 'f' : lower(i) == 'n' && lower(i + 2) == 'n') return true;
    }
  }
  return false;
}

}  // namespace

TriangleSoup read_obj(const Input& in, const ReadOptions& options) {
  std::string decoded;
  const bool utf16 = decode_utf16(in, decoded);
  const std::string_view file =
      utf16 ? std::string_view(decoded) : std::string_view(reinterpret_cast<const char*>(in.data), in.size);
  std::string joined;
  const std::string_view text = prepare_text(file, joined);
  const size_t skipped = file.size() - text.size();  // the byte-order mark
  check_numbers(in, text, [&](size_t offset) {
    return 1 + size_t(std::count(file.begin(), file.begin() + ptrdiff_t(offset + skipped), '\n'));
  });

  ObjState state;
  state.in = &in;
  state.options = &options;
  tinyobj::callback_t callbacks;
  callbacks.vertex_cb = on_vertex;
  callbacks.index_cb = on_face;
  MemoryBuffer buffer(text.data(), text.size());
  std::istream stream(&buffer);
  std::string warning, error;
  if (!tinyobj::LoadObjWithCallback(stream, callbacks, &state, nullptr, &warning, &error)) {
    fail(ErrorKind::InvalidInput, in, "the OBJ text cannot be parsed (" + error + ").");
  }
  TriangleSoup& soup = state.soup;
  const size_t vertices = soup.vertex_count();
  if (state.largest_index >= int64_t(vertices)) {
    fail(ErrorKind::InvalidInput, in,
         "face " + std::to_string(state.largest_index_face) + " refers to vertex " +
             std::to_string(state.largest_index + 1) + " but the file has " + std::to_string(vertices) + " vertices.");
  }
  if (mentions_non_finite(text)) restore_non_finite(text, soup.positions);
  if (utf16) soup.notes.push_back("The file is UTF-16 text; it was read as ASCII.");
  if (state.short_faces > 0) {
    soup.notes.push_back(std::to_string(state.short_faces) + " faces with fewer than 3 vertices were skipped.");
  }
  finish_soup(soup, in);
  return std::move(soup);
}

}  // namespace crestline::io::detail
