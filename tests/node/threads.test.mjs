// The threaded WASM build (crestline-mt) in node, its pthreads on
// worker_threads: it reports the threads it was given, and its lines are
// those of the plain single-threaded build, bit for bit (every parallel loop
// sums in a fixed order). wasm/build.sh builds both unless
// CRESTLINE_WASM_THREADS=0, which skips this file visibly.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { test } from 'node:test';
import { loadCrestline, loadCrestlineThreads } from '../../wasm/node.mjs';
import { selectLines } from '../../web/src/client/client.js';
import { sampleMesh } from '../../web/src/app/sample.js';
import { Engine } from '../../web/src/worker/engine.js';
import { ROOT, sineHeightField } from './helpers.mjs';

const built = existsSync(`${ROOT}wasm/dist/crestline-mt.wasm`);
const skip = process.env.CRESTLINE_WASM_THREADS === '0' && !built ? 'SKIPPED: CRESTLINE_WASM_THREADS=0, no crestline-mt' : false;

/** Lines of `mesh` with `options` on `module`, as plain arrays. */
function linesOf(module, mesh, options) {
  const engine = new Engine(module);
  try {
    engine.load(mesh);
    const result = engine.run(options, undefined, true);
    const lines = selectLines(result.lines, result.kept);
    return {
      stats: { ridges: result.stats.ridges, valleys: result.stats.valleys, threshold: result.stats.threshold },
      offsets: Array.from(lines.offsets),
      types: Array.from(lines.types),
      strengths: Array.from(lines.strengths),
      points: Array.from(lines.points),
    };
  } finally {
    engine.dispose();
  }
}

test("crestline-mt on 2 threads gives the plain build's lines", { skip }, async () => {
  assert.ok(built, 'wasm/dist/crestline-mt.wasm is missing: run wasm/build.sh');
  const [plain, threaded] = await Promise.all([loadCrestline(), loadCrestlineThreads(2)]);
  assert.equal(plain.threads(), 1, 'the plain build has one thread');
  assert.equal(threaded.threads(), 2, 'crestline-mt uses the threads it was given');
  assert.ok(threaded.HEAPU8.buffer instanceof SharedArrayBuffer, 'its memory is shared');
  // 2·120² triangles: every per-element loop is long enough to be split (2·2048 elements).
  try {
    const cases = [
      [sineHeightField({ n: 120, amplitude: 0.15 }), { threshold: 0 }],
      [sineHeightField({ n: 120, amplitude: 0.15 }), { threshold: 0, smoothingSteps: 8, presmoothSteps: 2 }],
      [sampleMesh(), {}],
    ];
    for (const [mesh, options] of cases) {
      const one = linesOf(plain, mesh, options);
      const two = linesOf(threaded, mesh, options);
      assert.ok(one.types.length >= 7, `${mesh.name ?? 'sine'} has lines (${one.types.length})`);
      assert.deepEqual(two, one, `identical lines on ${mesh.name ?? 'the sine field'} with ${JSON.stringify(options)}`);
    }
  } finally {
    // Its pthreads are worker_threads, which would keep node running.
    threaded.PThread.terminateAllThreads();
  }
});

test('crestline-mt reports errors and cancels as the plain build does', { skip }, async () => {
  // Emscripten 3.1.6's -fwasm-exceptions with -pthread matched no typed catch
  // clause: every error escaped as a WebAssembly.Exception (hence -fexceptions there).
  const [plain, threaded] = await Promise.all([loadCrestline(), loadCrestlineThreads(2)]);
  try {
    const outcomes = [];
    for (const module of [plain, threaded]) {
      const engine = new Engine(module);
      const garbage = await engine.open([{ name: 'x.glb', bytes: new TextEncoder().encode('this is not a mesh') }]).then(
        () => 'read',
        (error) => ({ error: error.message, kind: error.kind }),
      );
      engine.load(sineHeightField({ n: 120 }));
      const cancelled = engine.run({ threshold: 0 }, (stage) => stage !== 'smoothing');
      const again = engine.run({ threshold: 0 });
      engine.dispose();
      outcomes.push({ garbage, cancelled, lines: again.stats.ridges + again.stats.valleys });
    }
    assert.match(outcomes[0].garbage.error, /^x\.glb: /, 'the plain build names the file');
    assert.deepEqual(outcomes[0].cancelled, { cancelled: true });
    assert.deepEqual(outcomes[1], outcomes[0], 'the same sentence, the same cancel, the same lines after it');
  } finally {
    threaded.PThread.terminateAllThreads();
  }
});
