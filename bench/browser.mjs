#!/usr/bin/env node
// The browser row of the benchmark: the built app (web/dist) in headless
// Chromium (playwright-core, /usr/bin/chromium, a fresh profile per run), a
// mesh dropped on the page as a user drops it, timed from the drop to the
// frame that shows its lines, then a threshold change's main-thread work, then
// how soon a Cancel stops the pipeline: the whole pipeline re-run (0
// pre-smoothing steps, its time step toggled, so every stage is dirty), once
// to its end, then --cancels times with Cancel pressed at moments spread
// evenly over that run's time, each timed from the click to the worker's
// 'cancelled' arriving.
//   node bench/browser.mjs [--mesh large/dragon.glb] [--runs 3] [--drops 1] [--rethresholds 4]
//                          [--cancels 8] [--dist web/dist] [--json OUT.json] [--no-isolation]
//                          [--pause MS]
// --drops N drops the mesh N times in each page, one after the other's lines
// (a row each: run.drop); a second drop runs the code V8 optimised during the
// first (see the README's performance notes).
// --pause waits MS after the sample's lines before the drop (a user finding a
// file; default 0). The `warm-up` column says whether the worker had warmed its
// glTF reader up before the drop (web/src/worker/warm-up.js).
// --no-isolation serves the app without COOP/COEP: the plain one-thread WASM
// module instead of crestline-mt on every core (the table says which ran).
// The mesh is a path under ../shared/meshes. Without Chromium, the meshes or
// web/dist it says so and exits 0 (skipped), as the other benchmark rows do.
// Every time is the page's (performance.now() on the main thread), except the
// worker's own figures: `read+repair` (Session.loadFile) and `pipeline`
// (Session.run and the copies of lines and creases out of the WASM heap),
// with the stage split of its --stats. The `cpu` columns are the CPU
// milliseconds Chromium's parts spent from the drop to its lines' frame
// (cpu-time.mjs; Linux): the renderer's workers, its thread pool (V8's
// background compiles and GC), its main thread, the GPU process, and all of
// Chromium; less moved by other work on the machine than the wall clock.
import { existsSync, writeFileSync } from 'node:fs';
import { loadavg } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { CHROMIUM, launch } from '../tests/browser/browser.mjs';
import { browserCpu, cpuSpent } from './cpu-time.mjs';
import { serve } from '../tests/browser/server.mjs';
import { median, table } from './table.mjs';

const ROOT = fileURLToPath(new URL('../', import.meta.url));
const MESHES = resolve(ROOT, '../shared/meshes');
const STAGES = ['presmooth', 'curvature', 'extremality', 'regularity', 'smoothing', 'tracing', 'singular', 'polylines', 'fairing', 'filter', 'creases'];

function parseArgs(argv) {
  const args = { mesh: 'large/dragon.glb', runs: 3, drops: 1, rethresholds: 4, cancels: 8, dist: join(ROOT, 'web/dist') };
  for (let i = 0; i < argv.length; i++) {
    const value = () => argv[++i];
    if (argv[i] === '--mesh') args.mesh = value();
    else if (argv[i] === '--runs') args.runs = Math.max(1, Number(value()));
    else if (argv[i] === '--drops') args.drops = Math.max(1, Number(value()));
    else if (argv[i] === '--rethresholds') args.rethresholds = Math.max(1, Number(value()));
    else if (argv[i] === '--cancels') args.cancels = Math.max(0, Number(value()));
    else if (argv[i] === '--dist') args.dist = resolve(value());
    else if (argv[i] === '--json') args.json = value();
    else if (argv[i] === '--no-isolation') args.isolation = false;
    else if (argv[i] === '--pause') args.pause = Math.max(0, Number(value()));
    else throw new Error(`unknown argument ${argv[i]}`);
  }
  return args;
}

const load = () => loadavg()[0].toFixed(1);

/**
 * Installed in the page once the sample is shown: timestamps and durations of
 * what the main thread does for the worker's replies (per message type), of
 * every WebGL render, of posts to the worker, and the long tasks.
 */
function instrument() {
  const app = window.crestline;
  const log = (window.__bench = { messages: [], renders: [], posts: [], longTasks: [], surfaceDraws: 0 });
  const worker = app.client.connection.worker;
  const receive = worker.onmessage;
  worker.onmessage = (event) => {
    const at = performance.now();
    receive.call(worker, event);
    const { type, stage, milliseconds } = event.data;
    log.messages.push({ type, stage, milliseconds, at, ms: performance.now() - at });
  };
  const post = worker.postMessage.bind(worker);
  worker.postMessage = (message, transfer) => {
    const at = performance.now();
    post(message, transfer);
    log.posts.push({ type: message.type, at, ms: performance.now() - at });
  };
  // A frame: the viewer's draw (the surface cache's passes) where it has one, else the renderer's one render.
  const [drawer, method] = app.viewer.draw ? [app.viewer, 'draw'] : [app.viewer.renderer, 'render'];
  const draw = drawer[method].bind(drawer);
  drawer[method] = (...args) => {
    const at = performance.now();
    draw(...args);
    log.renders.push({ at, ms: performance.now() - at });
  };
  // The surface's draws (its mesh stays; its geometry changes).
  app.viewer.surface.mesh.onBeforeRender = () => log.surfaceDraws++;
  new PerformanceObserver((list) => log.longTasks.push(...list.getEntries().map((e) => ({ at: e.startTime, ms: e.duration })))).observe({
    type: 'longtask',
  });
  /**
   * Resolves once a frame has been shown after the page handled its next
   * result: the time of the animation frame that follows the render drawing it.
   */
  window.__benchFramed = (count) =>
    new Promise((resolve, reject) => {
      const poll = () => {
        if (document.body.dataset.state === 'error') return reject(new Error(document.getElementById('error').textContent));
        const handled = window.__bench.messages.findLast((m) => m.type === 'result');
        const drawn = handled && window.__bench.renders.find((r) => r.at >= handled.at + handled.ms);
        if (app.results.length > count && drawn) requestAnimationFrame(() => resolve(performance.now()));
        else setTimeout(poll, 5);
      };
      poll();
    });
}

/**
 * Drops `bytes` (fetched beforehand: not timed) named `name` as one file on
 * the page; returns the page's timeline and the CPU Chromium spent meanwhile.
 */
async function dropAndTime(page, url, name) {
  await page.evaluate(async (url) => (window.__benchBytes = await (await fetch(url)).arrayBuffer()), url);
  const cpuBefore = browserCpu();
  const timeline = await page.evaluate(async (name) => {
    const app = window.crestline;
    const log = window.__bench;
    const count = app.results.length;
    const file = new File([window.__benchBytes], name);
    delete window.__benchBytes;
    const transfer = new DataTransfer();
    transfer.items.add(file);
    log.messages.length = log.renders.length = log.posts.length = log.longTasks.length = log.surfaceDraws = 0;
    const start = performance.now();
    document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
    const end = await window.__benchFramed(count);
    window.__benchThreshold = app.lastResult.stats.threshold;
    return { start, end, ...structuredClone(log), result: app.lastResult, mesh: app.mesh };
  }, name);
  return { ...timeline, cpu: cpuSpent(cpuBefore, browserCpu()) };
}

/** A threshold change as the panel makes it, then the frame that shows it. */
function rethresholdAndTime(page, factor) {
  return page.evaluate(async (factor) => {
    const app = window.crestline;
    const log = window.__bench;
    const count = app.results.length;
    log.messages.length = log.renders.length = log.posts.length = log.longTasks.length = log.surfaceDraws = 0;
    const start = performance.now();
    app.update({ autoThreshold: false, threshold: window.__benchThreshold * factor });
    const handler = performance.now() - start;
    const end = await window.__benchFramed(count);
    return { start, end, handler, ...structuredClone(log), result: app.lastResult };
  }, factor);
}

/**
 * Re-runs the whole pipeline without pre-smoothing (0 steps, its time step
 * set to `timeStep`, 1 and 1.5 in turn: every stage is dirty, none costs more
 * than at the drop) and presses Cancel `delay` ms after the change: the ms from the
 * click to the worker's reply ('cancelled', or 'result' if the run ended
 * first; NaN ms and the run's ms if it ended before the click) and the
 * stage of the last progress message before the click.
 */
function cancelAndTime(page, delay, timeStep) {
  return page.evaluate(
    async ({ delay, timeStep }) => {
      const app = window.crestline;
      const log = window.__bench;
      log.messages.length = log.longTasks.length = 0;
      const start = performance.now();
      app.update({ autoPresmoothSteps: false, presmoothSteps: 0, presmoothTimeStep: timeStep });
      // Waits `delay` ms, or less if the run ends first.
      for (const until = start + delay; performance.now() < until && !log.messages.some((m) => m.type === 'result');)
        await new Promise((resolve) => setTimeout(resolve, Math.min(20, until - performance.now())));
      const at = performance.now();
      const stage = log.messages.findLast((m) => m.type === 'progress')?.stage ?? 'none';
      const done = log.messages.find((m) => m.type === 'result');
      if (done) return { type: 'result', ms: NaN, stage, runMs: done.at - start };
      app.cancel();
      const reply = () => log.messages.find((m) => (m.type === 'cancelled' || m.type === 'result') && m.at >= at);
      for (const start = performance.now(); !reply(); await new Promise((resolve) => setTimeout(resolve, 5)))
        if (performance.now() - start > 60000) throw new Error(`no reply to a Cancel in 60 s (${log.messages.map((m) => m.type).join(' ')})`);
      // The main thread's long tasks meanwhile (a reply waits for them) and the
      // time from the last progress message to the reply (the worker's gap).
      const end = reply().at;
      await new Promise((resolve) => setTimeout(resolve, 50)); // the long tasks' entries come late
      const mainBusy = log.longTasks.filter((l) => l.at < end && l.at + l.ms > at).reduce((s, l) => s + Math.min(end, l.at + l.ms) - Math.max(at, l.at), 0);
      const lastProgress = log.messages.findLast((m) => m.type === 'progress' && m.at < end);
      return { type: reply().type, ms: end - at, stage, mainBusy, sinceProgress: lastProgress ? end - Math.max(at, lastProgress.at) : NaN };
    },
    { delay, timeStep },
  );
}

/** The drop's timeline as a split of drop-to-lines (ms). */
function dropSplit(t) {
  const first = (type, stage) => t.messages.find((m) => m.type === type && (!stage || m.stage === stage));
  const open = t.posts.find((p) => p.type === 'open');
  const reading = first('progress', 'read');
  const loaded = first('loaded');
  const result = t.messages.findLast((m) => m.type === 'result');
  const firstRender = (after) => t.renders.find((r) => r.at >= after.at + after.ms);
  const surfaceRender = firstRender(loaded);
  const linesRender = firstRender(result);
  const loadMs = t.mesh.loadMs;
  const pipelineMs = t.result.milliseconds;
  const inWindow = t.longTasks.filter((l) => l.at >= t.start && l.at <= t.end);
  return {
    dropToLines: t.end - t.start,
    // Main thread: the File's bytes, the client's copies, the post.
    pageRead: open.at + open.ms - t.start,
    // The 'open' message reaching the worker (and the worker's queue).
    toWorker: reading.at - (open.at + open.ms),
    readRepair: loadMs,
    // Session.surface() out of the heap, posting it, and its arrival.
    surfaceOut: loaded.at - reading.at - loadMs,
    surfaceHandler: loaded.ms,
    surfaceRender: surfaceRender?.ms ?? NaN,
    pipeline: pipelineMs,
    // From the surface's arrival to the result's (the worker's run, its post and the page's own work meanwhile).
    linesOut: result.at - loaded.at - pipelineMs,
    linesHandler: result.ms,
    linesRender: linesRender?.ms ?? NaN,
    // From the render call that draws the lines to the next animation frame.
    frame: t.end - (linesRender ? linesRender.at + linesRender.ms : result.at + result.ms),
    longTasks: inWindow.reduce((s, l) => s + l.ms, 0),
    surfaceDraws: t.surfaceDraws,
    longestTask: Math.max(0, ...inWindow.map((l) => l.ms)),
    stages: Object.fromEntries(STAGES.map((s) => [s, 1000 * (t.result.stats.seconds?.[s] ?? NaN)])),
    cpu: t.cpu ?? {},
  };
}

function rethresholdSplit(t) {
  const result = t.messages.findLast((m) => m.type === 'result');
  const render = t.renders.find((r) => r.at >= result.at + result.ms);
  const mainThread = t.handler + result.ms + (render?.ms ?? 0);
  const inWindow = t.longTasks.filter((l) => l.at >= t.start && l.at <= t.end);
  return {
    toFrame: t.end - t.start,
    handler: t.handler,
    resultHandler: result.ms,
    render: render?.ms ?? NaN,
    mainThread,
    worker: t.result.milliseconds,
    longTasks: inWindow.reduce((s, l) => s + l.ms, 0),
    surfaceDraws: t.surfaceDraws,
    lines: t.result.lineCount,
    ran: t.result.ran,
  };
}

/** A global of every worker of the page; an idle pthread of crestline-mt waits in Atomics.wait and never answers: 2 s at most each. */
function askWorkers(page, read) {
  const within = (promise, ms) => Promise.race([promise, new Promise((resolve) => setTimeout(resolve, ms))]);
  return Promise.all(
    page.workers().map((w) =>
      within(
        w.evaluate(read).catch(() => undefined),
        2000,
      ),
    ),
  );
}

async function measureRun(args, server) {
  const browser = await launch();
  try {
    const page = await browser.newPage({ viewport: { width: 1000, height: 750 } });
    const errors = [];
    page.on('pageerror', (error) => errors.push(error.message));
    page.on('crash', () => process.stderr.write('browser: the page crashed\n'));
    page.on('console', (m) => m.type() === 'error' && process.stderr.write(`browser: console error: ${m.text().slice(0, 300)}\n`));
    const origin = `http://127.0.0.1:${server.address().port}`;
    await page.goto(`${origin}/`);
    await page.waitForFunction(() => window.crestline?.lastResult && document.body.dataset.state === 'ready', null, { timeout: 120000 });
    await page.evaluate(instrument);
    if (args.pause) await page.waitForTimeout(args.pause);
    const loadBefore = load();
    const drops = [];
    for (let i = 0; i < args.drops; i++) drops.push(await dropAndTime(page, `${origin}/meshes/${args.mesh}`, args.mesh.split('/').pop()));
    const drop = drops[0];
    const rethresholds = [];
    for (let i = 0; i < args.rethresholds; i++) rethresholds.push(rethresholdSplit(await rethresholdAndTime(page, i % 2 ? 1 : 1.5)));
    // One re-run to its end (no Cancel): how long the cancels' runs take.
    const rerun = args.cancels ? await cancelAndTime(page, 120000, 1.5) : null;
    const cancels = [];
    for (let i = 0; i < args.cancels; i++) cancels.push(await cancelAndTime(page, ((i + 0.5) / args.cancels) * rerun.runMs, i % 2 ? 1.5 : 1));
    if (errors.length) throw new Error(`the page failed: ${errors.join('; ')}`);
    const threads = await askWorkers(page, () => self.crestlineThreads);
    // Whether the worker's warm-up had ended before the drop (it waits while the worker is busy).
    const pageOrigin = await page.evaluate(() => performance.timeOrigin);
    const warmedUp = (await askWorkers(page, () => self.crestlineWarmedUp)).some((w) => w && w.at < pageOrigin + drop.start);
    return {
      threads: threads.find((t) => t !== undefined) ?? '?',
      warmedUp,
      load: [loadBefore, load()],
      triangles: drop.result.stats.triangles,
      lines: drop.result.lineCount,
      drops: drops.map(dropSplit),
      rethreshold: rethresholds,
      cancels,
      rerunMs: rerun?.runMs ?? NaN,
    };
  } finally {
    await browser.close();
  }
}

const args = parseArgs(process.argv.slice(2));
const missing = [
  [existsSync(CHROMIUM), `no Chromium at ${CHROMIUM}`],
  [existsSync(join(MESHES, args.mesh)), `no ${args.mesh} in ${MESHES}`],
  [existsSync(join(args.dist, 'index.html')), `no web app in ${args.dist} (web/build.sh)`],
].find(([present]) => !present);
if (missing) {
  console.log(`bench: browser row SKIPPED (${missing[1]}).`);
  process.exit(0);
}

const noIsolation = { 'Cross-Origin-Opener-Policy': null, 'Cross-Origin-Embedder-Policy': null };
const server = await serve({ '/meshes/': MESHES, '/': args.dist }, args.isolation === false ? noIsolation : {});
const runs = [];
try {
  for (let run = 0; run < args.runs; run++) {
    process.stderr.write(`browser: ${args.mesh}, run ${run + 1} of ${args.runs} (load ${load()}) …\n`);
    runs.push(await measureRun(args, server));
  }
} finally {
  server.close();
}

const f = (ms) => (Number.isFinite(ms) ? ms.toFixed(0) : '-');
const f1 = (ms) => (Number.isFinite(ms) ? ms.toFixed(1) : '-');
const DROP = [
  ['drop→lines', 'dropToLines'],
  ['page read', 'pageRead'],
  ['to worker', 'toWorker'],
  ['read+repair', 'readRepair'],
  ['surface out', 'surfaceOut'],
  ['surface (main)', 'surfaceHandler'],
  ['surface render', 'surfaceRender'],
  ['pipeline', 'pipeline'],
  ['lines out', 'linesOut'],
  ['lines (main)', 'linesHandler'],
  ['lines render', 'linesRender'],
  ['frame', 'frame'],
  ['long tasks', 'longTasks'],
  ['surface draws', 'surfaceDraws'],
];
const CPU = [
  ['cpu worker', 'worker'],
  ['cpu pool', 'pool'],
  ['cpu main', 'main'],
  ['cpu gpu', 'gpu'],
  ['cpu all', 'all'],
];
const rows = [['run', 'load', 'warm-up', ...DROP.map(([h]) => h), 'smoothing', ...CPU.map(([h]) => h)]];
const row = (label, loadText, warm, pick) => [
  label,
  loadText,
  warm,
  ...DROP.map(([, k]) => f(pick((d) => d[k]))),
  f(pick((d) => d.stages.smoothing)),
  ...CPU.map(([, k]) => f(pick((d) => d.cpu[k] ?? NaN))),
];
// A run's drops are rows run.1, run.2, … when there are several.
const label = (run, drop) => (args.drops > 1 ? `${run + 1}.${drop + 1}` : String(run + 1));
runs.forEach((r, i) => r.drops.forEach((d, k) => rows.push(row(label(i, k), k ? '' : r.load.join('→'), k ? '' : r.warmedUp ? 'done' : 'no', (get) => get(d)))));
for (let k = 0; k < args.drops; k++)
  rows.push(row(args.drops > 1 ? `median, drop ${k + 1}` : 'median', '', '', (get) => median(runs.map((r) => get(r.drops[k])))));
const mesh = `${args.mesh} (${runs[0].triangles} triangles, ${runs[0].lines} lines)`;
const times = args.drops > 1 ? `dropped ${args.drops} times in each page` : 'dropped on the app';
console.log(
  `Browser: headless Chromium, ${mesh}, ${times}, WASM on ${runs[0].threads} thread(s); ms, page clock; load = 1-minute load average before→after; cpu = ms of CPU from the drop to its frame`,
);
console.log(table(rows));

const all = runs.flatMap((r) => r.rethreshold);
const RETHR = [
  ['to frame', 'toFrame'],
  ['update()', 'handler'],
  ['result (main)', 'resultHandler'],
  ['render', 'render'],
  ['main thread', 'mainThread'],
  ['worker', 'worker'],
  ['long tasks', 'longTasks'],
  ['surface draws', 'surfaceDraws'],
];
const rrows = [['re-threshold', ...RETHR.map(([h]) => h)]];
rrows.push(['median', ...RETHR.map(([, k]) => f1(median(all.map((r) => r[k]))))]);
rrows.push(['max', ...RETHR.map(([, k]) => f1(Math.max(...all.map((r) => r[k]))))]);
console.log(`\nRe-threshold (×1.5 and back, ${all.length} changes): ms; main thread = update() + the result's handling + its render call`);
console.log(table(rrows));
const stopped = runs.flatMap((r) => r.cancels).filter((c) => c.type === 'cancelled');
if (stopped.length) {
  const slowest = stopped.reduce((a, b) => (b.ms > a.ms ? b : a));
  console.log(
    `\nCancel (the whole pipeline re-run without pre-smoothing, Cancel pressed at ${args.cancels} moments spread over it, per run): ms from the click to 'cancelled'; re-run = the run's ms uncancelled; at the slowest click, main busy = the page's long tasks between click and reply, since progress = from the last progress message (or the click) to the reply`,
  );
  console.log(
    table([
      ['re-run', 'cancels', 'median', 'max', 'stage at max', 'main busy at max', 'since progress at max', 'finished first'],
      [
        f(median(runs.map((r) => r.rerunMs))),
        String(stopped.length),
        f1(median(stopped.map((c) => c.ms))),
        f1(slowest.ms),
        slowest.stage,
        f1(slowest.mainBusy),
        f1(slowest.sinceProgress),
        String(runs.flatMap((r) => r.cancels).length - stopped.length),
      ],
    ]),
  );
}
if (args.json) writeFileSync(args.json, JSON.stringify({ runner: 'browser-chromium', chromium: CHROMIUM, mesh: args.mesh, runs }, null, 2) + '\n');
