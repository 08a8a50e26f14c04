// libFuzzer target: repair_mesh + Pipeline::run on small meshes decoded from
// the bytes (degenerate, non-manifold, coincident, huge and tiny
// coordinates); see decode_pipeline_input and check_pipeline.
#include <cstdio>
#include <cstdlib>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string problem = crestline::fuzz::check_pipeline(data, size);
  if (!problem.empty()) {
    std::fprintf(stderr, "contract broken: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
