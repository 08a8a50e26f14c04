#!/usr/bin/env node
// The crestline command on the WASM build:
//   node wasm/cli.mjs INPUT -o OUT.{obj,json,svg} [options]
// Same readers (io::read_mesh_bytes through Session.loadFile), options, messages
// and writers as the native build/cli/crestline. Only Draco/meshopt glTF, which
// the C++ readers leave to the browser under Emscripten, is decoded by
// web/src/worker/compressed-gltf.js (three.js: meshopt works in node, Draco does not).
import { readFileSync, renameSync, writeFileSync } from 'node:fs';
import { basename, dirname, extname, join } from 'node:path';
import { decodeCompressedGltf } from '../web/src/worker/compressed-gltf.js';
import { loadCrestline } from './node.mjs';

// flag → [Session option key, description]; --help shows the defaults that
// Session.options() reports before a mesh is loaded.
const OPTIONS = {
  '--smoothing-steps': ['smoothingSteps', 'extremality smoothing steps (paper §5.1)'],
  '--smoothing-time-step': ['smoothingTimeStep', 'time step per smoothing step, in mean edge lengths squared'],
  '--presmooth-steps': ['presmoothSteps', 'surface pre-smoothing steps (mean-curvature flow); negative: automatic from the noise level'],
  '--presmooth-time-step': ['presmoothTimeStep', 'time step per pre-smoothing step, in mean edge lengths squared'],
  '--threshold': ['threshold', 'drop lines with strength ∫|κ|ds below this; negative: automatic'],
  '--fairing-bound': ['hausdorffBound', 'line fairing Hausdorff bound, in mean edge lengths; 0 disables'],
  '--fairing-iterations': ['fairingIterations', 'line fairing iterations (paper §5.2)'],
  '--boundary-rings': ['boundaryRings', 'vertex rings along the mesh boundary left untraced'],
};
// SVG flag → [writer option key, default, description]
const SVG_OPTIONS = {
  '--svg-width': ['width', 1000, 'SVG size in pixels of the longer side'],
  '--stroke-width': ['strokeWidth', 1.5, 'SVG line width in pixels'],
};

function usage(defaults) {
  const lines = ['usage: node wasm/cli.mjs INPUT -o OUTPUT.{obj,json,svg} [options]', ''];
  for (const [flag, [key, text]] of Object.entries(OPTIONS)) lines.push(`  ${flag} X`.padEnd(28) + `${text} (default ${defaults[key]})`);
  lines.push('  --weights FILE'.padEnd(28) + 'per-vertex smoothing strength, one number per line (0 freezes a vertex)');
  lines.push('  --view V'.padEnd(28) + 'SVG view: front, back, left, right, top, bottom (default front)');
  for (const [flag, [, def, text]] of Object.entries(SVG_OPTIONS)) lines.push(`  ${flag} X`.padEnd(28) + `${text} (default ${def})`);
  lines.push('  --silhouette'.padEnd(28) + "also draw the surface's outline in the SVG");
  lines.push('  --repair-report'.padEnd(28) + 'print every count of the mesh repair on stderr');
  lines.push('  --stats'.padEnd(28) + 'print the statistics as one JSON object on stdout');
  lines.push('  --quiet'.padEnd(28) + 'no progress on stderr');
  return lines.join('\n');
}

function parseArgs(argv) {
  const args = { options: {}, svg: { view: 'front' }, stats: false, quiet: false };
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    const [flag, inline] = arg.startsWith('--') && arg.includes('=') ? arg.split(/=(.*)/s) : [arg, undefined];
    const value = () => {
      const v = inline ?? argv[++i];
      if (v === undefined) throw new Error(`${flag} needs a value.`);
      return v;
    };
    if (flag === '-h' || flag === '--help') args.help = true;
    else if (flag === '-o' || flag === '--output') args.output = value();
    else if (flag === '--stats') args.stats = true;
    else if (flag === '--quiet' || flag === '-q') args.quiet = true;
    else if (flag === '--view') args.svg.view = value();
    else if (flag === '--silhouette') args.svg.silhouette = true;
    else if (flag === '--repair-report') args.repairReport = true;
    else if (flag === '--weights') args.weights = value();
    else if (OPTIONS[flag] || SVG_OPTIONS[flag]) {
      const number = Number(value());
      if (!Number.isFinite(number)) throw new Error(`${flag} needs a number.`);
      if (OPTIONS[flag]) args.options[OPTIONS[flag][0]] = number;
      else args.svg[SVG_OPTIONS[flag][0]] = number;
    } else if (flag.startsWith('-')) throw new Error(`unknown option ${flag} (see --help).`);
    else if (args.input === undefined) args.input = arg;
    else throw new Error(`unexpected argument "${arg}".`);
  }
  return args;
}

/** A .gltf's external files (buffers, images), read from beside it; the browser gets them dropped together. */
function gltfCompanions(path, bytes) {
  if (extname(path).toLowerCase() !== '.gltf') return [];
  let json;
  try {
    json = JSON.parse(new TextDecoder().decode(bytes));
  } catch {
    return []; // the reader reports the broken JSON
  }
  const uris = [...(json.buffers ?? []), ...(json.images ?? [])]
    .map((entry) => entry?.uri)
    .filter((uri) => typeof uri === 'string' && uri && !uri.startsWith('data:'));
  return [...new Set(uris)].flatMap((uri) => {
    try {
      return [{ name: basename(uri), bytes: readFileSync(join(dirname(path), decodeURIComponent(uri))) }];
    } catch {
      return []; // named as missing by the reader
    }
  });
}

/** "FILE: problem", like the native CLI: a message that already names the file is not prefixed twice. */
function named(file, message) {
  for (const name of [file, basename(file)]) {
    if (message.startsWith(`${name}: `)) return `${file}: ${message.slice(name.length + 2)}`;
  }
  return `${file}: ${message}`;
}

/** Throws a Session's {error} as one sentence naming `file`. */
function check(file, result) {
  if (result.error) throw new Error(named(file, result.error));
  return result;
}

// The C++ readers refuse compressed glTF under Emscripten (core/src/io/read_gltf.cpp).
const isCompressedGltf = (result) => result.kind === 'unsupported' && /is compressed with/.test(result.error);

/** Reads the input with the C++ readers; compressed glTF through three.js (web/src/worker/compressed-gltf.js). */
async function loadInput(session, path, bytes) {
  const companions = gltfCompanions(path, bytes);
  const loaded = session.loadFile(basename(path), bytes, companions, {});
  if (!isCompressedGltf(loaded)) return check(path, loaded);
  let soup;
  try {
    soup = await decodeCompressedGltf({ name: basename(path), bytes }, companions);
  } catch (error) {
    if (/DRACOLoader/.test(error.message)) throw new Error(named(path, 'is Draco-compressed, which only the browser app and the native CLI decode.'));
    throw new Error(named(path, `cannot be decoded (${error.message.replace(/^THREE\.\w+:\s*/, '').split('\n')[0].replace(/\.$/, '')}).`));
  }
  return check(path, session.load(soup.positions, soup.indices, {}));
}

/** The native CLI's --repair-report: its header line, then "  snake_case: count". */
function printRepairReport(input, report) {
  console.error(`crestline: ${input}: repair report`);
  for (const [key, count] of Object.entries(report)) console.error(`  ${key.replace(/[A-Z]/g, (c) => `_${c.toLowerCase()}`)}: ${count}`);
}

function readWeights(path, vertices) {
  let text;
  try {
    text = readFileSync(path, 'utf8');
  } catch (error) {
    throw new Error(`${path}: cannot be read (${error.code ?? error.message}).`);
  }
  const weights = Float64Array.from(text.split(/\s+/).filter(Boolean), Number);
  if (weights.some((w) => !(w >= 0))) throw new Error(`${path}: every weight must be a non-negative number.`);
  if (weights.length !== vertices) throw new Error(`${path}: has ${weights.length} weights but the repaired mesh has ${vertices} vertices.`);
  return weights;
}

async function defaultOptions() {
  const session = new (await loadCrestline()).Session();
  try {
    return session.options();
  } finally {
    session.delete();
  }
}

async function main(argv) {
  const args = parseArgs(argv);
  if (args.help) return void console.log(usage(await defaultOptions()));
  if (!args.input || !args.output) throw new Error(`an INPUT and -o OUTPUT are required.\n${usage(await defaultOptions())}`);
  const format = extname(args.output).slice(1).toLowerCase();
  if (!['obj', 'json', 'svg'].includes(format)) throw new Error(`${args.output}: unknown output format (use .obj, .json or .svg).`);
  let bytes;
  try {
    bytes = readFileSync(args.input);
  } catch (error) {
    throw new Error(`${args.input}: cannot be read (${error.code ?? error.message}).`);
  }
  const module = await loadCrestline();
  const session = new module.Session();
  try {
    const loaded = await loadInput(session, args.input, bytes);
    if (!args.quiet) for (const note of loaded.notes) console.error(`crestline: ${named(args.input, note)}`);
    if (args.repairReport) printRepairReport(args.input, loaded.report);
    if (args.weights) args.options.vertexWeights = readWeights(args.weights, loaded.vertices);
    const progress = args.quiet || !process.stderr.isTTY
      ? undefined
      : (stage, fraction) => (process.stderr.write(`\r${stage} ${Math.round(100 * fraction)}%   `), true);
    check(args.input, session.setOptions(args.options));
    check(args.input, session.run(progress));
    if (progress) process.stderr.write('\r'.padEnd(30) + '\r');
    write(args, session);
  } finally {
    session.delete();
  }
}

function write(args, session) {
  const format = extname(args.output).slice(1).toLowerCase();
  let text;
  if (format === 'obj') text = session.linesObj();
  else if (format === 'json') text = session.linesJson();
  else {
    const svg = session.linesSvg(args.svg);
    if (svg.error) throw new Error(`--view: ${svg.error}.`);
    text = svg;
  }
  // Written whole or not at all: no partial file on failure.
  const temporary = `${args.output}.partial`;
  writeFileSync(temporary, text);
  renameSync(temporary, args.output);
  if (args.stats) console.log(session.statsJson());
}

main(process.argv.slice(2)).catch((error) => {
  console.error(`crestline: ${error.message}`);
  process.exitCode = 1;
});
