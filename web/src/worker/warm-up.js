// @ts-check
// A first large file in a fresh worker runs in V8's baseline WebAssembly
// code: V8 compiles a hot function's optimised code in the background but
// uses it only from the function's next call, so a long read or pipeline
// stage stays in the baseline tier throughout, while the compiles share the
// cores with it (≈ 0.3 s of the dragon's first read; ≈ 0.5 s of CPU of its
// first pipeline run in node 20). Reading a small generated GLB once,
// through the same Session.loadFile, and running the pipeline on it makes
// the reader's and the stages' functions hot before a user drops a file.
import { glb } from '../../../wasm/gltf-decompress.mjs';

/**
 * A closed torus of `rings` × `segments` quads (2 · rings · segments
 * triangles) as a GLB: float32 POSITION and uint32 indices in one buffer,
 * the layout of large scans (large/dragon.glb).
 * @param {number} rings @param {number} segments
 * @returns {Uint8Array}
 */
export function torusGlb(rings, segments) {
  const vertexCount = rings * segments;
  const positions = new Float32Array(3 * vertexCount);
  for (let i = 0; i < rings; i++) {
    const u = (2 * Math.PI * i) / rings;
    for (let j = 0; j < segments; j++) {
      const v = (2 * Math.PI * j) / segments;
      const r = 1 + 0.4 * Math.cos(v);
      positions.set([r * Math.cos(u), 0.4 * Math.sin(v), r * Math.sin(u)], 3 * (i * segments + j));
    }
  }
  const indices = new Uint32Array(6 * vertexCount);
  const at = (/** @type {number} */ i, /** @type {number} */ j) => (i % rings) * segments + (j % segments);
  for (let i = 0; i < rings; i++) {
    for (let j = 0; j < segments; j++) {
      const [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
      indices.set([a, c, b, a, d, c], 6 * (i * segments + j));
    }
  }
  const min = [-1.4, -0.4, -1.4];
  const max = [1.4, 0.4, 1.4];
  const json = {
    asset: { version: '2.0', generator: 'crestline warm-up' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1, mode: 4 }] }],
    buffers: [{ byteLength: positions.byteLength + indices.byteLength }],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: positions.byteLength, target: 34962 },
      { buffer: 0, byteOffset: positions.byteLength, byteLength: indices.byteLength, target: 34963 },
    ],
    accessors: [
      { bufferView: 0, componentType: 5126, count: vertexCount, type: 'VEC3', min, max },
      { bufferView: 1, componentType: 5125, count: indices.length, type: 'SCALAR' },
    ],
  };
  const binary = new Uint8Array(positions.byteLength + indices.byteLength); // a multiple of 4
  binary.set(new Uint8Array(positions.buffer));
  binary.set(new Uint8Array(indices.buffer), positions.byteLength);
  return glb(json, binary);
}

/** The warm-up mesh: 96 × 64 quads, 12,288 triangles (≈ 340 kB); reading and repairing them costs the worker ≈ 15-20 ms of CPU, the pipeline on them ≈ 0.1-0.2 s. */
export const WARM_UP_RINGS = 96;
export const WARM_UP_SEGMENTS = 64;

/**
 * Reads the warm-up GLB through the same Session.loadFile (and repair) a
 * dropped file takes, and runs the pipeline on it at the default options,
 * in a Session of its own that is deleted at once: no session, mesh or
 * option of a user is touched. Returns the triangles read.
 * @param {import('./engine.js').CrestlineModule} module
 */
export function warmUpEngine(module) {
  const session = new module.Session();
  try {
    const loaded = session.loadFile('warm-up.glb', torusGlb(WARM_UP_RINGS, WARM_UP_SEGMENTS), [], {});
    if (loaded.error) throw new Error(`the warm-up GLB could not be read (${loaded.error})`);
    const ran = session.run(() => true);
    if (ran.error) throw new Error(`the warm-up's pipeline failed (${ran.error})`);
    return loaded.triangles;
  } finally {
    session.delete();
  }
}
