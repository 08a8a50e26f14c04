#pragma once
// Building small files in memory for the reader tests.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace crestline::testing {

inline std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

/// Appends `value` in little- or big-endian byte order.
template <typename T>
void put(std::vector<uint8_t>& out, T value, bool big_endian = false) {
  uint8_t b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  out.insert(out.end(), b, b + sizeof(T));
}

}  // namespace crestline::testing
