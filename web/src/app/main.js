// Wires the page: files → the client (../client) → the worker (C++ readers,
// repair, Pipeline) → viewer; the panel re-runs only what a changed parameter needs.
import { sharedConnection } from '../client/browser.js';
import { overallFraction, selectLines } from '../client/client.js';
import { sampleMesh } from './sample.js';
import { WEIGHT_SCALE, WeightBrush } from '../three/brush.js';
import { Viewer } from '../three/viewer.js';
import { concaveShade } from '../three/line-layer.js';
import { render as renderDom, showLegend, showScale } from './dom.js';
import { emptyState, exportSource } from './page-state.js';
import { installDrop } from './drop.js';
import { createExports } from './exports.js';
import { PICKER_ACCEPT, ignoredSentence, selectFiles } from './files.js';
import { pipelineParameters } from '../client/parameters.js';
import { autoKey, createGui, defaultParams, pipelineOptions } from './gui.js';
import { linkFragment, parseLink } from './link.js';

const connection = sharedConnection();
// The parameter table of the core: the panel's controls and defaults.
const table = await connection.describe();
const params = defaultParams(table);
// Test and debugging hooks: the last result, the stages each run re-computed.
const app = (window.crestline = { results: [], params, parameters: table, lastResult: null, fields: null, mesh: null });

const viewer = new Viewer(document.getElementById('view'), {
  onContextLost: () => fail('The WebGL context was lost (the GPU was reset or ran out of memory); the view returns when the browser restores it.'),
  onContextRestored: () => fail(null),
});

const brush = new WeightBrush(viewer, { onStroke: () => compute() });

/** The one page state (page-state.js); `render()` draws it. */
const state = emptyState();
const render = () => renderDom(state);
let rescaleThreshold = false;

/** The session a parameter change goes to: the file loading, else the one shown. */
const active = () => state.loading?.session ?? state.shown?.session ?? null;
/** What the worker gets: the panel's values and the brushed weights of the shown mesh (a copy: it is transferred). */
const currentOptions = () => ({
  ...pipelineOptions(params, table),
  vertexWeights: state.loading ? null : brush.current()?.slice() ?? null,
});

/** A client session whose replies update the page only while it is the loading or the shown one. */
function newSession() {
  const session = connection.session({
    onProgress: (stage, fraction) => {
      if (session !== active()) return;
      state.progress = { stage, fraction: overallFraction(stage, fraction) };
      render();
      app.hooks.progress?.(stage);
    },
    onLoaded: ({ vertices, triangles, notes, milliseconds }) => {
      if (session !== state.loading?.session) return;
      Object.assign(state.loading, { vertices, triangles, loadMs: milliseconds, notes: [...state.loading.notes, ...notes] });
      state.notes = state.loading.notes;
      render();
      app.hooks.loaded?.();
    },
    onResult: (result) => received(session, result),
    onFields: (fields) => {
      if (session !== state.shown?.session) return;
      app.fields = fields;
      applyView();
    },
    onCancelled: () => cancelled(session),
    onError: (error) => failed(session, error),
  });
  return session;
}

/**
 * A session neither loading nor shown: its job is asked to stop and it is
 * freed (no worker restart: the worker stops it at its next progress check,
 * after the read if it is still reading, and keeps the shown mesh).
 */
function forget(session) {
  session.cancel();
  if (exporting.has(session)) retired.add(session); // an export still waits for it
  else session.dispose();
}
/** Sessions with exports on their way (how many), and those to free after them. */
const exporting = new Map();
const retired = new Set();

/** A result: the loading file becomes the shown mesh (the previous one is freed), or the shown mesh's lines change. */
function received(session, result) {
  let promoted = false;
  if (session === state.loading?.session) {
    const loaded = state.loading;
    delete loaded.restore;
    if (state.shown) forget(state.shown.session);
    state.shown = loaded;
    state.loading = null;
    viewer.setSurface(result.surface, { fit: false });
    promoted = true;
    brush.reset(result.surface.positions.length / 3);
    app.fields = null;
  } else if (session === state.shown?.session) {
    if (result.surface) viewer.setSurface(result.surface, { fit: false });
  } else {
    return forget(session);
  }
  const shown = /** @type {import('./page-state.js').MeshState} */ (state.shown);
  const started = performance.now();
  if (result.linesChanged) viewer.setLines(result.lines, result.kept);
  else viewer.setKept(result.kept);
  if (result.creasesChanged && result.creases) viewer.setCreases(result.creases);
  const drawMs = performance.now() - started; // main-thread work to show the result's lines
  shown.result = result;
  shown.stale = false;
  // The options that made these lines (unknown while newer ones wait behind them).
  if (!session.pending) shown.options = { ...session.options };
  const { lines, kept } = result;
  let selected = null;
  // What the exports save: the lines shown, selected on first use.
  app.shown = { name: shown.name, get lines() { return (selected ??= selectLines(lines, kept)); } };
  app.mesh = { name: shown.name, vertices: shown.vertices, triangles: shown.triangles, loadMs: shown.loadMs };
  app.lastResult = { name: shown.name, ran: result.ran, stats: result.stats, lineCount: kept.length, linesChanged: result.linesChanged, creaseCount: result.creases?.convex.length ?? 0, drawMs, milliseconds: result.milliseconds };
  app.results.push(app.lastResult);
  // The address bar: the link to this view of a linked mesh, else the bare page (no hashchange).
  const address = shown.src ? linkFragment(shown.src, { ...params, ...optionsAsParams(shown.options) }, table) : '';
  if (address !== location.hash) history.replaceState(null, '', `${location.pathname}${location.search}${address}`);
  gui.showUsed(result.stats, rescaleThreshold);
  rescaleThreshold = false;
  state.error = null; // a good result supersedes an earlier failure
  state.progress = null;
  const upstream = ['presmooth', 'curvature', 'extremality', 'regularity', 'smoothing'];
  if (result.ran.some((s) => upstream.includes(s))) app.fields = null;
  render();
  if (promoted) viewer.fitView(); // once the info box shows the new mesh: framing avoids it
  if (!session.busy) applyView();
  release(shown);
}

/** Exports waiting for the shown mesh's re-run go on (after a failure they fail with the worker's sentence). */
const release = (shown) => shown?.waiting?.splice(0).forEach((resolve) => resolve());

/** Pipeline options as the panel's values. */
function optionsAsParams(options = {}) {
  const out = {};
  for (const p of pipelineParameters(table)) {
    const value = options[p.key];
    if (value === undefined) continue;
    if (p.automatic) out[autoKey(p)] = value === 'auto';
    if (value !== 'auto') out[p.key] = value;
  }
  return out;
}

/** The panel shows `options` (the values that made the lines shown). */
function showOptions(options) {
  if (!options) return;
  Object.assign(params, optionsAsParams(options));
  gui.gui.controllersRecursive().forEach((c) => c.updateDisplay());
  if (state.shown?.result) gui.showUsed(state.shown.result.stats, false);
}

/** Cancel: a loading file is dropped at once (the previous mesh is whole); the shown mesh keeps the lines it had. */
function cancel() {
  if (state.loading) {
    const { session, name, restore } = state.loading;
    forget(session);
    state.loading = null;
    state.progress = null;
    state.notes = [state.shown ? `Cancelled ${name}: back to ${state.shown.name}.` : `Cancelled ${name}.`];
    showOptions(restore);
    render();
    applyView();
  } else if (state.shown?.session.busy) {
    state.shown.session.cancel();
  }
}

function cancelled(session) {
  if (session !== state.shown?.session) return forget(session);
  // The worker may hold a half-run pipeline: an OBJ/JSON export re-runs first.
  state.shown.stale = true;
  state.progress = null;
  state.notes = ['Cancelled: the lines shown are those of the values in the panel.'];
  release(state.shown);
  showOptions(state.shown.options);
  render();
  applyView();
}

function failed(session, { message }) {
  if (session === state.loading?.session) {
    // A file that cannot be read or computed: the previous mesh stays whole.
    showOptions(state.loading.restore);
    forget(session);
    state.loading = null;
  } else if (session === state.shown?.session) {
    state.shown.stale = true;
    release(state.shown);
  } else {
    return forget(session);
  }
  state.progress = null;
  fail(message);
}

/** The one-sentence error line; null clears it. */
function fail(message) {
  state.error = message;
  render();
}

/** The worker holds the shown mesh's lines exactly (after a cancel or a restart it runs them again). */
function current(shown) {
  if (!shown.stale && shown.session.hasMesh) return Promise.resolve();
  const done = new Promise((resolve) => (shown.waiting ??= []).push(resolve));
  shown.session.setOptions({ ...(shown.options ?? currentOptions()), vertexWeights: brush.current()?.slice() ?? null });
  render();
  return done;
}

/** Runs with the panel's options (the client queues them behind a running job). */
function compute() {
  const session = active();
  if (!session) return;
  session.setOptions(currentOptions());
  render();
}

function applyDisplay() {
  viewer.lines.setShown(params.showRidges, params.showValleys);
  viewer.lines.setColors(params.ridgeColor, params.valleyColor);
  const concave = `#${concaveShade(params.creaseColor).getHexString()}`;
  viewer.creases.setShown(params.showCreases, params.showCreases);
  viewer.creases.setColors(params.creaseColor, concave);
  viewer.lines.setWidth(params.lineWidth);
  viewer.setBackground(params.dark ? 'dark' : 'light');
  document.body.classList.toggle('dark', params.dark);
  showLegend(params, concave);
  applyView();
}

/** What each colour map shows, with its unit (the model's length unit L). */
const SCALE_NAMES = {
  kappaMax: 'κ max (1/L)',
  kappaMin: 'κ min (1/L)',
  eMax: '|e max| (1/L²)',
  eMin: '|e min| (1/L²)',
  weights: 'smoothing weight − 1',
};

/** Colour map or singular-triangle overlay; fetches fields from the worker when needed. */
function applyView() {
  const view = params.view;
  const session = state.shown?.session;
  let map = null;
  if (view === 'weights' && brush.weights) {
    viewer.surface.setSingular(null);
    map = { scale: viewer.surface.setColors(brush.weights.map((w) => w - 1), WEIGHT_SCALE), positive: false };
  } else if (view === 'shaded' || view === 'weights' || !session) {
    viewer.surface.setColors(null);
    viewer.surface.setSingular(null);
  } else if (!app.fields) {
    if (!session.busy && !state.shown?.stale) session.requestFields();
    return;
  } else if (view.startsWith('singular')) {
    viewer.surface.setColors(null);
    viewer.surface.setSingular(view === 'singularMax' ? app.fields.regularMax : app.fields.regularMin);
  } else {
    viewer.surface.setSingular(null);
    // An extremality's sign follows the arbitrary sign of its direction
    // (core/…/extremality.h): only |e| means something on its own.
    const values = app.fields[view];
    const positive = view.startsWith('e');
    map = { scale: viewer.surface.setColors(positive ? values.map(Math.abs) : values), positive };
  }
  showScale(map && { ...map, name: SCALE_NAMES[view] });
  viewer.render();
}

/** The brush settings of the panel; painting shows the weights. */
function applyBrush() {
  brush.setEnabled(params.brush);
  if (params.brush && state.shown) brush.surfaceIndex(); // built now rather than at the first stroke
  brush.radius = params.brushRadius;
  brush.value = params.brushValue;
  if (params.brush && params.view !== 'weights') app.update({ view: 'weights' });
}

/** The view preset and up axis of the panel. */
function applyCamera() {
  viewer.preset = params.preset;
  if (viewer.upAxis !== params.upAxis) viewer.setUpAxis(params.upAxis);
  else viewer.fitView();
}

/** The core writers' exports come from the worker's copy of the shown mesh. */
const workerExports = {
  async exportFile(format, view) {
    const source = exportSource(state);
    if ('refusal' in source) throw new Error(source.refusal);
    const { session } = source.shown;
    exporting.set(session, (exporting.get(session) ?? 0) + 1);
    try {
      await current(source.shown);
      if (source.shown.stale) throw new Error(`the lines of ${source.shown.name} could not be computed again for it (cancelled or failed).`);
      return await session.exportFile(format, view);
    } finally {
      exporting.set(session, exporting.get(session) - 1);
      if (!exporting.get(session)) exporting.delete(session);
      if (!exporting.has(session) && retired.delete(session)) session.dispose();
    }
  },
  exportText(format) {
    return this.exportFile(format);
  },
};
const exporter = createExports({
  viewer,
  client: workerExports,
  params,
  current: () => {
    const source = exportSource(state);
    if ('refusal' in source) throw new Error(source.refusal);
    return app.shown;
  },
});

const picker = /** @type {HTMLInputElement} */ (document.getElementById('picker'));
picker.accept = PICKER_ACCEPT;
const gui = createGui(params, table, {
  onCompute: compute,
  onDisplay: applyDisplay,
  onFit: () => viewer.fitView(),
  onCamera: applyCamera,
  onOpen: () => picker.click(),
  onBrush: applyBrush,
  onClearWeights: () => {
    brush.clear();
    applyView();
    compute();
  },
  onExport: (format) => app.save(format),
});

/** A new file: its own session, shown once its lines are ready; `send` starts the worker on it. */
function startMesh(name, send, notes = []) {
  let restore = state.shown?.options ?? null;
  if (state.loading) {
    // A newer file replaces the one loading.
    restore = state.loading.restore;
    forget(state.loading.session);
  }
  const session = newSession();
  state.loading = { session, name, notes, restore };
  state.error = null;
  state.notes = notes;
  state.progress = { stage: 'read', fraction: 0 };
  rescaleThreshold = true;
  send(session, { ...pipelineOptions(params, table), vertexWeights: null }); // a new mesh starts homogeneous
  render();
}

/** The built-in sample, already a soup. */
function loadSoup(soup) {
  startMesh(soup.name, (session, options) => session.load(soup, options));
}

/** The mesh of the page's link (#src=URL&…), fetched and read by the worker like a dropped file. */
function openLink(link) {
  Object.assign(params, link.settings);
  gui.gui.controllersRecursive().forEach((c) => c.updateDisplay());
  if (link.settings.upAxis) applyCamera();
  if (!link.url) return fail(`${link.name}: is not a URL the page can fetch.`);
  startMesh(link.name, (session, options) => session.openUrl(link.url, link.name, options));
  state.loading.src = link.src;
}

/** Dropped or picked files: read by the C++ readers in the worker, so the page never blocks. */
async function openFiles(fileList) {
  if (!fileList.length) return;
  try {
    const all = await Promise.all(fileList.map(async (f) => ({ name: f.name, bytes: await f.arrayBuffer() })));
    const { read: files, ignored } = selectFiles(all);
    const ignoredNote = ignoredSentence(files[0].name, ignored);
    startMesh(files[0].name, (session, options) => session.open(files, options), ignoredNote ? [ignoredNote] : []);
  } catch (error) {
    fail(`${fileList[0].name}: could not be read (${error.message}).`);
  }
}

// Test hooks: change parameters as the panel would.
app.viewer = viewer;
app.state = state;
/** Called on the loading file's progress and 'loaded' (tests cancel there). */
app.hooks = { progress: null, loaded: null };
Object.defineProperty(app, 'client', { get: () => state.shown?.session ?? state.loading?.session ?? null });
app.gui = gui.gui;
app.cancel = cancel;
/** Makes and downloads an export (the panel's buttons); failures show on the page, a success clears them. */
app.save = (format) =>
  exporter.save(format).then(
    (saved) => {
      if (state.error) fail(null); // the next action that succeeds clears an error
      return saved;
    },
    (error) => {
      fail(`Export ${format.toUpperCase()}: ${error.message}`);
      return null;
    },
  );
app.brush = brush;
app.update = (partial) => {
  Object.assign(params, partial);
  gui.gui.controllersRecursive().forEach((c) => c.updateDisplay());
  const pipelineKeys = pipelineParameters(table).flatMap((p) => [p.key, autoKey(p)]);
  if (Object.keys(partial).some((k) => pipelineKeys.includes(k))) compute();
  else if ('preset' in partial || 'upAxis' in partial) applyCamera();
  else if (['brush', 'brushRadius', 'brushValue'].some((k) => k in partial)) applyBrush();
  else applyDisplay();
};

// Framing avoids the info box and the panel; opening or closing them moves the model's centre.
viewer.covers = () => {
  const canvas = viewer.renderer.domElement.getBoundingClientRect();
  return [document.getElementById('hud'), gui.gui.domElement].map((element) => {
    const r = element.getBoundingClientRect();
    return { left: r.left - canvas.left, top: r.top - canvas.top, right: r.right - canvas.left, bottom: r.bottom - canvas.top };
  });
};
gui.gui.onOpenClose(() => viewer.applyFrame());
document.getElementById('details').addEventListener('toggle', () => viewer.applyFrame());
// Phones: the panel starts collapsed and the statistics folded away.
if (matchMedia('(max-width: 599px)').matches) {
  gui.gui.close();
  /** @type {HTMLDetailsElement} */ (document.getElementById('details')).open = false;
}
installDrop(document.body, openFiles);
picker.addEventListener('change', () => {
  openFiles([...picker.files]);
  picker.value = ''; // the same file can be picked again
});
document.getElementById('open').addEventListener('click', () => picker.click());
document.getElementById('cancel').addEventListener('click', cancel);
applyDisplay();
// The link's mesh, or the built-in sample.
const link = parseLink(location.hash, table, location.href);
if (link) openLink(link);
else loadSoup(sampleMesh());
addEventListener('hashchange', () => {
  const next = parseLink(location.hash, table, location.href);
  if (next) openLink(next);
});
