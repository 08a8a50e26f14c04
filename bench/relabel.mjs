// Relabelling check: do the lines depend on how a file numbers its vertices and triangles? For each mesh, the CLI
// writes its welded surface (--with-mesh); the same surface is written again with its vertices and triangles in a
// random order and each triangle's corners rotated (orientation kept); both are run unfaired (--fairing-bound 0: the
// points are the traced zero crossings and the crease vertices) and compared: line counts per kind, and how far each
// point lies from the nearest point of the same kind in the other output, in mean edge lengths.
//
//   node bench/relabel.mjs [--cli build/cli/crestline] [--seed 1] [--threads 1] [MESH ...]
//
// Without meshes: every mesh of ../shared/meshes/manifest.tsv. A diagnostic, not a test: on 2026-12-07 (16a882a, seed 1)
// 14 of the 143 shared meshes changed line counts (README, the fourteenth session's lists).
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  if (i < 0) return fallback;
  const value = args[i + 1];
  args.splice(i, 2);
  return value;
};
const cli = resolve(option('--cli', 'build/cli/crestline'));
const seed = BigInt(option('--seed', '1'));
const threads = option('--threads', '1');
const meshesDir = resolve('../shared/meshes');
let meshes = args;
if (meshes.length === 0) {
  if (!existsSync(join(meshesDir, 'manifest.tsv'))) {
    console.error(`relabel: no meshes given and ${meshesDir}/manifest.tsv is absent`);
    process.exit(2);
  }
  meshes = readFileSync(join(meshesDir, 'manifest.tsv'), 'utf8')
    .split('\n')
    .slice(1)
    .filter((line) => line.trim())
    .map((line) => join(meshesDir, line.split('\t')[0]));
}

// xorshift64: the same shuffle for the same seed.
function generator(start) {
  let s = start | 1n;
  const mask = (1n << 64n) - 1n;
  return (n) => {
    s ^= (s << 13n) & mask;
    s ^= s >> 7n;
    s ^= (s << 17n) & mask;
    return Number(s % BigInt(n));
  };
}

// The surface of a --with-mesh OBJ ("o surface": its v and f lines) numbered otherwise.
function shuffledSurface(text, random) {
  const vertices = [];
  const faces = [];
  let inSurface = false;
  for (const line of text.split('\n')) {
    if (line.startsWith('o ')) inSurface = line.trim() === 'o surface';
    else if (inSurface && line.startsWith('v ')) vertices.push(line);
    else if (inSurface && line.startsWith('f '))
      faces.push(
        line
          .slice(2)
          .trim()
          .split(/\s+/)
          .map((t) => parseInt(t, 10) - 1),
      );
  }
  const permutation = (n) => {
    const p = [...Array(n).keys()];
    for (let i = n - 1; i > 0; i--) {
      const j = random(i + 1);
      [p[i], p[j]] = [p[j], p[i]];
    }
    return p;
  };
  const place = permutation(vertices.length);
  const out = new Array(vertices.length);
  vertices.forEach((line, i) => (out[place[i]] = line));
  for (const t of permutation(faces.length)) {
    const f = faces[t].map((v) => place[v] + 1);
    const r = random(3);
    out.push(`f ${f[r]} ${f[(r + 1) % 3]} ${f[(r + 2) % 3]}`);
  }
  return out.join('\n') + '\n';
}

// The largest distance from a point of one output to the nearest of the other's, in mean edges (Infinity: more
// than one).
function largestMove(a, b, h) {
  const cell = h;
  const grid = new Map();
  const key = (p) => `${Math.floor(p[0] / cell)},${Math.floor(p[1] / cell)},${Math.floor(p[2] / cell)}`;
  for (const q of b) {
    const k = key(q);
    if (!grid.has(k)) grid.set(k, []);
    grid.get(k).push(q);
  }
  let worst = 0;
  for (const p of a) {
    let best = Infinity;
    const [i, j, k] = [0, 1, 2].map((d) => Math.floor(p[d] / cell));
    for (let di = -1; di <= 1; di++)
      for (let dj = -1; dj <= 1; dj++)
        for (let dk = -1; dk <= 1; dk++)
          for (const q of grid.get(`${i + di},${j + dj},${k + dk}`) ?? []) best = Math.min(best, Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
    worst = Math.max(worst, best / h);
  }
  return worst;
}

const work = mkdtempSync(join(tmpdir(), 'crestline-relabel-'));
const shown = (move) => (move === Infinity ? '> 1' : move.toExponential(2));
const run = (input, output, extra = []) =>
  execFileSync(cli, [input, '-o', output, '-q', '--threads', threads, ...extra], { stdio: ['ignore', 'ignore', 'pipe'] });
let differing = 0;
let worstOverall = 0;
try {
  for (const mesh of meshes) {
    const name = mesh.startsWith(meshesDir) ? mesh.slice(meshesDir.length + 1) : mesh;
    const welded = join(work, 'welded.obj');
    const shuffled = join(work, 'shuffled.obj');
    try {
      run(mesh, welded, ['--with-mesh']);
    } catch {
      console.log(`${name}: the CLI refuses it`);
      continue;
    }
    writeFileSync(shuffled, shuffledSurface(readFileSync(welded, 'utf8'), generator(seed)));
    run(welded, join(work, 'a.json'), ['--fairing-bound', '0']);
    run(shuffled, join(work, 'b.json'), ['--fairing-bound', '0']);
    const a = JSON.parse(readFileSync(join(work, 'a.json'), 'utf8'));
    const b = JSON.parse(readFileSync(join(work, 'b.json'), 'utf8'));
    const h = a.stats.mean_edge_length;
    const parts = [];
    let same = true;
    let worst = 0;
    for (const kind of ['ridges', 'valleys', 'creases']) {
      const la = a[kind] ?? [];
      const lb = b[kind] ?? [];
      same &&= la.length === lb.length;
      const pa = la.flatMap((l) => l.points);
      const pb = lb.flatMap((l) => l.points);
      worst = Math.max(worst, largestMove(pa, pb, h), largestMove(pb, pa, h));
      parts.push(`${kind} ${la.length}/${lb.length}`);
    }
    if (!same) differing++;
    worstOverall = Math.max(worstOverall, worst);
    console.log(`${name}: ${same ? 'same counts' : 'COUNTS DIFFER'}, ${parts.join(', ')}, largest move ${shown(worst)} mean edges`);
  }
} finally {
  rmSync(work, { recursive: true, force: true });
}
console.log(`relabel: ${meshes.length} meshes, ${differing} with other line counts; largest move ${shown(worstOverall)} mean edges`);
