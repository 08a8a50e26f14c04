// Wires the page: files → the client (../client) → the worker (C++ readers,
// repair, Pipeline) → viewer; the panel re-runs only what a changed parameter needs.
import { sharedConnection } from '../client/browser.js';
import { overallFraction, selectLines } from '../client/client.js';
import { sampleMesh } from './sample.js';
import { WeightBrush } from '../three/brush.js';
import { Viewer } from '../three/viewer.js';
import { concaveShade } from '../three/line-layer.js';
import { setState, showError, showFile, showLegend, showNotes, showProgress, showStats } from './dom.js';
import { installDrop } from './drop.js';
import { createExports } from './exports.js';
import { PICKER_ACCEPT, ignoredSentence, selectFiles } from './files.js';
import { pipelineParameters } from '../client/parameters.js';
import { autoKey, createGui, defaultParams, pipelineOptions } from './gui.js';

const connection = sharedConnection();
// The parameter table of the core: the panel's controls and defaults.
const table = await connection.describe();
const params = defaultParams(table);
// Test and debugging hooks: the last result, the stages each run re-computed.
const app = (window.crestline = { results: [], params, parameters: table, lastResult: null, fields: null, mesh: null });

const viewer = new Viewer(document.getElementById('view'), {
  onContextLost: () => fail('The WebGL context was lost (the GPU was reset or ran out of memory); the view returns when the browser restores it.'),
  onContextRestored: () => showError(null),
});

const brush = new WeightBrush(viewer, { onStroke: () => compute() });
/** What the worker gets: the panel's values and the brushed weights (a copy: it is transferred). */
const currentOptions = () => ({ ...pipelineOptions(params, table), vertexWeights: brush.current()?.slice() ?? null });

let rescaleThreshold = false;

const client = connection.session({
  onProgress: (stage, fraction) => showProgress(stage, overallFraction(stage, fraction)),
  onLoaded: ({ name, vertices, triangles, notes, milliseconds }) => {
    app.mesh = { name, vertices, triangles, loadMs: milliseconds }; // reading (C++) and repair
    showFile(`${name}: ${triangles.toLocaleString()} triangles`);
    showNotes([app.ignored, ...notes].filter(Boolean));
  },
  onResult: (result) => {
    if (result.surface) {
      viewer.setSurface(result.surface, { fit: !app.surfaceShown });
      app.surfaceShown = true;
      brush.reset(result.surface.positions.length / 3);
    }
    const started = performance.now();
    if (result.linesChanged) viewer.setLines(result.lines, result.kept);
    else viewer.setKept(result.kept);
    if (result.creasesChanged && result.creases) viewer.setCreases(result.creases);
    const drawMs = performance.now() - started; // main-thread work to show the result's lines
    const { lines, kept } = result;
    let selected = null;
    // What the exports save: the lines shown, selected on first use.
    app.shown = { name: app.mesh?.name, get lines() { return (selected ??= selectLines(lines, kept)); } };
    app.lastResult = { name: app.mesh?.name, ran: result.ran, stats: result.stats, lineCount: kept.length, linesChanged: result.linesChanged, creaseCount: result.creases?.convex.length ?? 0, drawMs, milliseconds: result.milliseconds };
    app.results.push(app.lastResult);
    gui.showUsed(result.stats, rescaleThreshold);
    rescaleThreshold = false;
    showStats(result, app.mesh);
    showProgress(null);
    showError(null); // a good result supersedes an earlier failure
    const upstream = ['presmooth', 'curvature', 'extremality', 'regularity', 'smoothing'];
    if (result.ran.some((s) => upstream.includes(s))) app.fields = null;
    if (!client.busy) {
      setState('ready');
      applyView();
    }
  },
  onFields: (fields) => {
    app.fields = fields;
    applyView();
  },
  onCancelled: () => {
    showProgress(null);
    setState('ready');
    showNotes(['Cancelled: change a parameter to compute again.']);
  },
  // A file that could not be read never replaced the worker's mesh, which stays usable.
  onError: ({ message }) => {
    fail(message);
    if (app.previous && client.hasMesh) Object.assign(app, app.previous);
    app.previous = null;
  },
});

function fail(message) {
  showProgress(null);
  showError(message);
  setState('error');
}

/** Runs with the panel's options (the client queues them behind a running job). */
function compute() {
  if (!app.mesh) return;
  setState('busy');
  client.setOptions(currentOptions());
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

/** Colour map or singular-triangle overlay; fetches fields from the worker when needed. */
function applyView() {
  const view = params.view;
  if (view === 'weights' && brush.weights) {
    viewer.surface.setSingular(null);
    viewer.surface.setColors(brush.weights.map((w) => w - 1));
  } else if (view === 'shaded' || view === 'weights' || !app.mesh) {
    viewer.surface.setColors(null);
    viewer.surface.setSingular(null);
  } else if (!app.fields) {
    if (!client.busy) client.requestFields();
    return;
  } else if (view.startsWith('singular')) {
    viewer.surface.setColors(null);
    viewer.surface.setSingular(view === 'singularMax' ? app.fields.regularMax : app.fields.regularMin);
  } else {
    viewer.surface.setSingular(null);
    // An extremality's sign follows the arbitrary sign of its direction
    // (core/…/extremality.h): only |e| means something on its own.
    const values = app.fields[view];
    viewer.surface.setColors(view.startsWith('e') ? values.map(Math.abs) : values);
  }
  viewer.render();
}

const exporter = createExports({ viewer, client, params, current: () => app.shown });

const picker = /** @type {HTMLInputElement} */ (document.getElementById('picker'));
picker.accept = PICKER_ACCEPT;
const gui = createGui(params, table, {
  onCompute: compute,
  onDisplay: applyDisplay,
  onFit: () => viewer.fitView(),
  onOpen: () => picker.click(),
  onBrush: () => {
    brush.setEnabled(params.brush);
    brush.radius = params.brushRadius;
    brush.value = params.brushValue;
    if (params.brush && params.view !== 'weights') app.update({ view: 'weights' });
  },
  onClearWeights: () => {
    brush.clear();
    applyView();
    compute();
  },
  onExport: (format) => app.save(format),
});

/** A new mesh: state reset, then `send` starts the worker on it. */
function startMesh(name, send) {
  app.previous = { mesh: app.mesh, surfaceShown: true };
  showError(null);
  showNotes([]);
  app.ignored = null;
  setState('busy');
  app.fields = null;
  app.surfaceShown = false; // the next surface is framed
  app.mesh = { name };
  rescaleThreshold = true;
  brush.weights = null; // a new mesh starts homogeneous
  send({ ...pipelineOptions(params, table), vertexWeights: null });
}

/** The built-in sample, already a soup. */
function loadSoup(soup) {
  startMesh(soup.name, (options) => client.load(soup, options));
}

/** Dropped or picked files: read by the C++ readers in the worker, so the page never blocks. */
async function openFiles(fileList) {
  if (!fileList.length) return;
  try {
    const all = await Promise.all(fileList.map(async (f) => ({ name: f.name, bytes: await f.arrayBuffer() })));
    const { read: files, ignored } = selectFiles(all);
    startMesh(files[0].name, (options) => client.open(files, options));
    app.ignored = ignoredSentence(files[0].name, ignored);
    showNotes([app.ignored].filter(Boolean));
  } catch (error) {
    fail(`${fileList[0].name}: could not be read (${error.message}).`);
  }
}

// Test hooks: change parameters as the panel would.
app.viewer = viewer;
app.client = client;
app.gui = gui.gui;
/** Makes and downloads an export (the panel's buttons); failures show on the page. */
app.save = (format) =>
  exporter.save(format).catch((error) => {
    showError(`Export ${format.toUpperCase()}: ${error.message}`);
    return null;
  });
app.brush = brush;
app.update = (partial) => {
  Object.assign(params, partial);
  gui.gui.controllersRecursive().forEach((c) => c.updateDisplay());
  const pipelineKeys = pipelineParameters(table).flatMap((p) => [p.key, autoKey(p)]);
  if (Object.keys(partial).some((k) => pipelineKeys.includes(k))) compute();
  else applyDisplay();
};

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
document.getElementById('cancel').addEventListener('click', () => client.cancel());
applyDisplay();
loadSoup(sampleMesh());
