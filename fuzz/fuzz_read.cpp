// libFuzzer target: one mesh reader (CRESTLINE_FUZZ_FORMAT, set per target
// in fuzz/CMakeLists.txt) on arbitrary bytes; see check_read.
#include <cstdio>
#include <cstdlib>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string problem = crestline::fuzz::check_read(crestline::io::MeshFormat::CRESTLINE_FUZZ_FORMAT, data, size);
  if (!problem.empty()) {
    std::fprintf(stderr, "contract broken: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
