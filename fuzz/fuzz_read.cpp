// libFuzzer target: one mesh reader (CRESTLINE_FUZZ_FORMAT, set per target
// in fuzz/CMakeLists.txt) on arbitrary bytes; see check_read. The text
// formats (OBJ, glTF) also get structure-aware mutations (text_mutator.h)
// for one input in four.
#include <cstdio>
#include <cstdlib>

#include "fuzz_inputs.h"
#if CRESTLINE_FUZZ_TEXT
#include "text_mutator.h"

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t max_size, unsigned int seed) {
  if (seed % 4 == 0) return crestline::fuzz::mutate_text(data, size, max_size, seed / 4);
  return LLVMFuzzerMutate(data, size, max_size);
}
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string problem = crestline::fuzz::check_read(crestline::io::MeshFormat::CRESTLINE_FUZZ_FORMAT, data, size);
  if (!problem.empty()) {
    std::fprintf(stderr, "contract broken: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
