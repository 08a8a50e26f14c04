// Wavefront OBJ, parsed in one pass over the bytes (a large file's parts on
// every thread when they hold only vertices and plain triangles): `v` lines
// give the vertices (x y z; a w or colours after them are checked and
// ignored), `f` lines the polygons with their 1-based or negative
// (relative) vertex indices (texture and normal indices after a '/' are
// ignored), ear-clipped by add_polygon; every other line (vn, vt, l, p, o,
// g, s, usemtl, mtllib, comments) is skipped, so a missing .mtl is
// irrelevant. Lines end at LF, CRLF or a lone CR; a `\` before the line
// break joins two lines.
//
// Coordinates are read with fast_float, correctly rounded (the nearest
// double to the decimal text, as strtod gives). Owner decision (issue 14):
// coordinates may differ in the last bit from the tinyobjloader parse this
// replaces, which was not correctly rounded and cost 6.15 G of the
// 7.5 G instructions of reading a 58 MB OBJ (2.1 G in pow); fast_float is
// header-only, so it also builds with Emscripten 3.1.6, whose libc++ has no
// floating-point std::from_chars.
#include <fast_float/fast_float.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../mesh/parts.h"
#include "crestline/numerics/parallel.h"
#include "readers.h"

namespace crestline::io::detail {
namespace {

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

// The text to parse: without a UTF-8 byte-order mark and with `\` line
// continuations joined (backslash and line break become spaces, so every
// byte keeps its offset and messages keep the file's line numbers). Copied
// only when the file has a continuation.
std::string_view prepare_text(std::string_view text, std::string& storage) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  bool joins = false;  // one scan for a backslash, rare elsewhere
  for (size_t i = text.find('\\'); i != std::string_view::npos && !joins; i = text.find('\\', i + 1))
    joins = text.substr(i + 1, 1) == "\n" || text.substr(i + 1, 2) == "\r\n";
  if (!joins) return text;
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

// The largest vertex index (2^31 - 1), checked in 64 bits so nothing wraps.
constexpr uint64_t kMaxIndex = INT32_MAX;

bool is_blank(char c) { return c == ' ' || c == '\t'; }
bool is_line_end(char c) { return c == '\n' || c == '\r'; }

// A number whose exponent has more than nine significant digits. No double
// needs more than four; such a number is refused with a message rather than
// read as 0 or infinity.
bool has_huge_exponent(std::string_view word) {
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

// As many vertices as a glTF accessor may have, and 32-bit indices.
size_t max_vertices(const ReadOptions& options) {
  const uint64_t triangles = std::min<uint64_t>(options.max_triangles, UINT32_MAX);
  return size_t(std::min<uint64_t>(3 * triangles + 3, UINT32_MAX));
}

class ObjParser {
 public:
  // The whole text, or (`stop` given) the lines in [first, last) alone, last
  // being a line's start, until *stop is set: see read_in_parts.
  ObjParser(const Input& in, const ReadOptions& options, std::string_view file, std::string_view text)
      : ObjParser(in, options, file, text, text.data(), text.data() + text.size(), nullptr) {}
  ObjParser(const Input& in, const ReadOptions& options, std::string_view file, std::string_view text,
            const char* first, const char* last, std::atomic<bool>* stop)
      : in_(in),
        options_(options),
        file_(file),
        begin_(text.data()),
        first_(first),
        end_(last),
        part_(stop != nullptr),
        stop_(stop) {
    skipped_ = file.size() - text.size();  // the byte-order mark
  }

  TriangleSoup run() {
    for (const char* p = first_; p < end_;) {
      if (part_ && stop_->load(std::memory_order_relaxed)) break;
      while (p < end_ && is_blank(*p)) ++p;
      if (p == end_) break;
      const char c = *p;
      const char next = p + 1 < end_ ? p[1] : '\0';
      if (c == 'v' && is_blank(next)) {
        p = vertex(p + 1);
      } else if (c == 'v' && (next == 'n' || next == 't') && p + 2 < end_ && is_blank(p[2])) {
        p = attribute(p + 2);
      } else if (c == 'f' && is_blank(next)) {
        p = face(p + 1);
      }
      while (p < end_ && !is_line_end(*p)) ++p;  // the rest of the line, or a line we skip
      if (p < end_ && *p == '\r') ++p;
      if (p < end_ && *p == '\n') ++p;
    }
    const size_t vertices = soup_.vertex_count();
    if (!part_ && largest_index_ >= int64_t(vertices)) {
      fail(ErrorKind::InvalidInput, in_,
           "the face on line " + std::to_string(line_of(largest_index_at_)) + " refers to vertex " +
               std::to_string(largest_index_ + 1) + " but the file has " + std::to_string(vertices) + " vertices.");
    }
    return std::move(soup_);
  }
  size_t short_faces() const { return short_faces_; }
  // The most a part's face index exceeds the vertices read before it in
  // the part: the vertices before the part must make up for it.
  int64_t index_excess() const { return index_excess_; }

 private:
  // The file's line number (1-based) of a position in the text: line breaks
  // are LF, CRLF or a lone CR, counted in the file as it is (continuations
  // too). Only computed for messages.
  size_t line_of(const char* at) const {
    const size_t offset = size_t(at - begin_) + skipped_;
    size_t line = 1;
    for (size_t i = 0; i < offset && i < file_.size(); ++i) {
      line += file_[i] == '\n' || (file_[i] == '\r' && (i + 1 == file_.size() || file_[i + 1] != '\n'));
    }
    return line;
  }

  const char* word_end(const char* p) const {
    while (p < end_ && !is_blank(*p) && !is_line_end(*p)) ++p;
    return p;
  }

  // The number starting at p (a word, at least one character); returns the
  // end of the word. A word that does not start with a number reads as 0,
  // and one with a number and more (1.5abc) as its number, as tinyobjloader
  // and strtod read them; "nan" and "inf" (any case) stay non-finite so that
  // repair drops their triangles. Hexadecimal numbers (in `v` lines) and
  // exponents of ten or more digits are refused.
  const char* number(const char* p, double& value, bool vertex) {
    const char* start = p;
    if (*start == '+' && start + 1 < end_ && start[1] != '-' && start[1] != '+') ++start;  // from_chars takes no '+'
    const fast_float::from_chars_result parsed = fast_float::from_chars(start, end_, value);
    const char* stop = parsed.ec == std::errc() ? parsed.ptr : start;
    if (stop == start) value = 0;
    // The common case: a whole word read, finite and non-zero (a huge
    // exponent gives 0 or infinity unless the mantissa has about as many
    // digits as the exponent's value, hence the length bound).
    const bool whole_word = stop == end_ || is_blank(*stop) || is_line_end(*stop);
    if (whole_word && value != 0 && std::isfinite(value) && stop - p < 400) return stop;
    const char* end = word_end(stop);
    const std::string_view word(p, size_t(end - p));
    const size_t sign = word[0] == '-' || word[0] == '+' ? 1 : 0;
    if (vertex && word.size() > sign + 1 && word[sign] == '0' && (word[sign + 1] | 0x20) == 'x') {
      fail(ErrorKind::InvalidInput, in_,
           "the vertex on line " + std::to_string(line_of(p)) + " has the hexadecimal number " + quote(word) +
               ", which OBJ does not allow.");
    }
    if (has_huge_exponent(word)) {
      fail(ErrorKind::InvalidInput, in_,
           "line " + std::to_string(line_of(p)) + " has the number " + quote(word) +
               ", whose exponent is out of range.");
    }
    return end;
  }

  // The numbers of a `v`, `vn` or `vt` line, up to its end or a comment,
  // each checked; the first three go to xyz where it is given.
  const char* numbers(const char* p, bool vertex, double* xyz) {
    for (int k = 0;; ++k) {
      while (p < end_ && is_blank(*p)) ++p;
      if (p == end_ || is_line_end(*p) || *p == '#') return p;
      double value = 0;
      p = number(p, value, vertex);
      if (xyz && k < 3) xyz[k] = value;
    }
  }

  // `v x y z [w | r g b]`: missing coordinates are 0.
  const char* vertex(const char* p) {
    if (!part_ && soup_.vertex_count() >= max_vertices_) {
      fail(ErrorKind::TooLarge, in_, "the file has more than " + std::to_string(max_vertices_) + " vertices.");
    }
    double xyz[3] = {0, 0, 0};
    p = numbers(p, true, xyz);
    soup_.positions.insert(soup_.positions.end(), xyz, xyz + 3);
    return p;
  }

  // `vn` and `vt`: not used, but their numbers are checked as in `v`.
  const char* attribute(const char* p) { return numbers(p, false, nullptr); }

  // The common face, read with fewer tests per byte: three positive indices
  // of vertices already read, without sign or leading zero, each optionally
  // followed by /t/n, then the line's end or a comment. Returns the end as
  // face() does, or nullptr for anything else (nothing changed then), which
  // face() reads, checks and reports in full: at most 10 digits are read, so
  // the value cannot overflow, and a value within the vertices read so far
  // is a valid index up to kMaxIndex. A part takes any index up to
  // kMaxIndex and keeps its excess, and leaves the triangle count to
  // read_in_parts.
  const char* plain_triangle(const char* p) {
    if (!part_ && soup_.triangle_count() >= options_.max_triangles) return nullptr;
    const char* const at = p;
    const uint64_t known = part_ ? kMaxIndex : std::min<uint64_t>(soup_.vertex_count(), kMaxIndex);
    uint32_t index[3];
    for (uint32_t& i : index) {
      if (p == end_ || !is_blank(*p)) return nullptr;
      while (p < end_ && is_blank(*p)) ++p;
      if (p == end_ || unsigned(*p - '1') > 8) return nullptr;
      const char* const last = p + std::min<ptrdiff_t>(10, end_ - p);
      uint64_t value = 0;
      for (unsigned digit; p < last && (digit = unsigned(*p) - '0') < 10; ++p) value = value * 10 + digit;
      if (value > known) return nullptr;
      if (p < end_ && *p == '/') p = word_end(p);  // texture and normal indices
      i = uint32_t(value - 1);
    }
    // A comment only after a blank: "3#" is a malformed index.
    if (p < end_ && !is_blank(*p) && !is_line_end(*p)) return nullptr;
    while (p < end_ && is_blank(*p)) ++p;
    if (p < end_ && !is_line_end(*p) && *p != '#') return nullptr;
    const uint32_t largest = std::max({index[0], index[1], index[2]});
    if (int64_t(largest) > largest_index_) largest_index_ = largest, largest_index_at_ = at;
    index_excess_ = std::max(index_excess_, int64_t(largest) + 1 - int64_t(soup_.vertex_count()));
    soup_.indices.insert(soup_.indices.end(), index, index + 3);
    return p;
  }

  // `f i[/t[/n]] ...`: every vertex index a whole number up to kMaxIndex,
  // 1-based or counting back from the last vertex read so far.
  const char* face(const char* p) {
    if (const char* end = plain_triangle(p)) return end;
    if (part_) {  // the other parts stop too: the text is read again in one pass
      stop_->store(true, std::memory_order_relaxed);
      return p;
    }
    corners_.clear();
    const char* at = p;
    for (;;) {
      while (p < end_ && is_blank(*p)) ++p;
      if (p == end_ || is_line_end(*p) || *p == '#') break;
      const char* start = p;
      const bool negative = *p == '-';
      if (*p == '-' || *p == '+') ++p;
      const char* digits = p;
      uint64_t value = 0;
      for (unsigned digit; p < end_ && (digit = unsigned(*p) - '0') < 10 && value <= kMaxIndex; ++p) {
        value = value * 10 + digit;
      }
      const char* stop = p;
      while (p < end_ && !is_blank(*p) && !is_line_end(*p) && *p != '/') ++p;
      const std::string_view index(start, size_t(p - start));
      if (stop == digits || (stop < p && value <= kMaxIndex)) {
        fail(ErrorKind::InvalidInput, in_,
             "the face on line " + std::to_string(line_of(start)) + " has the vertex index " + quote(index) +
                 ", which is not a whole number.");
      }
      if (value > kMaxIndex) {
        fail(ErrorKind::InvalidInput, in_,
             "the face on line " + std::to_string(line_of(start)) + " uses vertex index " + quote(index) +
                 ", which is out of range (at most " + std::to_string(kMaxIndex) + ").");
      }
      p = word_end(p);  // texture and normal indices
      corners_.push_back(negative ? -int64_t(value) : int64_t(value));
      if (corners_.size() > 2 && soup_.triangle_count() + corners_.size() - 2 > options_.max_triangles) {
        fail(ErrorKind::TooLarge, in_,
             "the file has more than " + std::to_string(options_.max_triangles) + " triangles.");
      }
    }
    if (corners_.empty()) return p;
    if (corners_.size() < 3) {
      ++short_faces_;
      return p;
    }
    const int64_t known = int64_t(soup_.vertex_count());
    polygon_.clear();
    for (const int64_t raw : corners_) {
      const int64_t index = raw > 0 ? raw - 1 : known + raw;
      if (raw == 0 || index < 0) {
        fail(ErrorKind::InvalidInput, in_,
             "the face on line " + std::to_string(line_of(at)) + " uses vertex index " + std::to_string(raw) +
                 ", which does not exist (OBJ indices start at 1, negative ones count back from " +
                 std::to_string(known) + ").");
      }
      if (index > largest_index_) {
        largest_index_ = index;
        largest_index_at_ = at;
      }
      polygon_.push_back(uint32_t(index));
    }
    if (largest_index_ < known) {
      add_polygon(soup_, polygon_.data(), polygon_.size());
    } else {
      // Refers ahead to a vertex not read yet: legal only if it comes later.
      // Fanned now, checked at the end (rare enough not to ear-clip).
      for (size_t i = 1; i + 1 < polygon_.size(); ++i) {
        soup_.indices.insert(soup_.indices.end(), {polygon_[0], polygon_[i], polygon_[i + 1]});
      }
    }
    return p;
  }

  const Input& in_;
  const ReadOptions& options_;
  std::string_view file_;  // as read (or decoded), for line numbers
  const char* begin_;      // the text's
  const char* first_;      // where reading starts
  const char* end_;
  bool part_ = false;
  std::atomic<bool>* stop_ = nullptr;  // set by the first part that stops
  int64_t index_excess_ = INT64_MIN;
  size_t skipped_ = 0;
  const size_t max_vertices_ = max_vertices(options_);
  TriangleSoup soup_;
  std::vector<int64_t> corners_;
  std::vector<uint32_t> polygon_;
  size_t short_faces_ = 0;
  int64_t largest_index_ = -1;  // validated once all vertices are known
  const char* largest_index_at_ = nullptr;
};

// A large file's lines read in parts on every thread, each part as the
// whole text would read them (the numbers are most of the time: 1,048 M
// instructions for the 1.1M mesh's 58 MB at af4309a). A part takes `v`, `vn`
// and `vt` lines and the plain triangles, the common case, and stops at any
// other face (relative indices, polygons, short faces); its indices are the
// file's whatever comes before it, and whether each was a vertex read before
// the face is checked once the parts' vertex counts are known. Nothing when
// a part stopped or threw (a message must name the file's first problem),
// or a limit is passed: the whole text is then read in one pass, so the
// soup and every message are the same for any thread count.
std::optional<TriangleSoup> read_in_parts(const Input& in, const ReadOptions& options, std::string_view file,
                                          std::string_view text) {
  constexpr size_t kPartBytes = size_t{1} << 18;
  const size_t threads = std::min<size_t>({text.size() / kPartBytes, size_t(max_threads()), 8});
  if (threads < 2) return std::nullopt;
  // Four parts a thread, dealt round: vertex lines and faces cost
  // differently per byte (the 1.1M mesh's first half is its vertices), so
  // each thread takes some of both.
  const size_t parts = 4 * threads;
  // Each part starts after a line feed: always the start of a line (a CR
  // alone or before it ends the line before).
  std::vector<const char*> start(parts + 1, text.data() + text.size());
  start[0] = text.data();
  for (size_t p = 1; p < parts; ++p) {
    const char* at = std::max(text.data() + text.size() * p / parts, start[p - 1]);
    const void* feed = std::memchr(at, '\n', size_t(text.data() + text.size() - at));
    start[p] = feed ? static_cast<const char*>(feed) + 1 : text.data() + text.size();
  }
  std::vector<TriangleSoup> soups(parts);
  std::vector<int64_t> excess(parts, 0);
  std::atomic<bool> stop{false};
  crestline::detail::for_each_part(threads, threads, [&](size_t thread, size_t, size_t) {
    for (size_t p = thread; p < parts; p += threads) {
      try {
        ObjParser parser(in, options, file, text, start[p], start[p + 1], &stop);
        soups[p] = parser.run();
        excess[p] = parser.index_excess();
      } catch (...) {  // read again in one pass, which reports the file's first problem
        stop.store(true, std::memory_order_relaxed);
      }
    }
  });
  if (stop.load()) return std::nullopt;
  // The vertices before each part: every index within them and the limits.
  uint64_t vertices = 0, triangles = 0;
  for (size_t p = 0; p < parts; ++p) {
    if (excess[p] > int64_t(vertices)) return std::nullopt;
    vertices += soups[p].vertex_count(), triangles += soups[p].triangle_count();
  }
  if (vertices > max_vertices(options) || triangles > options.max_triangles) return std::nullopt;
  // The parts' positions and indices joined in part order, each array on a
  // thread of its own: the copies write fresh pages (26 MB at 1.1M
  // triangles), whose faults cost more than the copying. Allocated on this
  // thread (a block allocated on a kept thread would sit in that thread's
  // malloc arena).
  TriangleSoup soup;
  soup.positions.reserve(3 * vertices);
  soup.indices.reserve(3 * triangles);
  const auto join = [&](auto member) {
    auto& joined = soup.*member;
    for (TriangleSoup& part : soups) {
      auto& piece = part.*member;
      joined.insert(joined.end(), piece.begin(), piece.end());
      piece = std::decay_t<decltype(piece)>();
    }
  };
  run_side_by_side([&] { join(&TriangleSoup::positions); }, [&] { join(&TriangleSoup::indices); });
  soup.notes = std::move(soups[0].notes);
  return soup;
}

}  // namespace

TriangleSoup read_obj(const Input& in, const ReadOptions& options) {
  std::string decoded;
  const bool utf16 = decode_utf16(in, decoded);
  const std::string_view file =
      utf16 ? std::string_view(decoded) : std::string_view(reinterpret_cast<const char*>(in.data), in.size);
  std::string joined;
  const std::string_view text = prepare_text(file, joined);
  std::optional<TriangleSoup> parts = read_in_parts(in, options, file, text);
  size_t short_faces = 0;
  if (!parts) {
    ObjParser parser(in, options, file, text);
    parts = parser.run();
    short_faces = parser.short_faces();
  }
  TriangleSoup soup = std::move(*parts);
  if (utf16) soup.notes.push_back("The file is UTF-16 text; it was read as ASCII.");
  if (short_faces > 0) {
    soup.notes.push_back(std::to_string(short_faces) + " faces with fewer than 3 vertices were skipped.");
  }
  finish_soup(soup, in);
  return soup;
}

}  // namespace crestline::io::detail
