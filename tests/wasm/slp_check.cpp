// A pattern LLVM 14's SLP vectorizer miscompiles for WASM SIMD128 (Emscripten
// 3.1.6, -O2 -msimd128): points transformed in place by a 4×4 matrix came
// out with a wrong coordinate (a rotated glTF node's positions, 2e97d32).
// Built with the module's flags (CMakeLists.txt turns SLP off for WASM);
// tests/node/toolchain.test.mjs runs it and compares with the true values.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <vector>

__attribute__((noinline)) void transform_in_place(std::vector<double>& positions, const std::vector<double>& source,
                                                  const Eigen::Matrix4d& world) {
  const size_t first = positions.size();
  positions.insert(positions.end(), source.begin(), source.end());
  for (size_t v = first; v < positions.size(); v += 3) {
    double* p = &positions[v];
    const Eigen::Vector4d q = world * Eigen::Vector4d(p[0], p[1], p[2], 1.0);
    p[0] = q[0], p[1] = q[1], p[2] = q[2];
  }
}

int main() {
  // A quarter turn about x: (x, y, z) -> (x, -z, y).
  const double m[16] = {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1};
  const Eigen::Matrix4d world = Eigen::Map<const Eigen::Matrix4d>(m);
  std::vector<double> source;
  for (int i = 0; i < 72; ++i) source.push_back(i);
  std::vector<double> positions;
  positions.reserve(source.size());
  transform_in_place(positions, source, world);
  int wrong = 0;
  for (size_t v = 0; v < source.size(); v += 3) {
    const double expected[3] = {source[v], -source[v + 2], source[v + 1]};
    for (int k = 0; k < 3; ++k) wrong += positions[v + k] != expected[k];
  }
  std::printf("%d of %zu coordinates wrong\n", wrong, source.size());
  return wrong == 0 ? 0 : 1;
}
