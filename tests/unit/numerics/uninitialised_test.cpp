// UninitialisedVector (numerics/uninitialised.h): resize() leaves new
// elements of a trivial type as the memory held them (no zero-fill, which is
// what it is for), while every construction with a value still happens.
#include "crestline/numerics/uninitialised.h"

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

using crestline::filled_on_every_thread;
using crestline::max_threads;
using crestline::set_max_threads;
using crestline::UninitialisedAllocator;
using crestline::UninitialisedVector;

TEST_CASE("UninitialisedVector: resize does not zero-fill, values are constructed", "[numerics]") {
  // The allocator's one-argument construct is what resize() calls: on memory
  // holding a pattern it must leave the pattern (std::allocator writes 0).
  UninitialisedAllocator<uint64_t> allocator;
  alignas(uint64_t) unsigned char storage[sizeof(uint64_t)];
  std::memset(storage, 0xAB, sizeof storage);
  std::allocator_traits<UninitialisedAllocator<uint64_t>>::construct(allocator, reinterpret_cast<uint64_t*>(storage));
  CHECK(storage[0] == 0xAB);
  CHECK(storage[sizeof storage - 1] == 0xAB);

  // With values: as std::vector.
  UninitialisedVector<uint32_t> v(3, 7u);
  v.push_back(9);
  v.insert(v.end(), {1u, 2u});
  CHECK(v == UninitialisedVector<uint32_t>{7, 7, 7, 9, 1, 2});
  v.resize(8);
  v[6] = 5, v[7] = 6;
  v.resize(7);
  CHECK(v.back() == 5);
  // A class type is still default-constructed.
  UninitialisedVector<std::string> words(2);
  CHECK(words[0].empty());
  words.emplace_back("x");
  CHECK(words.size() == 3);
  CHECK(words[2] == "x");
}

TEST_CASE("filled_on_every_thread writes every element, on 1 to 3 threads", "[numerics][threads]") {
  const int threads_before = max_threads();
  for (int threads : {1, 2, 3}) {
    INFO("threads " << threads);
    set_max_threads(threads);
    const std::array<double, 6> value = {1.5, -2, 0, 3, 4, 5};
    const UninitialisedVector<std::array<double, 6>> filled = filled_on_every_thread(100003, value);
    CHECK(filled.size() == 100003);
    CHECK(std::count(filled.begin(), filled.end(), value) == 100003);
    CHECK(filled_on_every_thread(0, 7).empty());
  }
  set_max_threads(threads_before);
}
