// The page's one state (issue 17, items 1–2): mesh A is shown, file B is
// dropped; while B loads, the header names B and the picture, stats and
// exports stay A's, labelled as the previous mesh; Cancel — while B is read,
// once it is loaded, at the start of each pipeline stage — gives A's page back
// whole (the same header, stats, picture and byte-identical OBJ export); an
// export error clears when a later action succeeds. Generated meshes, so it
// is quick. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { dropFiles, nextResult, openApp, sampleReady } from './app-page.mjs';
import { boxObj } from './box-obj.mjs';
import { sineHeightField } from '../node/helpers.mjs';
import { STAGES } from '../../web/src/worker/protocol.js';

/** A soup as OBJ text. */
function objText({ positions, indices }) {
  const lines = [];
  for (let i = 0; i < positions.length; i += 3) lines.push(`v ${positions[i]} ${positions[i + 1]} ${positions[i + 2]}`);
  for (let i = 0; i < indices.length; i += 3) lines.push(`f ${indices[i] + 1} ${indices[i + 1] + 1} ${indices[i + 2] + 1}`);
  return `${lines.join('\n')}\n`;
}

const A = { name: 'box.obj', text: boxObj() }; // 6,912 triangles
const B = { name: 'waves.obj', text: objText(sineHeightField({ n: 110 })) }; // 24,200 triangles
let app, page;

before(async () => {
  app = await openApp({}, { acceptDownloads: true });
  ({ page } = app);
  await sampleReady(page);
});

after(() => app?.close());

/** Every view of the page: header, label, state, error, stats, the picture's mesh and lines. */
const views = () =>
  page.evaluate(() => {
    const { viewer } = window.crestline;
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
      linePoints: viewer.lines.group.children.reduce((n, o) => n + (o.geometry.getAttribute('instanceStart')?.count ?? 0), 0),
    };
  });

/** An export made as the panel's button does: {fileName, text} or the error line. */
const save = (format) =>
  page.evaluate(async (format) => {
    const saved = await window.crestline.save(format);
    return saved ? { fileName: saved.fileName, text: format === 'png' ? '' : await saved.blob.text() } : { error: document.getElementById('error').textContent };
  }, format);

let shownA, objA;

test('mesh A loaded: its header, stats, picture and exports agree', async () => {
  const result = await nextResult(page, () => dropFiles(page, [A]));
  assert.equal(result.name, 'box.obj');
  assert.equal(result.stats.triangles, 6912);
  shownA = await views();
  assert.equal(shownA.state, 'ready');
  assert.match(shownA.header, /^box\.obj: 6,912 triangles — /);
  assert.equal(shownA.label, '');
  assert.match(shownA.stats, /^box\.obj\n.*6,912 triangles/);
  assert.equal(shownA.surfaceVertices, result.stats.vertices);
  assert.ok(shownA.linePoints > 0, 'lines drawn');
  const obj = await save('obj');
  assert.equal(obj.fileName, 'box-lines.obj');
  objA = obj.text;
  assert.match(objA, /^o ridges$/m);
});

/** Drops B and cancels when `hook` ('read' | 'loaded' | a pipeline stage) is reached. */
async function dropAndCancelAt(hook) {
  const count = await page.evaluate(() => window.crestline.results.length);
  await page.evaluate((hook) => {
    const { hooks } = window.crestline;
    const cancelNow = () => {
      hooks.progress = hooks.loaded = null;
      // What the page shows at the moment of Cancel (B loading, A in view).
      window.beforeCancel = { state: document.body.dataset.state, header: document.getElementById('file').firstChild.textContent, label: document.getElementById('view-label').textContent };
      document.getElementById('cancel').click();
    };
    if (hook === 'loaded') hooks.loaded = cancelNow;
    else hooks.progress = (stage) => stage === hook && cancelNow();
  }, hook);
  await dropFiles(page, [B]);
  await page.waitForFunction(() => window.beforeCancel, null, { timeout: 30000 });
  const before = await page.evaluate(() => window.beforeCancel);
  await page.evaluate(() => delete window.beforeCancel);
  return { before, count };
}

// Every point of a load: reading, loaded, and the start of each pipeline stage.
for (const hook of ['read', 'loaded', ...STAGES]) {
  test(`Cancel while B is at "${hook}": A's page comes back whole`, async () => {
    const { before, count } = await dropAndCancelAt(hook);
    assert.equal(before.state, 'loading');
    assert.match(before.header, hook === 'read' ? /^waves\.obj: reading…/ : /^waves\.obj: 24,200 triangles, computing its lines…/);
    assert.equal(before.label, 'Previous mesh: box.obj (shown until waves.obj is ready)');
    const after = await views();
    assert.deepEqual({ ...after }, { ...shownA }, 'header, state, stats, picture: A\'s');
    assert.match(await page.textContent('#notes'), /^Cancelled waves\.obj: back to box\.obj\.$/);
    // The worker still holds A: its core writer gives the same lines, byte for byte.
    const obj = await save('obj');
    assert.equal(obj.fileName, 'box-lines.obj');
    assert.equal(obj.text, objA);
    assert.equal((await save('svg')).fileName, 'box-lines.svg');
    // Nothing of B arrives later.
    await page.waitForTimeout(300);
    assert.equal(await page.evaluate(() => window.crestline.results.length), count);
    assert.deepEqual(await views(), shownA);
  });
}

test('while B loads: header B, picture and stats A labelled and dimmed, exports A\'s; then all B', async () => {
  await page.evaluate(() => {
    window.crestline.hooks.loaded = async () => {
      window.crestline.hooks.loaded = null;
      const text = (id) => document.getElementById(id).textContent;
      window.during = { state: document.body.dataset.state, header: text('file'), label: text('view-label'), dimmed: document.body.classList.contains('previous'), stats: text('stats') };
      window.during.svg = (await window.crestline.save('svg'))?.fileName;
    };
  });
  const result = await nextResult(page, () => dropFiles(page, [B]));
  const during = await page.evaluate(() => window.during);
  assert.equal(during.state, 'loading');
  assert.match(during.header, /^waves\.obj: 24,200 triangles, computing its lines… — /);
  assert.equal(during.label, 'Previous mesh: box.obj (shown until waves.obj is ready)');
  assert.equal(during.dimmed, true);
  assert.match(during.stats, /^box\.obj\n/, 'the stats are A\'s, named');
  assert.equal(during.svg, 'box-lines.svg', 'an export while B loads is A\'s, as the label says');
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
  page.evaluate(async ([delta, between]) => {
    window.crestline.update({ smoothingSteps: window.crestline.params.smoothingSteps + delta });
    const state = document.body.dataset.state;
    const inBetween = await eval(between)();
    document.getElementById('cancel').click();
    return { state, inBetween };
  }, [delta, between.toString()]);

test('Cancel of a recompute: the lines, stats, panel and exports stay those of the lines shown', async () => {
  const before = await views();
  const obj = (await save('obj')).text;
  const steps = await page.evaluate(() => window.crestline.params.smoothingSteps);
  const count = await page.evaluate(() => window.crestline.results.length);
  const { state } = await recomputeAndCancel(3);
  assert.equal(state, 'computing');
  await page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 30000 });
  assert.equal(await page.evaluate(() => window.crestline.results.length), count, 'no new result');
  assert.equal(await page.evaluate(() => window.crestline.params.smoothingSteps), steps, 'the panel shows the value of the lines shown');
  assert.deepEqual(await views(), before);
  assert.match(await page.textContent('#notes'), /^Cancelled/);
  // The OBJ export is the lines shown (the worker re-runs what the cancel left half done).
  assert.equal((await save('obj')).text, obj);
  assert.equal(await page.evaluate(() => window.crestline.params.smoothingSteps), steps);
});

test('an export refused while lines are recomputed stays on screen until the next export succeeds', async () => {
  const { inBetween } = await recomputeAndCancel(2, async () => {
    await window.crestline.save('obj');
    return document.getElementById('error').textContent;
  });
  assert.equal(inBetween, 'Export OBJ: Nothing to export yet: wait for the new lines of waves.obj (or Cancel).');
  await page.waitForFunction(() => document.body.dataset.state === 'error', null, { timeout: 30000 });
  assert.equal(await page.textContent('#error'), inBetween, 'the cancel does not hide the failure');
  const saved = await save('svg');
  assert.equal(saved.fileName, 'waves-lines.svg');
  assert.equal(await page.textContent('#error'), '');
  assert.equal(await page.evaluate(() => document.body.dataset.state), 'ready');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
