#!/usr/bin/env node
// The smoothing brush's main-thread cost per pointer move (issue 17: ≤ 8 ms
// on the 871k-triangle dragon): the page's WeightBrush (web/src/three) on
// the repaired surface the worker sends, driven by rays at random surface
// points as a stroke would be: pick (BVH), geodesic radius (Dijkstra),
// weights, and the touched vertices' colours. The GPU upload of those
// colour ranges is not in it (node has no WebGL). Not a test: timings.
//   node bench/brush.mjs [MESH] [--moves N] [--radius R]   (R: fraction of the model's size, the panel's default 0.08)
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';
import { Vector3 } from 'three';
import { loadCrestline } from '../wasm/node.mjs';
import { WeightBrush } from '../web/src/three/brush.js';
import { SurfaceLayer } from '../web/src/three/surface-layer.js';
import { MESHES } from '../tests/node/helpers.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => (args.includes(name) ? Number(args[args.indexOf(name) + 1]) : fallback);
const file = args.find((a, i) => !a.startsWith('--') && !args[i - 1]?.startsWith('--')) ?? `${MESHES}large/dragon.glb`;
const moves = option('--moves', 200);
const radius = option('--radius', 0.08);

const module = await loadCrestline();
const session = new module.Session();
const loaded = session.loadFile(basename(file), new Uint8Array(readFileSync(file)), [], {});
if (loaded.error) throw new Error(loaded.error);
const { positions, indices } = session.surface();
session.delete();

// The page's surface: centred, float32 (Viewer.setSurface).
const surface = new SurfaceLayer();
const centre = [0, 1, 2].map((k) => {
  let [lo, hi] = [Infinity, -Infinity];
  for (let i = k; i < positions.length; i += 3) [lo, hi] = [Math.min(lo, positions[i]), Math.max(hi, positions[i])];
  return (lo + hi) / 2;
});
surface.setMesh(
  Float32Array.from(positions, (x, i) => x - centre[i % 3]),
  Uint32Array.from(indices),
);
const viewer = { renderer: { domElement: new EventTarget() }, controls: {}, surface, render() {} };
const brush = new WeightBrush(viewer, { onStroke() {} });
brush.reset(positions.length / 3);
brush.radius = radius;
brush.value = 0;
surface.setColors(
  brush.weights.map((w) => w - 1),
  1,
);

let started = performance.now();
brush.surfaceIndex();
const buildMs = performance.now() - started;

// Rays from outside the model at random triangles' centroids, along their normals.
let seed = 17;
const random = () => (seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32;
const p = surface.mesh.geometry.getAttribute('position').array;
const R = surface.mesh.geometry.boundingSphere.radius;
const times = [];
const cpu = []; // CPU time of the process: without the waits of a busy machine
let touched = 0;
for (let m = 0; m < moves; m++) {
  const t = Math.floor(random() * (indices.length / 3));
  const [a, b, c] = [0, 1, 2].map((k) => new Vector3().fromArray(p, 3 * indices[3 * t + k]));
  const centroid = a.clone().add(b).add(c).divideScalar(3);
  const normal = b.clone().sub(a).cross(c.clone().sub(a)).normalize();
  const origin = centroid.clone().addScaledVector(normal, 0.01 * R);
  started = performance.now();
  const before = process.cpuUsage();
  touched += brush.paintRay(origin, normal.clone().negate());
  const used = process.cpuUsage(before);
  times.push(performance.now() - started);
  cpu.push((used.user + used.system) / 1000);
}
const quantiles = (list) => {
  const sorted = [...list].sort((x, y) => x - y);
  const at = (q) => sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))].toFixed(2);
  return `median ${at(0.5)} ms, 90th percentile ${at(0.9)} ms, max ${at(1)} ms`;
};
console.log(`${basename(file)}: ${indices.length / 3} triangles; brush radius ${radius} of the model's size`);
console.log(`index (BVH + adjacency) built in ${buildMs.toFixed(0)} ms, once per surface`);
console.log(`${moves} moves, wall clock: ${quantiles(times)}; ${Math.round(touched / moves)} vertices touched per move`);
console.log(`${moves} moves, CPU time: ${quantiles(cpu)} (uptime's load average tells how busy the machine was)`);
