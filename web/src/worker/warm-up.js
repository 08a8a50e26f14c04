// @ts-check
// A first large file in a fresh worker runs in V8's baseline WebAssembly
// code: V8 compiles a hot function's optimised code in the background but
// uses it only from the function's next call, so a long read or pipeline
// stage stays in the baseline tier throughout, while the compiles share the
// cores with it (≈ 0.3 s of the dragon's first read; ≈ 0.5 s of CPU of its
// first pipeline run in node 20). Reading a small generated GLB through the
// same Session.loadFile and running the pipeline on it, in a few rounds,
// makes the reader's and the stages' functions hot before a user drops a
// file. V8 optimises a function only once it has run enough (Chromium 156:
// one round of a plain torus optimised 40 functions before the dragon's
// first drop and left ≈ 140 to compile during it, 0.72 s of CPU on the
// cores the pipeline uses; these rounds leave ≈ 60), so the torus has
// creases and crowded rings (the crease cut and the solver's coarse level
// run too) and the last round reads a larger one (the reader's loops).
import { glb } from '../../../wasm/gltf-decompress.mjs';

/**
 * A closed torus of `rings` × `segments` quads (2 · rings · segments
 * triangles) as a GLB: float32 POSITION and uint32 indices in one buffer,
 * the layout of large scans (large/dragon.glb). `creased`: four crease
 * rings along the tube and the rings crowded on one side.
 * @param {number} rings @param {number} segments @param {{creased?: boolean}} [shape]
 * @returns {Uint8Array}
 */
export function torusGlb(rings, segments, { creased = false } = {}) {
  const vertexCount = rings * segments;
  const positions = new Float32Array(3 * vertexCount);
  for (let i = 0; i < rings; i++) {
    const even = (2 * Math.PI * i) / rings;
    // Creased: the rings crowd together on one side (4.7 times closer there than opposite) …
    const u = creased ? even + 0.65 * Math.sin(even) : even;
    for (let j = 0; j < segments; j++) {
      const v = (2 * Math.PI * j) / segments;
      // … and the tube has four sharp grooves (where |sin 2v| has its kinks).
      const tube = creased ? 0.4 * (1 + 0.35 * Math.abs(Math.sin(2 * v))) : 0.4;
      const r = 1 + tube * Math.cos(v);
      positions.set([r * Math.cos(u), tube * Math.sin(v), r * Math.sin(u)], 3 * (i * segments + j));
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
  const extent = creased ? 1.54 : 1.4; // the tube's radius 0.4, up to 0.54 creased
  const min = [-extent, 1 - extent, -extent];
  const max = [extent, extent - 1, extent];
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
/** Rounds of the warm-up (warmUpEngine each), each an idle task of the worker's (handler.js): the creased torus read and run, then a larger one read. */
export const WARM_UP_ROUNDS = 6;
/** The last round's torus, read only: 384 × 256 quads, 196,608 triangles (the glTF reader's loops run too few elements on the small one to be optimised); 0.14 s in node, the first time. */
export const WARM_UP_READ_RINGS = 384;
export const WARM_UP_READ_SEGMENTS = 256;

/**
 * Round `round` of the warm-up: reads the creased torus through the same
 * Session.loadFile (and repair) a dropped file takes and runs the pipeline
 * on it at the default options, or in the last round reads the larger
 * torus only; in a Session of its own that is deleted at once: no session,
 * mesh or option of a user is touched. Returns the triangles read.
 * @param {import('./engine.js').CrestlineModule} module @param {number} [round]
 */
export function warmUpEngine(module, round = 0) {
  const readOnly = round === WARM_UP_ROUNDS - 1;
  const session = new module.Session();
  try {
    const torus = readOnly ? torusGlb(WARM_UP_READ_RINGS, WARM_UP_READ_SEGMENTS) : torusGlb(WARM_UP_RINGS, WARM_UP_SEGMENTS, { creased: true });
    const loaded = session.loadFile('warm-up.glb', torus, [], {});
    if (loaded.error) throw new Error(`the warm-up GLB could not be read (${loaded.error})`);
    if (readOnly) return loaded.triangles;
    const ran = session.run(() => true);
    if (ran.error) throw new Error(`the warm-up's pipeline failed (${ran.error})`);
    return loaded.triangles;
  } finally {
    session.delete();
  }
}
