// The web app in headless Chromium: the bunny sample, dropped GLB / Draco GLB
// / multi-file glTF / OBJ files, line counts against the native CLI, line
// pixels in a screenshot, instant re-thresholding, and errors that the page
// survives. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';
import { dropFiles, nextResult as waitForResult, useApp } from './app-page.mjs';
import { concaveOctagonObj } from '../node/concave-octagons.mjs';
import { MESHES, NATIVE_CLI, ROOT, haveMeshes, haveNativeCli } from '../node/helpers.mjs';

const SHOTS = join(ROOT, 'test-results');
const noMeshes = !haveMeshes && `SKIPPED: ${MESHES} is absent`;
const app = useApp({ '/meshes/': MESHES }, {}, { sample: false });

const nextResult = (action, timeout) => waitForResult(app.page, action, timeout);
const drop = (files) => dropFiles(app.page, files);

function nativeStats(file) {
  const out = join(SHOTS, 'native-lines.obj');
  mkdirSync(SHOTS, { recursive: true });
  return JSON.parse(execFileSync(NATIVE_CLI, [join(MESHES, file), '-o', out, '--stats', '-q'], { encoding: 'utf8' }));
}

/** Pixels of the rendered canvas close to the ridge and valley colours. */
function linePixels() {
  return app.page.evaluate(async () => {
    const { viewer, params } = window.crestline;
    viewer.renderer.render(viewer.scene, viewer.camera);
    const source = viewer.renderer.domElement;
    const canvas = new OffscreenCanvas(source.width, source.height);
    const context = canvas.getContext('2d');
    context.drawImage(source, 0, 0);
    const { data } = context.getImageData(0, 0, source.width, source.height);
    const rgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
    const targets = [rgb(params.ridgeColor), rgb(params.valleyColor)];
    const counts = [0, 0];
    for (let i = 0; i < data.length; i += 4) {
      targets.forEach((t, k) => {
        if (Math.abs(data[i] - t[0]) + Math.abs(data[i + 1] - t[1]) + Math.abs(data[i + 2] - t[2]) < 40) counts[k]++;
      });
    }
    return { ridges: counts[0], valleys: counts[1] };
  });
}

async function checkAgainstNative(file, result) {
  if (!haveNativeCli) return console.log(`# SKIPPED native comparison: ${NATIVE_CLI} is not built`);
  const native = nativeStats(file);
  assert.equal(result.stats.triangles, native.triangles, `${file}: triangles after repair`);
  assert.equal(result.stats.ridges, native.ridges, `${file}: ridges`);
  assert.equal(result.stats.valleys, native.valleys, `${file}: valleys`);
}

test('the built-in bunny gets ridges and valleys on first load', async () => {
  await app.page.waitForFunction(() => window.crestline?.lastResult, null, { timeout: 60000 });
  const result = await app.page.evaluate(() => window.crestline.lastResult);
  assert.match(result.name, /bunny/);
  assert.ok(result.lineCount > 0, 'bunny lines');
  assert.equal(result.ran[0], 'presmooth', 'a load runs every stage');
});

test('the panel is made from Session.describe(): a control per pipeline parameter, its range and default', async () => {
  const mismatches = await app.page.evaluate(() => {
    const { parameters, params, gui } = window.crestline;
    const controllers = gui.controllersRecursive();
    const out = [];
    for (const p of parameters.filter((q) => q.group === 'pipeline' && q.stage)) {
      const c = controllers.find((k) => k.property === p.key);
      if (!c) {
        out.push(`${p.key}: no control`);
        continue;
      }
      // A Boolean (creaseBoundaries) is a checkbox: no range.
      if (p.min !== null && c._min !== p.min) out.push(`${p.key}: min ${c._min} ≠ ${p.min}`);
      if (Number.isFinite(p.max) && c._max !== p.max) out.push(`${p.key}: max ${c._max} ≠ ${p.max}`);
      const auto = controllers.find((k) => k.property === `auto${p.key[0].toUpperCase()}${p.key.slice(1)}`);
      if (p.automatic !== Boolean(auto)) out.push(`${p.key}: automatic ${p.automatic}, switch ${Boolean(auto)}`);
      if (p.default === 'auto' ? !auto?.getValue() : params[p.key] !== p.default) out.push(`${p.key}: default ${p.default}, panel ${params[p.key]}`);
    }
    return out;
  });
  assert.deepEqual(mismatches, []);
  assert.ok(await app.page.evaluate(() => window.crestline.parameters.some((p) => p.key === 'threshold' && p.automatic)));
});

test('GLB (feline): lines match the native CLI and are drawn', { skip: noMeshes }, async () => {
  const result = await nextResult(() => drop(['glb/feline.glb']));
  assert.equal(result.name, 'feline.glb');
  await checkAgainstNative('glb/feline.glb', result);
  const pixels = await linePixels();
  mkdirSync(SHOTS, { recursive: true });
  await app.page.screenshot({ path: join(SHOTS, 'feline.png') });
  assert.ok(pixels.ridges > 200 && pixels.valleys > 200, `line pixels: ${JSON.stringify(pixels)}`);
});

test('threshold change re-filters only, and changes the count', { skip: noMeshes }, async () => {
  const before = await app.page.evaluate(() => window.crestline.lastResult);
  // The ridge geometry before: a threshold change must keep it and only hide lines.
  await app.page.evaluate(() => (window.ridgeGeometry = window.crestline.viewer.lines.objects[0].geometry));
  const pixelsBefore = await linePixels();
  const result = await nextResult(() => app.page.evaluate((t) => window.crestline.update({ autoThreshold: false, threshold: t }), before.stats.threshold * 3));
  assert.deepEqual(result.ran, ['filter'], 'only the filter ran');
  assert.ok(result.lineCount < before.lineCount, `${result.lineCount} < ${before.lineCount} lines`);
  assert.equal(result.linesChanged, false, 'no lines were sent');
  assert.ok(await app.page.evaluate(() => window.crestline.viewer.lines.objects[0].geometry === window.ridgeGeometry), 'the geometry was not rebuilt');
  const pixelsAfter = await linePixels();
  assert.ok(pixelsAfter.ridges < pixelsBefore.ridges, `fewer ridge pixels: ${pixelsAfter.ridges} < ${pixelsBefore.ridges}`);
  console.log(`# re-threshold on ${before.stats.triangles} triangles: ${result.milliseconds.toFixed(1)} ms in the worker`);
  const smoothed = await nextResult(() => app.page.evaluate(() => window.crestline.update({ autoThreshold: true, smoothingSteps: 4 })));
  assert.equal(smoothed.ran[0], 'smoothing', 'a smoothing change re-runs from smoothing on');
  assert.ok(!smoothed.ran.includes('curvature'));
  const camera = () => app.page.evaluate(() => window.crestline.viewer.camera.position.toArray());
  const view = await camera();
  const presmoothed = await nextResult(() =>
    app.page.evaluate(() => window.crestline.update({ smoothingSteps: 3, autoPresmoothSteps: false, presmoothSteps: 1 })),
  );
  assert.equal(presmoothed.ran[0], 'presmooth');
  assert.deepEqual(await camera(), view, 'a new surface of the same mesh keeps the view');
  await nextResult(() => app.page.evaluate(() => window.crestline.update({ autoPresmoothSteps: true })));
});

test('a broken file and an unsupported one: one sentence each, and the page recovers', async () => {
  await drop([{ name: 'broken.glb', text: 'glTF this is not a binary glTF' }]);
  await app.page.waitForFunction(() => document.body.dataset.state === 'error');
  assert.match(await app.page.textContent('#error'), /^broken\.glb: only GLB version 2 is supported/);
  await drop([{ name: 'readme.txt', text: 'hello' }]);
  await app.page.waitForFunction(() => /readme/.test(document.getElementById('error').textContent));
  assert.match(await app.page.textContent('#error'), /^readme\.txt: the format is not recognised/);
  // The previous mesh is still loaded and re-filters without a recompute.
  const previous = await app.page.evaluate(() => window.crestline.lastResult);
  const result = await nextResult(() =>
    app.page.evaluate((t) => window.crestline.update({ autoThreshold: false, threshold: t }), previous.stats.threshold * 0.9),
  );
  assert.equal(result.name, previous.name);
  assert.deepEqual(result.ran, ['filter']);
  await nextResult(() => app.page.evaluate(() => window.crestline.update({ autoThreshold: true })));
});

test('OBJ (mannequin): lines match the native CLI', { skip: noMeshes }, async () => {
  const result = await nextResult(() => drop(['classic/mannequin.obj']));
  assert.equal(result.name, 'mannequin.obj');
  await checkAgainstNative('classic/mannequin.obj', result);
});

test(
  "concave L-shaped octagons (OBJ polygons): the C++ reader in the page gives the CLI's lines, byte for byte",
  { skip: !haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built` },
  async () => {
    const text = concaveOctagonObj();
    mkdirSync(SHOTS, { recursive: true });
    const input = join(SHOTS, 'concave-octagons.obj');
    const output = join(SHOTS, 'concave-octagons-lines.obj');
    writeFileSync(input, text);
    execFileSync(NATIVE_CLI, [input, '-o', output, '-q']);
    const result = await nextResult(() => drop([{ name: 'concave-octagons.obj', text }]));
    assert.ok(result.stats.ridges > 0 && result.stats.valleys > 0, JSON.stringify(result.stats));
    const obj = await app.page.evaluate(() => window.crestline.client.exportText('obj'));
    assert.equal(obj, readFileSync(output, 'utf8'));
  },
);

test('Draco GLB (pmndrs bunny): decompressed in the worker by the npm decoders, lines match the native CLI', { skip: noMeshes }, async () => {
  const result = await nextResult(() => drop(['glb/pmndrs-bunny-draco.glb']));
  assert.equal(result.name, 'pmndrs-bunny-draco.glb');
  await checkAgainstNative('glb/pmndrs-bunny-draco.glb', result);
});

test('multi-file glTF dropped together (Duck.gltf + .bin + texture)', { skip: noMeshes }, async () => {
  const result = await nextResult(() => drop(['gltf/Duck/Duck.gltf', 'gltf/Duck/Duck0.bin', 'gltf/Duck/DuckCM.png']));
  assert.equal(result.name, 'Duck.gltf');
  assert.equal(result.stats.triangles, 4212);
  await checkAgainstNative('gltf/Duck/Duck.gltf', result);
});

test('curvature colour map and singular triangles views', async () => {
  await app.page.evaluate(() => window.crestline.update({ view: 'kappaMax' }));
  await app.page.waitForFunction(() => window.crestline.fields && window.crestline.viewer.surface.material.vertexColors);
  const colours = await app.page.evaluate(() => window.crestline.viewer.surface.mesh.geometry.getAttribute('color').count);
  assert.equal(colours, await app.page.evaluate(() => window.crestline.lastResult.stats.vertices));
  await app.page.evaluate(() => window.crestline.update({ view: 'singularMax' }));
  const singular = await app.page.evaluate(() => window.crestline.viewer.surface.singular.geometry.index.count / 3);
  assert.equal(singular, await app.page.evaluate(() => window.crestline.lastResult.stats.singularMax));
  await app.page.evaluate(() => window.crestline.update({ view: 'shaded' }));
});

test('smoothing brush: painting frozen weights re-runs from the smoothing stage', async () => {
  const before = await app.page.evaluate(() => window.crestline.lastResult);
  await app.page.evaluate(async () => {
    const { brush } = window.crestline;
    brush.setEnabled(true);
    brush.radius = 0.6;
    brush.value = 0;
    await brush.ready(); // the surface index, built in a worker
  });
  const box = await app.page.locator('#view canvas').boundingBox();
  const result = await nextResult(async () => {
    await app.page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
    await app.page.mouse.down();
    await app.page.mouse.move(box.x + box.width * 0.55, box.y + box.height * 0.45, { steps: 4 });
    await app.page.mouse.up();
  });
  assert.equal(result.ran[0], 'smoothing', `ran ${result.ran}`);
  assert.ok(!result.ran.includes('curvature'));
  const frozen = await app.page.evaluate(() => window.crestline.brush.weights.filter((w) => w < 0.5).length);
  assert.ok(frozen > 0, 'some vertices were painted');
  assert.notDeepEqual(
    [result.stats.ridges, result.stats.valleys, result.stats.ridgeLength],
    [before.stats.ridges, before.stats.valleys, before.stats.ridgeLength],
  );
  await app.page.evaluate(() => window.crestline.brush.setEnabled(false));
});

test('the file picker opens an OFF file (an octahedron)', async () => {
  mkdirSync(SHOTS, { recursive: true });
  const path = join(SHOTS, 'octahedron.off');
  writeFileSync(path, 'OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n' + '3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n');
  const result = await nextResult(() => app.page.setInputFiles('#picker', path));
  assert.equal(result.name, 'octahedron.off');
  assert.equal(result.stats.triangles, 8);
});

test('cancel stops a long computation and the page stays usable', { skip: noMeshes }, async () => {
  // The stage is seen through the page's progress hook: polling the text could miss it while the
  // page draws the dragon's surface (shown as soon as it is loaded). The most smoothing steps keep
  // the stage running well past the second measured below: in SwiftShader on a loaded machine the
  // surface's first frame holds the page's main thread for seconds (the worker's progress queues
  // behind it), and 3 steps could end before the Cancel.
  await nextResult(() => app.page.evaluate(() => window.crestline.update({ smoothingSteps: 50 })));
  await app.page.evaluate(() => (window.crestline.hooks.progress = (stage) => stage === 'smoothing' && (window.sawSmoothing = true)));
  await drop(['large/dragon-draco.glb']);
  await app.page.waitForFunction(() => window.sawSmoothing, null, { timeout: 60000 });
  await app.page.evaluate(() => (window.crestline.hooks.progress = null));
  // The main thread keeps drawing frames while the worker computes: frames
  // are counted within one second of computing (no time is asserted; the
  // longest frame is printed).
  const frames = await app.page.evaluate(
    () =>
      new Promise((resolve) => {
        let last = performance.now();
        let longest = 0;
        let count = 0;
        const end = last + 1000;
        const tick = (now) => {
          longest = Math.max(longest, now - last);
          last = now;
          count += 1;
          if (now < end) requestAnimationFrame(tick);
          else resolve({ count, longest, state: document.body.dataset.state });
        };
        requestAnimationFrame(tick);
      }),
  );
  console.log(`# frames while computing: ${frames.count} in 1 s, longest ${frames.longest.toFixed(0)} ms`);
  assert.equal(frames.state, 'computing', 'the pipeline was still running when the frames were counted');
  assert.ok(frames.count >= 3, `the page drew ${frames.count} frames in one second of computing`);
  const started = Date.now();
  await app.page.evaluate(() => (window.workerBeforeCancel = window.crestline.client.connection.worker));
  await app.page.click('#cancel');
  await app.page.waitForFunction(() => document.body.dataset.state === 'ready', null, { timeout: 10000 });
  console.log(`# cancel during smoothing took effect after ${Date.now() - started} ms`);
  assert.match(await app.page.textContent('#notes'), /Cancelled/);
  // The pipeline saw the shared flag inside the stage: no worker restart (which
  // would follow after CANCEL_GRACE_MS), the worker keeps its module.
  assert.ok(await app.page.evaluate(() => window.crestline.client.connection.worker === window.workerBeforeCancel), 'the worker was not restarted');
  const result = await nextResult(() => drop(['classic/mannequin.obj']));
  assert.equal(result.name, 'mannequin.obj');
});

test('a lost WebGL context is one sentence; the view comes back on restore', async () => {
  await app.page.evaluate(() => {
    const gl = window.crestline.viewer.renderer.getContext();
    window.loseContext = gl.getExtension('WEBGL_lose_context');
    window.loseContext.loseContext();
  });
  await app.page.waitForFunction(() => document.body.dataset.state === 'error');
  assert.match(await app.page.textContent('#error'), /WebGL context was lost/);
  await app.page.evaluate(() => window.loseContext.restoreContext());
  await app.page.waitForFunction(() => document.getElementById('error').textContent === '');
  const pixels = await linePixels();
  assert.ok(pixels.ridges > 50, `line pixels after restore: ${JSON.stringify(pixels)}`);
});

// The acceptance mesh, the whole pipeline with default parameters.
test('871k triangles (large/dragon.glb): lines, then an instant re-threshold', { skip: noMeshes }, async () => {
  await nextResult(() => app.page.evaluate(() => window.crestline.update({ smoothingSteps: 3, autoThreshold: true })));
  const started = Date.now();
  const result = await nextResult(() => drop(['large/dragon.glb']), 150000);
  assert.equal(result.name, 'dragon.glb');
  assert.equal(result.stats.triangles, 871298);
  assert.ok(result.lineCount > 100);
  const mesh = await app.page.evaluate(() => window.crestline.mesh);
  console.log(
    `# dragon.glb: drop to lines ${Date.now() - started} ms: read and repair ${mesh.loadMs.toFixed(0)} ms, ` + `pipeline ${result.milliseconds.toFixed(0)} ms`,
  );
  await checkAgainstNative('large/dragon.glb', result);
  // What crosses the worker boundary for a threshold change (typed arrays' bytes plus the JSON of
  // the rest, both ways), and the page's main-thread work on the replies and in the frame after.
  const lines = await app.page.evaluate(() => {
    const { connection, lines } = window.crestline.client;
    const bytesOf = (message) => {
      let arrays = 0;
      const json = JSON.stringify(message, (_key, value) => (ArrayBuffer.isView(value) ? ((arrays += value.byteLength), undefined) : value));
      return arrays + json.length;
    };
    const traffic = (window.traffic = { posted: 0, received: 0, replies: 0, renders: 0 });
    const [post, receive] = [connection.post.bind(connection), connection.receive.bind(connection)];
    connection.post = (message) => ((traffic.posted += bytesOf(message)), post(message));
    connection.receive = (message) => {
      traffic.received += bytesOf(message);
      const started = performance.now();
      receive(message);
      traffic.replies += performance.now() - started;
    };
    const { renderer } = window.crestline.viewer;
    const render = renderer.render.bind(renderer);
    renderer.render = (...args) => {
      const started = performance.now();
      render(...args);
      traffic.renders += performance.now() - started;
    };
    return { count: lines.types.length, pointBytes: lines.points.byteLength };
  });
  const filtered = await nextResult(() => app.page.evaluate(() => window.crestline.update({ autoThreshold: false, threshold: 3 })));
  await app.page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
  const traffic = await app.page.evaluate(() => window.traffic);
  assert.deepEqual(filtered.ran, ['filter']);
  assert.equal(filtered.linesChanged, false, 'a threshold change sends no lines');
  assert.ok(filtered.lineCount < result.lineCount);
  // At most a 4-byte id per line, and the stats: no coordinates (the lines' points alone are pointBytes).
  const bound = 4 * lines.count + 4096;
  assert.ok(traffic.received <= bound, `${traffic.received} bytes came from the worker for ${lines.count} lines (bound ${bound})`);
  assert.ok(traffic.posted < 4096, `${traffic.posted} bytes went to the worker`);
  assert.ok(lines.pointBytes > 20 * bound, `the lines' coordinates (${lines.pointBytes} bytes) would not fit the bound`);
  // Times are printed, not asserted (the machine is shared).
  console.log(
    `# dragon.glb: re-threshold ${filtered.milliseconds.toFixed(1)} ms in the worker; ${traffic.received} bytes back, ${traffic.posted} sent ` +
      `(${lines.count} lines, whose points are ${lines.pointBytes} bytes); ` +
      `main thread: ${traffic.replies.toFixed(1)} ms handling the replies (${filtered.drawMs.toFixed(1)} ms of it showing the lines), ` +
      `${traffic.renders.toFixed(1)} ms in the next frame's render call`,
  );
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
