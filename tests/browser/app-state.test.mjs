// The page's one state (issue 17, items 1–2): mesh A is shown, file B is
// dropped; while B is read, the header names B and the picture, stats and
// exports stay A's, labelled as the previous mesh, and Cancel gives A's page
// back whole (the same header, stats, picture and byte-identical OBJ export).
// Once B is loaded (repaired) its surface is shown at once, lines pending;
// Cancel from then on — once it is loaded, at the start of each pipeline
// stage — keeps B without lines (header, stats and exports say so), and a
// changed setting computes them. An export error clears when a later action
// succeeds. Generated meshes, so it is quick. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { dropFiles, nextResult, useApp } from './app-page.mjs';
import { sineHeightField } from '../node/helpers.mjs';
import { STAGES } from '../../web/src/worker/protocol.js';

/** A soup as OBJ text. */
function objText({ positions, indices }) {
  const lines = [];
  for (let i = 0; i < positions.length; i += 3) lines.push(`v ${positions[i]} ${positions[i + 1]} ${positions[i + 2]}`);
  for (let i = 0; i < indices.length; i += 3) lines.push(`f ${indices[i] + 1} ${indices[i + 1] + 1} ${indices[i + 2] + 1}`);
  return `${lines.join('\n')}\n`;
}

const A = { name: 'hills.obj', text: objText(sineHeightField({ n: 48 })) }; // 4,608 triangles
const B = { name: 'waves.obj', text: objText(sineHeightField({ n: 110 })) }; // 24,200 triangles
const app = useApp({}, { acceptDownloads: true });

/** Every view of the page: header, label, state, error, stats, the picture's mesh and lines (as the next frame draws them). */
const views = () =>
  app.page.evaluate(async () => {
    const { viewer } = window.crestline;
    // New lines get their geometry when drawn (the level of detail of the frame's view).
    await new Promise((resolve) => viewer.afterFrame(resolve));
    const text = (id) => document.getElementById(id).textContent;
    return {
      state: document.body.dataset.state,
      header: document.getElementById('file').firstChild.textContent,
      label: document.getElementById('view-label').hidden ? '' : text('view-label'),
      dimmed: document.body.classList.contains('previous'),
      error: text('error'),
      progress: !document.getElementById('progress').hidden,
      stats: text('stats'),
      surfaceVertices: viewer.surface.mesh.geometry.getAttribute('position').count,
      linePoints: viewer.lines.group.children.reduce((n, o) => n + (o.geometry.segmentCount ?? 0), 0),
    };
  });

/** An export made as the panel's button does: {fileName, text} or the error line. */
const save = (format) =>
  app.page.evaluate(async (format) => {
    const saved = await window.crestline.save(format);
    return saved
      ? { fileName: saved.fileName, text: format === 'png' ? '' : await saved.blob.text() }
      : { error: document.getElementById('error').textContent };
  }, format);

let shownA, objA;

/** How many workers the page's connection started (1: never restarted). */
const workerGeneration = () => app.page.evaluate(() => window.crestline.client.connection.generation);

test('mesh A loaded: its header, stats, picture and exports agree', async () => {
  const result = await nextResult(app.page, () => dropFiles(app.page, [A]));
  assert.equal(result.name, 'hills.obj');
  assert.equal(result.stats.triangles, 4608);
  shownA = await views();
  assert.equal(shownA.state, 'ready');
  assert.match(shownA.header, /^hills\.obj: 4,608 triangles — /);
  assert.equal(shownA.label, '');
  assert.match(shownA.stats, /^hills\.obj\n.*4,608 triangles/);
  assert.equal(shownA.surfaceVertices, result.stats.vertices);
  assert.ok(shownA.linePoints > 0, 'lines drawn');
  const obj = await save('obj');
  assert.equal(obj.fileName, 'hills-lines.obj');
  objA = obj.text;
  assert.match(objA, /^o ridges$/m);
});

/** Drops `file` (B) and cancels when `hook` ('read' | 'loaded' | a pipeline stage) is reached. */
async function dropAndCancelAt(hook, file = B) {
  const count = await app.page.evaluate(() => window.crestline.results.length);
  await app.page.evaluate((hook) => {
    const { hooks } = window.crestline;
    const cancelNow = () => {
      hooks.progress = hooks.loaded = null;
      // What the page shows at the moment of Cancel (B loading, A in view).
      window.beforeCancel = {
        state: document.body.dataset.state,
        header: document.getElementById('file').firstChild.textContent,
        label: document.getElementById('view-label').textContent,
        canvas: (({ opacity, filter, transitionDuration }) => ({ opacity, filter, transitionDuration }))(
          getComputedStyle(document.querySelector('#view canvas')),
        ),
        at: performance.now(),
      };
      document.getElementById('cancel').click();
    };
    if (hook === 'loaded') hooks.loaded = cancelNow;
    else hooks.progress = (stage) => stage === hook && cancelNow();
  }, hook);
  await dropFiles(app.page, [file]);
  await app.page.waitForFunction(() => window.beforeCancel, null, { timeout: 30000 });
  const before = await app.page.evaluate(() => window.beforeCancel);
  await app.page.evaluate(() => delete window.beforeCancel);
  return { before, count };
}

test("Cancel while B is read: A's page comes back whole", async () => {
  const { before, count } = await dropAndCancelAt('read');
  assert.equal(before.state, 'loading');
  assert.match(before.header, /^waves\.obj: reading…/);
  assert.equal(before.label, 'Previous mesh: hills.obj (shown until waves.obj is read)');
  // Dimmed by opacity alone, at once: no filter pass or fade for the compositor to redraw in every frame.
  assert.deepEqual(before.canvas, { opacity: '0.45', filter: 'none', transitionDuration: '0s' });
  const after = await views();
  assert.deepEqual({ ...after }, { ...shownA }, "header, state, stats, picture: A's");
  assert.match(await app.page.textContent('#notes'), /^Cancelled waves\.obj: back to hills\.obj\.$/);
  // The worker still holds A: its core writer gives the same lines, byte for byte.
  const obj = await save('obj');
  assert.equal(obj.fileName, 'hills-lines.obj');
  assert.equal(obj.text, objA);
  assert.equal((await save('svg')).fileName, 'hills-lines.svg');
  // Nothing of B arrives later.
  await app.page.waitForTimeout(300);
  assert.equal(await app.page.evaluate(() => window.crestline.results.length), count);
  assert.deepEqual(await views(), shownA);
});

/** Drops A again (its lines shown), as the start of each of the next tests. */
async function showA() {
  await nextResult(app.page, () => dropFiles(app.page, [A]));
  // The same page as A's first time, but for the times measured.
  const untimed = (v) => ({ ...v, stats: v.stats.replace(/^(ran|read and repair).*$/gm, '') });
  assert.deepEqual(untimed(await views()), untimed(shownA));
}

const B_VERTICES = 111 * 111;

// Once B is loaded: at 'loaded' and the start of each pipeline stage.
for (const hook of ['loaded', ...STAGES]) {
  test(`Cancel once B is loaded, at "${hook}": B stays shown without lines, and a setting computes them`, async () => {
    await showA();
    const { before, count } = await dropAndCancelAt(hook);
    assert.equal(before.state, 'computing');
    assert.match(before.header, /^waves\.obj: 24,200 triangles, computing its lines… — /);
    assert.equal(before.label, '', 'B is shown, not labelled');
    await app.page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30000 });
    const after = await views();
    assert.deepEqual(after, {
      state: 'ready',
      header: 'waves.obj: 24,200 triangles, lines not computed — drop another mesh or ',
      label: '',
      dimmed: false,
      error: '',
      progress: false,
      stats: after.stats,
      surfaceVertices: B_VERTICES,
      linePoints: 0,
    });
    assert.match(
      after.stats,
      /^waves\.obj\n12,321 vertices, 24,200 triangles\nlines: not computed \(cancelled; change a setting to compute them\)\nread and repair \d+ ms$/,
    );
    assert.equal(await app.page.textContent('#notes'), 'Cancelled: waves.obj has no lines yet; change a setting to compute them.');
    assert.equal(await app.page.evaluate(() => window.crestline.results.length), count, 'no result of B');
    assert.equal(await workerGeneration(), 1, 'the pipeline saw the cancel flag: the worker was not restarted');
    // Exports say plainly that there are no lines (A is gone).
    for (const format of ['obj', 'svg']) {
      assert.deepEqual(await save(format), {
        error: `Export ${format.toUpperCase()}: Nothing to export yet: the lines of waves.obj are not computed (cancelled); change a setting to compute them.`,
      });
    }
    // A changed setting computes B's lines (every line, though some stages ran before the cancel).
    const result = await nextResult(app.page, () => app.page.evaluate(() => window.crestline.update({ threshold: window.crestline.params.threshold * 1.01 })));
    assert.equal(result.name, 'waves.obj');
    assert.ok(result.lineCount > 0, 'lines kept');
    const now = await views();
    assert.equal(now.state, 'ready');
    assert.match(now.header, /^waves\.obj: 24,200 triangles — /);
    assert.ok(now.linePoints > 0, 'lines drawn');
    assert.equal((await save('obj')).fileName, 'waves-lines.obj');
    assert.equal(await app.page.textContent('#error'), '', 'the export error cleared');
  });
}

test("while B is read: A labelled and dimmed, exports A's; once loaded: B's surface, counts, lines pending; then all B", async () => {
  await showA();
  await app.page.evaluate(() => {
    const { hooks, viewer } = window.crestline;
    const text = (id) => document.getElementById(id).textContent;
    const look = () => ({
      state: document.body.dataset.state,
      header: document.getElementById('file').firstChild.textContent,
      label: text('view-label'),
      dimmed: document.body.classList.contains('previous'),
      stats: text('stats'),
      surfaceVertices: viewer.surface.mesh.geometry.getAttribute('position').count,
      results: window.crestline.results.length,
    });
    hooks.progress = async (stage) => {
      if (stage !== 'read') return;
      hooks.progress = null;
      window.reading = look();
      window.reading.svg = (await window.crestline.save('svg'))?.fileName;
    };
    hooks.loaded = async () => {
      hooks.loaded = null;
      window.loaded = look();
      window.loaded.svg = (await window.crestline.save('svg'))?.fileName ?? text('error');
    };
  });
  const count = await app.page.evaluate(() => window.crestline.results.length);
  const result = await nextResult(app.page, () => dropFiles(app.page, [B]));
  const { reading, loaded } = await app.page.evaluate(() => ({ reading: window.reading, loaded: window.loaded }));
  assert.equal(reading.state, 'loading');
  assert.match(reading.header, /^waves\.obj: reading… — /);
  assert.equal(reading.label, 'Previous mesh: hills.obj (shown until waves.obj is read)');
  assert.equal(reading.dimmed, true);
  assert.match(reading.stats, /^hills\.obj\n/, "the stats are A's, named");
  assert.equal(reading.surfaceVertices, shownA.surfaceVertices);
  assert.equal(reading.svg, 'hills-lines.svg', "an export while B is read is A's, as the label says");
  // Loaded: B's surface is in the picture before any of its lines.
  assert.deepEqual(
    { ...loaded, stats: '' },
    {
      state: 'computing',
      header: 'waves.obj: 24,200 triangles, computing its lines… — drop another mesh or ',
      label: '',
      dimmed: false,
      stats: '',
      surfaceVertices: B_VERTICES,
      results: count,
      svg: 'Export SVG: Nothing to export yet: wait for the lines of waves.obj (or Cancel).',
    },
  );
  assert.match(loaded.stats, /^waves\.obj\n12,321 vertices, 24,200 triangles\nlines: computing…\n/);
  await app.page.evaluate(() => window.crestline.save('svg')); // clears the export error
  assert.equal(result.name, 'waves.obj');
  const now = await views();
  assert.equal(now.state, 'ready');
  assert.match(now.header, /^waves\.obj: 24,200 triangles — /);
  assert.equal(now.label, '');
  assert.equal(now.dimmed, false);
  assert.match(now.stats, /^waves\.obj\n/);
  assert.equal(now.surfaceVertices, result.stats.vertices);
  assert.equal((await save('obj')).fileName, 'waves-lines.obj');
});

/** Changes the smoothing steps by `delta` and presses Cancel at once (the worker sees the flag at its first check). */
const recomputeAndCancel = (delta, between = async () => null) =>
  app.page.evaluate(
    async ([delta, between]) => {
      window.crestline.update({ smoothingSteps: window.crestline.params.smoothingSteps + delta });
      const state = document.body.dataset.state;
      const inBetween = await eval(between)();
      document.getElementById('cancel').click();
      return { state, inBetween };
    },
    [delta, between.toString()],
  );

test('Cancel of a recompute: the lines, stats, panel and exports stay those of the lines shown', async () => {
  const before = await views();
  const obj = (await save('obj')).text;
  const steps = await app.page.evaluate(() => window.crestline.params.smoothingSteps);
  const count = await app.page.evaluate(() => window.crestline.results.length);
  const { state } = await recomputeAndCancel(3);
  assert.equal(state, 'computing');
  await app.page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30000 });
  assert.equal(await app.page.evaluate(() => window.crestline.results.length), count, 'no new result');
  assert.equal(await app.page.evaluate(() => window.crestline.params.smoothingSteps), steps, 'the panel shows the value of the lines shown');
  assert.deepEqual(await views(), before);
  assert.match(await app.page.textContent('#notes'), /^Cancelled/);
  // The OBJ export is the lines shown (the worker re-runs what the cancel left half done).
  assert.equal((await save('obj')).text, obj);
  assert.equal(await app.page.evaluate(() => window.crestline.params.smoothingSteps), steps);
});

test('an export refused while lines are recomputed stays on screen until the next export succeeds', async () => {
  const { inBetween } = await recomputeAndCancel(2, async () => {
    await window.crestline.save('obj');
    return document.getElementById('error').textContent;
  });
  assert.equal(inBetween, 'Export OBJ: Nothing to export yet: wait for the new lines of waves.obj (or Cancel).');
  await app.page.waitForFunction(() => document.body.dataset.state === 'error', null, { timeout: 30000 });
  assert.equal(await app.page.textContent('#error'), inBetween, 'the cancel does not hide the failure');
  const saved = await save('svg');
  assert.equal(saved.fileName, 'waves-lines.svg');
  assert.equal(await app.page.textContent('#error'), '');
  assert.equal(await app.page.evaluate(() => document.body.dataset.state), 'ready');
});

// The core checks the flag inside the smoothing solver's iterations (issue 15, item 7): a cancel
// there stops the stage itself, and the same worker computes the mesh's lines afterwards.
test('Cancel inside the smoothing of a 180,000-triangle mesh: it stops there, without a worker restart, and the same worker computes again', async () => {
  // The most smoothing steps with a 50-times time step (several times the solver's iterations), so
  // the Cancel, pressed when the page sees the stage begin, lands inside it: the page may be busy
  // drawing the new surface then (over a second in SwiftShader on a loaded machine, with the
  // worker's progress messages queued), and 50 default steps no longer outlast that.
  await nextResult(app.page, () => app.page.evaluate(() => window.crestline.update({ smoothingSteps: 50, smoothingTimeStep: 50 })));
  await app.page.evaluate(() => {
    const { connection } = window.crestline.client;
    const receive = connection.receive.bind(connection);
    window.replies = [];
    connection.receive = (message) => {
      window.replies.push({ type: message.type, stage: message.stage, at: performance.now() });
      receive(message);
    };
  });
  const C = { name: 'ripples.obj', text: objText(sineHeightField({ n: 300, wavelength: 0.5 })) };
  const { before } = await dropAndCancelAt('smoothing', C);
  assert.match(before.header, /^ripples\.obj: 180,000 triangles, computing its lines/);
  await app.page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30000 });
  const replies = await app.page.evaluate(() => window.replies);
  const cancelled = replies.findIndex((r) => r.type === 'cancelled');
  assert.ok(cancelled > 0, `the worker replied 'cancelled': ${replies.map((r) => `${r.type}:${r.stage}@${Math.round(r.at - before.at)}`).join(' ')}`);
  const stages = replies.slice(0, cancelled).filter((r) => r.type === 'progress');
  assert.equal(stages.at(-1).stage, 'smoothing', 'the last progress before the stop is the smoothing stage (no later stage began)');
  assert.equal(await workerGeneration(), 1, 'the worker was not restarted');
  console.log(`# cancel inside smoothing: 'cancelled' came ${(replies[cancelled].at - before.at).toFixed(0)} ms after the click`);
  const result = await nextResult(app.page, () => app.page.evaluate(() => window.crestline.update({ smoothingSteps: 3, smoothingTimeStep: 1 })));
  assert.equal(result.name, 'ripples.obj');
  assert.ok(result.ran.includes('smoothing') && result.lineCount > 0, `ran ${result.ran}, ${result.lineCount} lines`);
  assert.equal(await workerGeneration(), 1, 'computed in the same worker');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
