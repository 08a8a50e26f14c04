// node wasm/cli.mjs against the native build/cli/crestline on real meshes:
// same OBJ contract, same line counts, the same coordinates, the same bytes. Skips visibly without ../shared/meshes or the native CLI.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, test } from 'node:test';
import {
  MESHES, NATIVE_CLI, ROOT, haveMeshes, haveNativeCli, maxNearestDistance, parseLinesObj,
} from './helpers.mjs';

// Natively Eigen is built scalar, as in WASM (core/CMakeLists.txt), and
// extremality smoothing runs the same single-threaded solve, so both CLIs do
// the same arithmetic: counts, coordinates and bytes agree. fandisk's flat
// patches (no principal directions) and spot's flat zero crossings are where
// last-bit differences showed before (15 vs 14 ridges, 6e-4 of the diagonal).
const MESH_FILES = [
  'classic/mannequin.obj',
  'smooth/torus.obj',
  'cad/rocker-arm.obj',
  'cad/fandisk.obj',
  'classic/dino.obj',
  'classic/spot.obj',
  'gltf/Duck/Duck.gltf', // multi-file glTF: .bin found beside the .gltf
];
const dir = mkdtempSync(join(tmpdir(), 'crestline-cli-'));
after(() => rmSync(dir, { recursive: true, force: true }));

function wasmCli(...args) {
  return execFileSync(process.execPath, [join(ROOT, 'wasm/cli.mjs'), ...args], { encoding: 'utf8' });
}

const flat = (lines, vertices) => lines.flatMap((line) => line.flatMap((i) => vertices[i]));

test('cli.mjs --help, and a missing file is one sentence with exit code 1', () => {
  assert.match(wasmCli('--help'), /--smoothing-steps/);
  assert.throws(() => execFileSync(process.execPath, [join(ROOT, 'wasm/cli.mjs'), join(dir, 'missing.obj'), '-o', join(dir, 'x.obj')], { stdio: 'pipe' }),
    (error) => error.status === 1 && /missing\.obj: cannot be read/.test(error.stderr));
});

for (const file of MESH_FILES) {
  const why = !haveMeshes ? `SKIPPED: ${MESHES} is absent` : !haveNativeCli ? `SKIPPED: ${NATIVE_CLI} is not built` : false;
  test(`${file}: WASM CLI output matches the native CLI`, { skip: why }, () => {
    const input = join(MESHES, file);
    const name = file.replace(/\W/g, '_');
    const wasmOut = join(dir, `${name}.wasm.obj`);
    const nativeOut = join(dir, `${name}.native.obj`);
    wasmCli(input, '-o', wasmOut, '--quiet');
    // The native CLI's own defaults: both sides run without options.
    execFileSync(NATIVE_CLI, [input, '-o', nativeOut], { stdio: ['ignore', 'ignore', 'pipe'] });
    const a = parseLinesObj(readFileSync(wasmOut, 'utf8'));
    const b = parseLinesObj(readFileSync(nativeOut, 'utf8'));
    assert.equal(a.ridges.length, b.ridges.length, `${file}: ridge count`);
    assert.equal(a.valleys.length, b.valleys.length, `${file}: valley count`);
    assert.equal(a.vertices.length, b.vertices.length, `${file}: line vertex count`);
    for (const group of ['ridges', 'valleys']) {
      const d = Math.max(maxNearestDistance(flat(a[group], a.vertices), flat(b[group], b.vertices)),
        maxNearestDistance(flat(b[group], b.vertices), flat(a[group], a.vertices)));
      assert.equal(d, 0, `${file}: ${group} differ by up to ${d}`);
    }
    assert.ok(readFileSync(wasmOut).equals(readFileSync(nativeOut)), `${file}: the files differ`);
  });
}
