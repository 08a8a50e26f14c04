#pragma once
// A structure-aware mutator for the text formats (glTF JSON, OBJ), used by
// the fuzz targets' LLVMFuzzerCustomMutator next to libFuzzer's own byte
// mutations (and by tests/unit/hardening/mutator_test.cpp). Each mutation
// makes one kind of input that byte flips almost never reach, the kinds
// issue 18 found by hand:
//   - a number replaced by an extreme one (2^32 + 3, 2^63, 20 digits, -7,
//     1e300, a hexadecimal float): integers that wrapped when narrowed;
//   - brackets nested thousands deep after a ':' or '[': the JSON depth
//     that overflowed tinygltf's recursion;
//   - an OBJ face repeated into one polygon of thousands of corners, or a
//     new round polygon appended: the quadratic ear clipping;
//   - a byte-order mark or a `\` line continuation inserted.
// fuzz/text.dict lists the same tokens for libFuzzer's -dict.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

namespace crestline::fuzz {

/// A small deterministic generator (the mutation must be reproducible from
/// libFuzzer's seed).
class Random {
 public:
  explicit Random(uint32_t seed) : state_(seed * 2654435761u + 1) {}
  uint32_t next() {
    state_ ^= state_ << 13, state_ ^= state_ >> 17, state_ ^= state_ << 5;
    return state_;
  }
  size_t below(size_t n) { return n ? next() % n : 0; }

 private:
  uint32_t state_;
};

inline const char* const kExtremeNumbers[] = {
    "4294967299",
    "4294967296",
    "2147483648",
    "12345678901234567890",
    "9223372036854775808",
    "18446744073709551616",
    "-7",
    "-4294967299",
    "1e300",
    "-1e308",
    "0x1p3",
    "1e-320",
};

namespace detail {

inline bool is_number_start(char c) { return (c >= '0' && c <= '9') || c == '-'; }

// Replaces the number at a random digit with an extreme one.
inline void replace_number(std::string& text, Random& random) {
  size_t at = random.below(text.size());
  while (at < text.size() && !is_number_start(text[at])) ++at;
  if (at == text.size()) {
    at = text.find_first_of("0123456789");
    if (at == std::string::npos) return;
  }
  while (at > 0 && (is_number_start(text[at - 1]) || text[at - 1] == '.')) --at;
  size_t end = at;
  while (end < text.size() &&
         (is_number_start(text[end]) || text[end] == '.' || text[end] == 'e' || text[end] == 'E' || text[end] == '+'))
    ++end;
  const char* number = kExtremeNumbers[random.below(sizeof kExtremeNumbers / sizeof kExtremeNumbers[0])];
  text.replace(at, end - at, number);
}

// Nests brackets `depth` deep as a JSON value after a ':' or '['.
inline void nest(std::string& text, Random& random, size_t room) {
  const size_t depth = std::min<size_t>(room / 2, 1 + random.below(30000));
  if (depth == 0) return;
  size_t at = text.find_first_of(":[", random.below(text.size()));
  if (at == std::string::npos) at = text.find_first_of(":[");
  if (at == std::string::npos) return;
  const std::string value = std::string(depth, '[') + std::string(depth, ']') + (text[at] == '[' ? "," : "");
  if (text[at] == ':') {
    // Replaces the value up to the next ',' or '}' (a whole nested value
    // would need a parser; a broken one is still a useful input).
    const size_t end = text.find_first_of(",}", at + 1);
    text.replace(at + 1, (end == std::string::npos ? text.size() : end) - at - 1, value);
  } else {
    text.insert(at + 1, value);
  }
}

// Repeats the corners of a face until the line is `room` bytes longer.
inline void grow_face(std::string& text, Random& random, size_t room) {
  size_t at = text.find("\nf ", random.below(text.size()));
  if (at == std::string::npos) at = text.find("\nf ");
  if (at == std::string::npos) return;
  const size_t end = std::min(text.find('\n', at + 1), text.size());
  const std::string corners = text.substr(at + 2, end - at - 2);
  if (corners.size() < 2) return;
  std::string grown;
  const size_t target = std::min<size_t>(room, 1 + random.below(1 << 20));
  while (grown.size() + corners.size() < target) grown += corners;
  text.insert(end, grown);
}

// Appends a round polygon: `n` vertices on a circle and one face of all.
inline void add_round_polygon(std::string& text, Random& random, size_t room) {
  const size_t n = std::min<size_t>(room / 48, 3 + random.below(100000));
  if (n < 3) return;
  std::string polygon = "\n";
  char line[64];
  for (size_t i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * double(i) / double(n), r = i % 2 ? 0.9 : 1.0;
    std::snprintf(line, sizeof line, "v %.6f %.6f 0\n", r * std::cos(a), r * std::sin(a));
    polygon += line;
  }
  polygon += "f";
  for (size_t i = n; i >= 1; --i) polygon += " -" + std::to_string(i);  // relative: works after any vertices
  text += polygon + "\n";
}

}  // namespace detail

/// Applies one structure-aware mutation to `data` (`size` bytes, room for
/// `max_size`) and returns the new size, as LLVMFuzzerCustomMutator does.
inline size_t mutate_text(uint8_t* data, size_t size, size_t max_size, uint32_t seed) {
  Random random(seed);
  std::string text(reinterpret_cast<const char*>(data), size);
  const size_t room = max_size > size ? max_size - size : 0;
  switch (random.below(6)) {
    case 0:
    case 1:
      detail::replace_number(text, random);
      break;
    case 2:
      detail::nest(text, random, room);
      break;
    case 3:
      detail::grow_face(text, random, room);
      break;
    case 4:
      detail::add_round_polygon(text, random, room);
      break;
    default: {
      const size_t at = text.find('\n', random.below(text.size() + 1));
      if (random.below(2) || at == std::string::npos)
        text.insert(0, "\xEF\xBB\xBF");
      else
        text.insert(at, " \\");
      break;
    }
  }
  const size_t out = std::min(text.size(), max_size);
  std::memcpy(data, text.data(), out);
  return out;
}

}  // namespace crestline::fuzz
