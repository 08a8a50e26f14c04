// The WASM toolchain with the module's flags: build-wasm/wasm/slp-check.cjs
// (tests/wasm/slp_check.cpp, built by wasm/build.sh) transforms points in
// place, which LLVM 14's SLP vectorizer miscompiles for SIMD128 (24 of its
// 72 coordinates came out wrong); CMakeLists.txt turns SLP off for WASM.
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';
import { ROOT } from './helpers.mjs';

const CHECK = join(ROOT, 'build-wasm/wasm/slp-check.cjs');

test(
  'the WASM build computes points transformed in place exactly (no SLP miscompile)',
  { skip: existsSync(CHECK) ? false : `SKIPPED: ${CHECK} is not built (wasm/build.sh)` },
  async () => {
    const { code, stdout } = await new Promise((resolve) => {
      execFile(process.execPath, [CHECK], { timeout: 60_000 }, (error, out) => resolve({ code: error ? error.code : 0, stdout: out }));
    });
    assert.equal(stdout.trim(), '0 of 72 coordinates wrong');
    assert.equal(code, 0);
  },
);
