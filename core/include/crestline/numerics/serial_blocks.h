#pragma once
// Long serial loops run as a sequence of calls, block by block.
//
// Why: a WebAssembly engine (V8's dynamic tiering) compiles a hot function's
// optimised code in the background and uses it from the function's next
// call on; a loop that runs in one call stays in the baseline code to its
// end, several times slower. A fresh page's first large file goes through
// such loops once (the glTF reader's conversions and copies: ≈ 0.1 s of the
// dragon's first read in V8's baseline tier, node 20). Called block by block,
// the later blocks run optimised. Natively a call per block of thousands of
// items costs nothing measurable.
#include <algorithm>
#include <cstddef>

namespace crestline {

/// Items per call of for_serial_blocks' body.
inline constexpr size_t kSerialBlock = 16384;

namespace detail {
/// One block: a function of its own per body type, never inlined into the
/// loop over the blocks (the body is inlined here).
template <typename Body>
[[gnu::noinline]] void run_serial_block(Body& body, size_t begin, size_t end) {
  body(begin, end);
}
}  // namespace detail

/// body(begin, end) over [0, count) in blocks of kSerialBlock items, in
/// order, on the calling thread.
template <typename Body>
void for_serial_blocks(size_t count, Body&& body) {
  for (size_t begin = 0; begin < count; begin += kSerialBlock)
    detail::run_serial_block(body, begin, std::min(count, begin + kSerialBlock));
}

}  // namespace crestline
