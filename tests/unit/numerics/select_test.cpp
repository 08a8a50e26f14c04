#include "../../../core/src/numerics/select.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace crestline;

namespace {

// nth_element's value at `rank`, on a copy.
template <typename T>
T reference(std::vector<T> values, size_t rank) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

}  // namespace

TEST_CASE("value_at_rank is nth_element's value, whatever the sample", "[numerics][select]") {
  // Above 2^17 values the sample's window serves unless it misses. Random
  // values (the window holds the rank); sorted ones and a sawtooth whose
  // period is the sample's stride (every sampled value the smallest: the
  // window misses); few distinct values (a window of one value holding a
  // quarter); +∞ tails as the crease measure's boundary entries; small
  // counts (nth_element alone).
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0, 1);
  const size_t n = 1670000, stride = n >> 14;
  std::vector<std::vector<float>> cases(5, std::vector<float>(n));
  for (size_t i = 0; i < n; ++i) {
    cases[0][i] = unit(random);
    cases[1][i] = static_cast<float>(i);
    cases[2][i] = static_cast<float>(i % stride);
    cases[3][i] = static_cast<float>(random() % 4);
    cases[4][i] = i % 5 == 0 ? std::numeric_limits<float>::infinity() : unit(random) * unit(random);
  }
  cases.push_back(std::vector<float>(cases[0].begin(), cases[0].begin() + 1000));
  for (size_t c = 0; c < cases.size(); ++c) {
    const size_t count = cases[c].size();
    for (size_t rank : {size_t{0}, count / 3, count * 2 / 5, count / 2, count - 1}) {
      INFO("case " << c << ", rank " << rank);
      std::vector<float> values = cases[c];
      CHECK(detail::value_at_rank(values.data(), count, rank) == reference(cases[c], rank));
    }
  }
  // Where the window serves, the values are only read.
  std::vector<float> values = cases[0];
  detail::value_at_rank(values.data(), n, n / 2);
  CHECK(values == cases[0]);
}

TEST_CASE("value_at_rank of doubles is nth_element's value", "[numerics][select]") {
  std::mt19937 random(3);
  std::lognormal_distribution<double> length(0, 0.3);
  std::vector<double> values(300000);
  for (double& v : values) v = length(random);
  for (size_t rank : {size_t{1}, values.size() / 2, values.size() - 2}) {
    std::vector<double> copy = values;
    CHECK(detail::value_at_rank(copy.data(), copy.size(), rank) == reference(values, rank));
  }
}

TEST_CASE("value_at_rank has the same bits on any number of threads", "[numerics][select][threads]") {
  // Signed zeros at the median: nth_element may return either, so only the
  // copies' order decides which, and the blocks' copies join in the values'
  // order whatever thread made them. 3 % zeros keep the window inside its
  // eighth (no fallback to nth_element over all values).
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<double> values(1000000);
  for (double& v : values) v = random() % 100 < 3 ? (random() % 2 ? 0.0 : -0.0) : unit(random);
  const int threads_before = max_threads();
  std::vector<double> medians;
  for (int threads : {1, 2, 3, 7}) {
    set_max_threads(threads);
    std::vector<double> copy = values;
    medians.push_back(detail::value_at_rank(copy.data(), copy.size(), copy.size() / 2));
    CHECK(copy == values);  // the window served
  }
  set_max_threads(threads_before);
  CHECK(medians[0] == 0.0);
  for (double m : medians) CHECK(std::signbit(m) == std::signbit(medians[0]));
}
