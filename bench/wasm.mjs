#!/usr/bin/env node
// The WASM column of the benchmark: runs the WASM build in node on the very
// soups crestline_bench exported (--export), and prints native vs WASM.
//   node bench/wasm.mjs --native NATIVE.json [--dist DIR] [--runs N] [--json OUT.json]
// "load" here is Session.load: copying the soup in, repair and topology.
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { median, table } from './table.mjs';

const STAGES = ['presmooth', 'curvature', 'extremality', 'regularity', 'smoothing', 'tracing', 'singular', 'polylines', 'fairing', 'filter'];

function parseArgs(argv) {
  const args = { dist: fileURLToPath(new URL('../wasm/dist/', import.meta.url)), runs: 3 };
  for (let i = 0; i < argv.length; i++) {
    const value = () => argv[++i];
    if (argv[i] === '--native') args.native = value();
    else if (argv[i] === '--dist') args.dist = value();
    else if (argv[i] === '--runs') args.runs = Math.max(1, Number(value()));
    else if (argv[i] === '--json') args.json = value();
    else throw new Error(`unknown argument ${argv[i]}`);
  }
  if (!args.native) throw new Error('usage: node bench/wasm.mjs --native NATIVE.json [--dist DIR] [--runs N] [--json OUT]');
  return args;
}

// A fresh module per mesh, so that its heap size is that mesh's peak (a WASM
// heap only grows). Same loading as wasm/node.mjs, from any dist folder.
async function loadModule(dist) {
  const url = pathToFileURL(resolve(dist) + '/');
  globalThis.__dirname ??= fileURLToPath(url);
  globalThis.require ??= createRequire(import.meta.url);
  const { default: createCrestline } = await import(new URL('crestline.js', url).href);
  return createCrestline({ wasmBinary: readFileSync(new URL('crestline.wasm', url)) });
}

function readSoup(path) {
  const bytes = readFileSync(path);
  if (bytes.toString('latin1', 0, 7) !== 'CRSOUP1') throw new Error(`${path}: not a benchmark soup.`);
  const vertices = Number(bytes.readBigUInt64LE(8));
  const triangles = Number(bytes.readBigUInt64LE(16));
  const buffer = bytes.buffer.slice(bytes.byteOffset + 24, bytes.byteOffset + bytes.length);
  return {
    positions: new Float64Array(buffer, 0, 3 * vertices),
    indices: new Uint32Array(buffer, 24 * vertices, 3 * triangles),
  };
}

function check(result) {
  if (result && result.error) throw new Error(result.error);
  return result;
}

async function measure(mesh, options, runs, dist) {
  const module = await loadModule(dist);
  const soup = readSoup(mesh.soup);
  const samples = { load: [], total: [], rethreshold: [], resmooth: [], ...Object.fromEntries(STAGES.map((s) => [s, []])) };
  let stats;
  for (let run = 0; run < runs; run++) {
    const session = new module.Session();
    let t = performance.now();
    check(session.load(soup.positions, soup.indices, {}));
    const load = (performance.now() - t) / 1000;
    check(session.setOptions(options));
    stats = check(session.run(null)).stats;
    samples.load.push(load);
    let total = load;
    for (const s of STAGES) (samples[s].push(stats.seconds[s]), (total += stats.seconds[s]));
    samples.total.push(total);
    check(session.setOptions({ threshold: 1.5 * stats.threshold }));
    t = performance.now();
    check(session.run(null));
    samples.rethreshold.push((performance.now() - t) / 1000);
    check(session.setOptions({ smoothingTimeStep: 1.5 * options.smoothingTimeStep }));
    t = performance.now();
    check(session.run(null));
    samples.resmooth.push((performance.now() - t) / 1000);
    session.delete();
  }
  const seconds = Object.fromEntries(Object.entries(samples).map(([k, v]) => [k, median(v)]));
  return {
    name: mesh.name,
    triangles: stats.triangles,
    runs,
    seconds,
    heap_bytes: module.HEAPU8.length,
    lines: { ridges: stats.ridges, valleys: stats.valleys, ridge_length: stats.ridgeLength, valley_length: stats.valleyLength },
  };
}

const args = parseArgs(process.argv.slice(2));
const native = JSON.parse(readFileSync(args.native, 'utf8'));
const options = {
  smoothingSteps: native.options.smoothing_steps,
  smoothingTimeStep: native.options.smoothing_time_step,
  hausdorffBound: native.options.fairing_bound,
  fairingIterations: native.options.fairing_iterations,
};
const results = [];
for (const mesh of native.meshes) {
  if (mesh.error || !mesh.soup) continue;
  process.stderr.write(`wasm: ${mesh.name} …\n`);
  try {
    results.push(await measure(mesh, options, args.runs, args.dist));
  } catch (error) {
    results.push({ name: mesh.name, error: String(error.message ?? error) });
  }
}

const f = (s) => (Number.isFinite(s) ? s.toFixed(3) : '-');
const rows = [['mesh', 'triangles', 'load+repair', ...STAGES, 'total', 're-thr', 're-smooth', 'heap MB', 'native total', 'WASM/native']];
for (const r of results) {
  const n = native.meshes.find((m) => m.name === r.name);
  if (r.error) {
    rows.push([r.name, n.triangles, `error: ${r.error}`, ...Array(rows[0].length - 3).fill('')]);
    continue;
  }
  const s = r.seconds;
  rows.push([
    r.name,
    r.triangles,
    f(s.load),
    ...STAGES.map((k) => f(s[k])),
    f(s.total),
    f(s.rethreshold),
    f(s.resmooth),
    (r.heap_bytes / 1048576).toFixed(0),
    f(n.seconds.total),
    (s.total / n.seconds.total).toFixed(2),
  ]);
}
console.log(`WASM in node ${process.version}, seconds, median of ${args.runs} run${args.runs === 1 ? '' : 's'}; total = load+repair + stages`);
console.log(table(rows));
if (args.json)
  writeFileSync(args.json, JSON.stringify({ runner: 'wasm-node', node: process.version, runs: args.runs, options, meshes: results }, null, 2) + '\n');
