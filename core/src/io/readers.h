#pragma once
// Private to the readers: one parse function per format and the helpers they
// share (error messages, header-claim checks, files; polygons are
// triangulated by add_polygon, triangulate_polygon.h).
#include <fast_float/fast_float.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "triangulate_polygon.h"

namespace crestline::io::detail {

/// The bytes of one file plus what is needed to find its companions.
struct Input {
  std::string name;  // basename, used in every message
  const uint8_t* data = nullptr;
  size_t size = 0;
  /// In-memory companions (read_mesh_bytes); looked up by URI, then basename.
  const std::vector<NamedBuffer>* companions = nullptr;
  /// Directory of the file on disk ("" for in-memory input; companions are
  /// then only taken from `companions`).
  std::string directory;
};

/// Limits every reader applies before it allocates or recurses (README,
/// "Limits"); the triangle limit is ReadOptions::max_triangles.
/// Brackets nested deeper than this in glTF JSON (real files nest about 8
/// deep; tinygltf converts the JSON recursively, so 20,000 levels overflowed
/// the stack).
constexpr int kMaxJsonDepth = 64;
/// Bytes read from one external glTF buffer file, besides its declared
/// byteLength; also the largest integer a glTF index, count or size may have.
constexpr uint64_t kMaxGltfInteger = 2147483647;  // 2^31 - 1
/// Text taken from a file into a message (a URI, a number as written).
constexpr size_t kMaxQuoted = 60;

/// `text` in single quotes, cut to kMaxQuoted characters with "...".
std::string quote(std::string_view text);

/// Throws Error(kind, "<name>: <problem>"); `problem` is a sentence fragment
/// ending with a full stop.
[[noreturn]] void fail(ErrorKind kind, const Input& in, const std::string& problem);

/// Refuses a header claim of `count` items before anything is allocated for
/// it: TooLarge beyond `options.max_triangles`, InvalidInput when the file
/// is too short to hold `count` items of at least `min_bytes_each` bytes.
void check_claim(const Input& in, const ReadOptions& options, uint64_t count, uint64_t min_bytes_each,
                 size_t bytes_left, const char* what);

/// The checks every reader ends with: at least one triangle (InvalidInput
/// "contains no triangles" otherwise), every index in range, and not every
/// referenced vertex non-finite. Non-finite vertices are otherwise passed
/// through with a note; repair_mesh drops their triangles.
void finish_soup(TriangleSoup& soup, const Input& in);

/// A number read from a file, for messages: integers exactly, anything else
/// (huge, fractional, NaN) as %g would, never through an integer cast.
inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

/// Reads at most `max_bytes` of a regular file (not a folder, device or
/// pipe: /dev/zero would never end); throws Error naming `display_name`:
/// Io when it cannot be opened or is not a regular file, TooLarge when it
/// does not fit in memory.
std::vector<uint8_t> read_file(const std::string& path, const std::string& display_name,
                               uint64_t max_bytes = UINT64_MAX);

/// Finds a companion file (glTF buffer) by URI, at most `max_bytes` of it:
/// first in in.companions, then on disk inside the folder of the file and
/// nowhere else (absolute paths, `..` and links leading out are refused
/// with InvalidInput). Returns false when absent.
bool find_companion(const Input& in, const std::string& uri, uint64_t max_bytes, std::vector<uint8_t>& out);

/// The last path component ("a/b/c.gltf" -> "c.gltf").
std::string basename_of(const std::string& path);

/// Words of a text format, line by line (OFF, ASCII PLY and STL). With
/// `comments`, '#' starts a comment that runs to the end of the line.
class TextScanner {
 public:
  TextScanner(const uint8_t* data, size_t size, bool comments)
      : p_(reinterpret_cast<const char*>(data)), end_(p_ + size), comments_(comments) {}

  /// Moves to the next line that has a word; false at the end of the text.
  bool next_line() {
    while (p_ < end_) {
      line_ = p_;
      const char* newline = static_cast<const char*>(std::memchr(p_, '\n', size_t(end_ - p_)));
      line_end_ = newline ? newline : end_;
      p_ = newline ? newline + 1 : end_;
      ++line_number_;
      if (comments_) {
        const char* hash = static_cast<const char*>(std::memchr(line_, '#', size_t(line_end_ - line_)));
        if (hash) line_end_ = hash;
      }
      const char* probe = line_;
      skip_space(probe);
      if (probe < line_end_) return true;
    }
    return false;
  }
  /// The next word of the current line; false when the line has no more.
  bool word(std::string_view& out) {
    skip_space(line_);
    if (line_ >= line_end_) return false;
    const char* start = line_;
    while (line_ < line_end_ && !is_space(*line_)) ++line_;
    out = std::string_view(start, size_t(line_ - start));
    return true;
  }
  /// The next word as a number (strtod syntax, so "nan" and "inf" too).
  /// Plain decimals by fast_float, correctly rounded as strtod is, the same
  /// double: Emscripten's strtod takes ≈ 1 µs a number (25× fast_float), a
  /// second per million in the page. The rest (a '+', hexadecimal, zero,
  /// non-finite, malformed) by strtod itself.
  bool number(double& out) {
    std::string_view w;
    if (!word(w) || w.size() >= 63) return false;
    if (w[0] != '+') {
      const fast_float::from_chars_result parsed = fast_float::from_chars(w.data(), w.data() + w.size(), out);
      if (parsed.ec == std::errc() && parsed.ptr == w.data() + w.size() && std::isfinite(out) && out != 0) return true;
    }
    char buffer[64];
    std::memcpy(buffer, w.data(), w.size());
    buffer[w.size()] = '\0';
    char* stop = nullptr;
    out = std::strtod(buffer, &stop);
    return stop == buffer + w.size();
  }
  /// The next word as an integer (a number with no fraction).
  bool integer(int64_t& out) {
    double value = 0;
    if (!number(value) || !(std::fabs(value) < 9e18) || value != std::floor(value)) return false;
    out = int64_t(value);
    return true;
  }
  size_t line_number() const { return line_number_; }
  size_t bytes_left() const { return size_t(end_ - p_); }
  /// Byte offset just past the current line (where binary PLY data starts).
  const char* after_line() const { return p_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  void skip_space(const char*& q) const {
    while (q < line_end_ && is_space(*q)) ++q;
  }
  const char* p_;
  const char* end_;
  const char* line_ = nullptr;
  const char* line_end_ = nullptr;
  size_t line_number_ = 0;
  bool comments_;
};

TriangleSoup read_obj(const Input& in, const ReadOptions& options);
TriangleSoup read_gltf(const Input& in, const ReadOptions& options);  // .gltf and .glb
TriangleSoup read_ply(const Input& in, const ReadOptions& options);
TriangleSoup read_stl(const Input& in, const ReadOptions& options);
TriangleSoup read_off(const Input& in, const ReadOptions& options);

/// True when the first 4 KB hold no control characters other than white space.
bool looks_like_text(const uint8_t* data, size_t size);

/// True when `size` bytes are a binary STL: 84-byte header and 50 bytes per
/// triangle exactly (the only reliable test: many binary STL headers start
/// with "solid" too).
bool is_binary_stl_size(size_t size, const uint8_t* data);

}  // namespace crestline::io::detail
