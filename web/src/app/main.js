// Wires the page: files → the client (../client) → the worker (C++ readers,
// repair, Pipeline) → viewer; the panel re-runs only what a changed parameter needs.
import { sharedConnection, sideConnection } from '../client/browser.js';
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

// The worker warms its glTF reader up after the sample's lines, for the first file dropped.
const connection = sharedConnection({ warmUp: true });
// The parameter table of the core: the panel's controls and defaults.
const table = await connection.describe().catch((error) => {
  // The engine cannot start in this browser (no WebAssembly SIMD, a blocked
  // .wasm): the page says so in its error line instead of staying blank.
  const line = /** @type {HTMLElement} */ (document.getElementById('error'));
  line.textContent = error.message;
  line.hidden = false;
  document.body.dataset.state = 'error';
  throw error;
});
const params = defaultParams(table);
// Test and debugging hooks: the last result, the stages each run re-computed.
const app = (window.crestline = { results: [], params, parameters: table, lastResult: null, fields: null, mesh: null });

const viewer = new Viewer(document.getElementById('view'), {
  onContextLost: () => fail('The WebGL context was lost (the GPU was reset or ran out of memory); the view returns when the browser restores it.'),
  onContextRestored: () => fail(null),
});

// The brush's surface index is built by a second worker: the first may be running the pipeline.
const brush = new WeightBrush(viewer, { onStroke: () => compute(), buildIndex: (positions, indices) => sideConnection().surfaceIndex(positions, indices) });

/** The one page state (page-state.js); `render()` draws it. */
const state = emptyState();
const render = () => renderDom(state);
let rescaleThreshold = false;

/** The session a parameter change goes to: the file loading, else the one shown. */
const active = () => state.loading?.session ?? state.shown?.session ?? null;
/** What the worker gets: the panel's values and the brushed weights of the shown mesh (a copy: it is transferred). */
const currentOptions = () => ({
  ...pipelineOptions(params, table),
  vertexWeights: state.loading ? null : (brush.current()?.slice() ?? null),
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
    onLoaded: ({ vertices, triangles, notes, milliseconds, surface }) => {
      // The shown session reads its mesh again only after a worker restart: the same surface.
      if (session !== state.loading?.session) return;
      Object.assign(state.loading, { vertices, triangles, loadMs: milliseconds, notes: [...state.loading.notes, ...notes] });
      state.notes = state.loading.notes;
      promote(surface);
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
  if (exporting.has(session))
    retired.add(session); // an export still waits for it
  else session.dispose();
}
/** Sessions with exports on their way (how many), and those to free after them. */
const exporting = new Map();
const retired = new Set();

/**
 * The loading file's surface is repaired: it becomes the shown mesh, its
 * lines still to come (Cancel from here on keeps this one). Framed once the
 * info box names it.
 */
function promote(surface) {
  const loaded = state.loading;
  if (state.shown) dropPrevious(state.shown); // one mesh is held behind the shown one, no more
  // The previous mesh is kept (not drawn) until the new one has lines: a
  // computation that fails before them gives the previous page back.
  loaded.previous = state.shown && { mesh: state.shown, restore: loaded.restore, weights: brush.weights, shown: app.shown };
  delete loaded.restore;
  state.shown = loaded;
  state.loading = null;
  loaded.surface = surface;
  viewer.setSurface(surface, { fit: false });
  viewer.clearLines();
  brush.weights = null;
  brush.reset(surface.positions.length / 3);
  app.fields = null;
  app.shown = null;
  app.mesh = { name: loaded.name, vertices: loaded.vertices, triangles: loaded.triangles, loadMs: loaded.loadMs };
  render();
  viewer.fitView();
  applyView();
}

/** The shown mesh keeps the page: the previous one is freed. */
function dropPrevious(shown) {
  if (shown.previous) forget(shown.previous.mesh.session);
  shown.previous = null;
}

/** The mesh shown before `shown` (whose lines failed) is the page's again, picture, brush, panel and exports. */
function backToPrevious(shown) {
  const { mesh, restore, weights, shown: lines } = shown.previous;
  shown.previous = null;
  forget(shown.session);
  state.shown = mesh;
  viewer.setSurface(mesh.surface, { fit: false });
  viewer.clearLines();
  if (mesh.result) {
    viewer.setLines(mesh.result.lines, mesh.result.kept);
    if (mesh.result.creases) viewer.setCreases(mesh.result.creases);
  }
  brush.weights = weights;
  brush.reset(mesh.surface.positions.length / 3);
  app.fields = null;
  app.shown = lines;
  app.mesh = { name: mesh.name, vertices: mesh.vertices, triangles: mesh.triangles, loadMs: mesh.loadMs };
  showOptions(restore);
  viewer.fitView();
}

/**
 * A reply of the mesh held behind a new one (a recompute it ran when the new
 * file came): the worker's lines may differ from those it would come back with.
 */
function ofPrevious(session) {
  const previous = state.shown?.previous?.mesh;
  if (session !== previous?.session) return false;
  previous.stale = true;
  return true;
}

let cacheWarmedUp = false;

/** A result: the shown mesh's lines (the first ones after a load, or new ones after a change). */
function received(session, result) {
  if (ofPrevious(session)) return;
  if (session === state.loading?.session)
    promote(result.surface); // no 'loaded' seen (not expected)
  else if (session !== state.shown?.session) return forget(session);
  const shown = /** @type {import('./page-state.js').MeshState} */ (state.shown);
  dropPrevious(shown);
  // Drawn already when it was loaded; again only after a worker restart read the mesh anew.
  if (result.surface && result.surface !== shown.surface) {
    viewer.setSurface(result.surface, { fit: false });
    shown.surface = result.surface;
  }
  const started = performance.now();
  // New lines, or lines the page did not draw (a result that came after Cancel).
  if (result.lines !== shown.result?.lines) viewer.setLines(result.lines, result.kept);
  else viewer.setKept(result.kept);
  if (result.creases && result.creases !== shown.result?.creases) viewer.setCreases(result.creases);
  const drawMs = performance.now() - started; // main-thread work to show the result's lines
  const firstLines = !shown.result;
  shown.result = result;
  shown.stale = false;
  // The options that made these lines (unknown while newer ones wait behind them).
  if (!session.pending) shown.options = { ...session.options };
  const { lines, kept } = result;
  let selected = null;
  // What the exports save: the lines shown, selected on first use.
  app.shown = {
    name: shown.name,
    get lines() {
      return (selected ??= selectLines(lines, kept));
    },
  };
  app.mesh = { name: shown.name, vertices: shown.vertices, triangles: shown.triangles, loadMs: shown.loadMs };
  app.lastResult = {
    name: shown.name,
    ran: result.ran,
    stats: result.stats,
    lineCount: kept.length,
    linesChanged: result.linesChanged,
    creaseCount: result.creases?.convex.length ?? 0,
    drawMs,
    milliseconds: result.milliseconds,
  };
  app.results.push(app.lastResult);
  showAddress();
  gui.showUsed(result.stats, rescaleThreshold);
  rescaleThreshold = false;
  state.error = null; // a good result supersedes an earlier failure
  state.progress = null;
  const upstream = ['presmooth', 'curvature', 'extremality', 'regularity', 'smoothing'];
  if (result.ran.some((s) => upstream.includes(s))) app.fields = null;
  render();
  // The statistics' lines are reserved in the info box (style.css), so it does not grow over the model
  // and the picture stays: a new view would draw the surface again (three/surface-cache.js; ≈ 0.3 s for
  // 871k triangles in SwiftShader). Where it did grow over it (a longer text, a narrow window), the model
  // is framed again after the frame that shows the lines, unless the user moved the camera meanwhile.
  const reframe = () => state.shown === shown && !shown.cameraMoved && !viewer.framingUncovered() && viewer.fitView();
  if (firstLines && !shown.cameraMoved) viewer.afterFrame(reframe);
  // After the page's first lines (the sample's), the first frames of a large mesh are prepared, once.
  if (!cacheWarmedUp) {
    viewer.afterFrame(() => {
      cacheWarmedUp = true;
      viewer.warmUpCache();
    });
  }
  if (!session.busy) applyView();
  release(shown);
}

/**
 * The address bar: the link to the view shown of a linked mesh, else the bare
 * page (replaceState: no hashchange). A link that failed or was cancelled goes.
 */
function showAddress() {
  const { shown } = state;
  const address = shown?.src ? linkFragment(shown.src, { ...params, ...optionsAsParams(shown.options) }, table) : '';
  if (address !== location.hash) history.replaceState(null, '', `${location.pathname}${location.search}${address}`);
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
    showAddress();
    render();
    applyView();
  } else if (state.shown?.session.busy) {
    state.shown.session.cancel();
  }
}

function cancelled(session) {
  if (ofPrevious(session)) return;
  if (session !== state.shown?.session) return forget(session);
  dropPrevious(state.shown); // Cancel keeps the new mesh once it is shown
  // The worker may hold a half-run pipeline: an OBJ/JSON export re-runs first.
  state.shown.stale = true;
  state.progress = null;
  state.notes = [
    state.shown.result
      ? 'Cancelled: the lines shown are those of the values in the panel.'
      : `Cancelled: ${state.shown.name} has no lines yet; change a setting to compute them.`,
  ];
  release(state.shown);
  showOptions(state.shown.options);
  render();
  applyView();
}

function failed(session, { message }) {
  if (ofPrevious(session)) return;
  if (session === state.loading?.session) {
    // A file that cannot be read or computed: the previous mesh stays whole.
    showOptions(state.loading.restore);
    forget(session);
    state.loading = null;
    showAddress();
  } else if (session === state.shown?.session && state.shown.previous) {
    // The new mesh's first lines failed (out of memory, say): the previous page comes back.
    const previous = state.shown;
    release(previous);
    backToPrevious(previous);
    showAddress();
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

/** The field view applied last: {view, fields, geometry, map}. */
let fieldView = null;

/** Colour map or singular-triangle overlay; fetches fields from the worker when needed. */
function applyView() {
  const view = params.view;
  const session = state.shown?.session;
  let map = null;
  // A field view shown already (the same fields on the same surface) is left as it is: set again, it
  // would draw the surface anew (three/surface-cache.js), e.g. after every threshold change.
  const same = fieldView?.view === view && fieldView.fields === app.fields && fieldView.geometry === viewer.surface.mesh.geometry;
  if (view === 'weights' && brush.weights) {
    fieldView = null;
    viewer.surface.setSingular(null);
    map = {
      scale: viewer.surface.setColors(
        brush.weights.map((w) => w - 1),
        WEIGHT_SCALE,
      ),
      positive: false,
    };
  } else if (view === 'shaded' || view === 'weights' || !session) {
    fieldView = null;
    viewer.surface.setColors(null);
    viewer.surface.setSingular(null);
  } else if (!app.fields) {
    if (!session.busy && !state.shown?.stale) session.requestFields();
    return;
  } else if (same) {
    map = fieldView.map;
  } else if (view.startsWith('singular')) {
    viewer.surface.setColors(null);
    viewer.surface.setSingular(view === 'singularMax' ? app.fields.regularMax : app.fields.regularMin);
    fieldView = { view, fields: app.fields, geometry: viewer.surface.mesh.geometry, map };
  } else {
    viewer.surface.setSingular(null);
    // An extremality's sign follows the arbitrary sign of its direction
    // (core/…/extremality.h): only |e| means something on its own.
    const values = app.fields[view];
    const positive = view.startsWith('e');
    map = { scale: viewer.surface.setColors(positive ? values.map(Math.abs) : values), positive };
    fieldView = { view, fields: app.fields, geometry: viewer.surface.mesh.geometry, map };
  }
  showScale(map && { ...map, name: SCALE_NAMES[view] });
  viewer.render();
}

/** The brush settings of the panel; painting shows the weights. */
const PREPARING = 'Brush: preparing the surface (a few seconds on a large mesh); strokes paint once it is ready.';

function applyBrush() {
  brush.setEnabled(params.brush);
  // Built now rather than at the first stroke, in a worker: the page says so until it is there.
  if (params.brush && state.shown && !brush.surfaceIndex()) {
    state.notes = [...state.notes.filter((n) => n !== PREPARING), PREPARING];
    render();
    brush.ready().then(
      () => {
        state.notes = state.notes.filter((n) => n !== PREPARING);
        render();
      },
      (error) => fail(error.message),
    );
  }
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
viewer.controls.addEventListener('start', () => state.shown && (state.shown.cameraMoved = true));
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
