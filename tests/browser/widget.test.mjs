// <crestline-viewer> in headless Chromium, loaded from another origin than
// the page (two static servers): load then lines, a re-threshold that changes
// the count, the exports, 20 viewers on one page without WebGL context loss,
// clear errors for bad sources, and the iframe embed. The widget is built
// afresh into a private folder (widget-site.mjs). Needs wasm/dist.
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { launch } from './browser.mjs';
import { MESHES, ROOT, haveMeshes, sineHeightField } from '../node/helpers.mjs';
import { boxObj } from './box-obj.mjs';
import { glbFromSoup } from './widget-glb.mjs';
import { serveWidgetSite } from './widget-site.mjs';

// The page's site (its pages, its meshes) and the widget's (a CDN, say).
let servers, browser, pages, siteUrl, cdnUrl;

// Real meshes when ../shared/meshes is there, otherwise a generated GLB.
const MAIN_MESH = haveMeshes ? '/meshes/glb/fandisk.glb' : '/pages/sine.glb';
const SECOND_MESH = haveMeshes ? '/meshes/glb/pmndrs-bunny-draco.glb' : '/pages/sine.glb';

before(async () => {
  pages = mkdtempSync(join(tmpdir(), 'crestline-widget-'));
  writeFileSync(join(pages, 'sine.glb'), glbFromSoup(sineHeightField({ n: 40 })));
  writeFileSync(join(pages, 'garbage.glb'), 'this is not a mesh');
  writeFileSync(join(pages, 'box.obj'), boxObj());
  servers = await serveWidgetSite({ '/meshes/': MESHES, '/pages/': pages });
  ({ siteUrl, cdnUrl } = servers);
  browser = await launch();
});

after(async () => {
  await browser?.close();
  servers?.close();
  if (pages) rmSync(pages, { recursive: true, force: true });
});

/** A page on the site that loads the element from the CDN; events are recorded in window.events. */
async function openPage(name, body, viewport = { width: 1000, height: 700 }) {
  writeFileSync(
    join(pages, name),
    `<!doctype html>
<html><head><meta charset="utf-8"><link rel="icon" href="data:,">
<script type="module" src="${cdnUrl}/crestline-viewer.js"></script>
<script>
  window.events = [];
  window.progress = [];
  // Counts the canvases that get a WebGL context (the widget should need one).
  window.webglCanvases = new Set();
  const getContext = HTMLCanvasElement.prototype.getContext;
  HTMLCanvasElement.prototype.getContext = function (type, ...rest) {
    if (/webgl/.test(type)) window.webglCanvases.add(this);
    return getContext.call(this, type, ...rest);
  };
  document.addEventListener('progress', (e) => e.target.localName === 'crestline-viewer' && window.progress.push(e.detail), true);
  for (const type of ['load', 'lines', 'error', 'cancel']) {
    document.addEventListener(type, (e) => {
      if (e.target.localName === 'crestline-viewer')
        window.events.push({ type, id: e.target.id, detail: type === 'lines' ? { counts: e.detail.counts, lengths: e.detail.lengths, threshold: e.detail.stats.threshold } : e.detail });
    }, true);
  }
</script></head><body style="margin:0">${body}</body></html>`,
  );
  const page = await browser.newPage({ viewport });
  const problems = [];
  page.requested = [];
  page.on('request', (request) => page.requested.push(request.url()));
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  page.on('console', (message) => {
    if (/context (was )?lost|too many active webgl contexts|CONTEXT_LOST/i.test(message.text())) problems.push(`console: ${message.text()}`);
  });
  await page.goto(`${siteUrl}/pages/${name}`);
  await page.waitForFunction(() => customElements.get('crestline-viewer'));
  return { page, problems };
}

const eventsOf = (page, id, type) => page.evaluate(([id, type]) => window.events.filter((e) => e.id === id && e.type === type), [id, type]);

async function waitForEvents(page, id, type, count, timeout = 30000) {
  try {
    await page.waitForFunction(
      ([id, type, count]) =>
        window.events.filter((e) => e.id === id && e.type === type).length >= count || window.events.some((e) => e.id === id && e.type === 'error'),
      [id, type, count],
      { timeout },
    );
  } catch (error) {
    const seen = await page.evaluate(() => ({ events: window.events, progress: window.progress.slice(-3) }));
    throw new Error(`${id}: no ${count}× ${type} within ${timeout} ms; saw ${JSON.stringify(seen)}`);
  }
}

const total = (counts) => counts.ridges + counts.valleys;

test('a viewer from another origin loads a GLB, re-thresholds and exports', async () => {
  const { page, problems } = await openPage(
    'one.html',
    '<crestline-viewer id="v" alt="A fan disk" interaction="orbit" style="width:480px;height:320px"></crestline-viewer>',
  );
  assert.notEqual(new URL(siteUrl).origin, new URL(cdnUrl).origin);
  // The worker and the .wasm are separate files, found beside the module on its own origin.
  for (const file of ['crestline-viewer.js', 'crestline-viewer-worker.js']) {
    const text = await (await fetch(`${cdnUrl}/${file}`)).text();
    assert.doesNotMatch(text, /AGFzbQ/, `${file} inlines a WebAssembly module`);
  }
  // The widget's choice: the worker sends the repaired surface before the lines, but the
  // widget keeps its poster and shows the surface with the first lines (one picture, complete).
  await page.evaluate(() => {
    const v = document.getElementById('v');
    window.during = [];
    v.addEventListener('progress', (e) =>
      window.during.push({
        stage: e.detail.stage,
        poster: !v.parts.poster.hidden,
        vertices: v.view.surface.mesh.geometry.getAttribute('position')?.count ?? 0,
      }),
    );
  });
  await page.evaluate((src) => (document.getElementById('v').src = src), MAIN_MESH);
  await waitForEvents(page, 'v', 'lines', 1);
  const during = await page.evaluate(() => window.during);
  assert.ok(
    during.some((p) => p.stage === 'fairing'),
    'progress through the pipeline, after the surface was loaded',
  );
  assert.deepEqual(
    during.filter((p) => !p.poster || p.vertices),
    [],
    'no surface before the lines',
  );
  const shown = await page.evaluate(() => ({
    vertices: document.getElementById('v').view.surface.mesh.geometry.getAttribute('position').count,
    stats: document.getElementById('v').stats.vertices,
  }));
  assert.equal(shown.vertices, shown.stats, 'the surface came with the first lines');
  for (const file of ['crestline-viewer-worker.js', 'crestline.wasm'])
    assert.ok(page.requested.includes(`${cdnUrl}/${file}`), `${file} was not fetched from the module's origin: ${page.requested}`);
  const order = await page.evaluate(() => window.events.map((e) => e.type));
  assert.deepEqual(order, ['load', 'lines'], `events: ${order}`);
  const [first] = await eventsOf(page, 'v', 'lines');
  const progress = await page.evaluate(() => window.progress);
  assert.ok(
    progress.length > 3 && progress.every(({ stage, fraction }) => typeof stage === 'string' && fraction >= 0 && fraction <= 1),
    JSON.stringify(progress),
  );
  assert.ok(total(first.detail.counts) > 0, 'the first result has lines');
  assert.ok(first.detail.lengths.ridges + first.detail.lengths.valleys > 0);

  // The pipeline's attributes are the core's table (Session.describe()): one per parameter,
  // named by its CLI flag, the core's default when absent; `smoothing` and `fairing` stay as aliases.
  const parameters = await page.evaluate(() => {
    const table = customElements.get('crestline-viewer').parameters.filter((p) => p.group === 'pipeline' && p.stage);
    const v = document.getElementById('v');
    const loose = document.createElement('crestline-viewer');
    loose.setAttribute('smoothing-steps', '2');
    loose.setAttribute('fairing', '0.5');
    loose.setAttribute('threshold', 'nonsense');
    return {
      table: table.map((p) => ({ key: p.key, default: p.default, property: v[p.key], sent: v.pipelineOptions()[p.key] })),
      loose: { smoothingSteps: loose.smoothingSteps, smoothing: loose.smoothing, hausdorffBound: loose.hausdorffBound, threshold: loose.threshold },
    };
  });
  assert.ok(parameters.table.length >= 5, JSON.stringify(parameters.table));
  for (const p of parameters.table) assert.deepEqual([p.property, p.sent], [p.default, p.default], `${p.key}: the element's default is the core's`);
  assert.deepEqual(parameters.loose, { smoothingSteps: 2, smoothing: 2, hausdorffBound: 0.5, threshold: 'auto' });

  // A higher threshold, set as a property (reflected to the attribute), keeps fewer lines.
  const threshold = first.detail.threshold * 4 || 1;
  await page.evaluate((t) => (document.getElementById('v').threshold = t), threshold);
  assert.equal(await page.getAttribute('#v', 'threshold'), String(threshold));
  await waitForEvents(page, 'v', 'lines', 2);
  const [, second] = await eventsOf(page, 'v', 'lines');
  assert.ok(
    total(second.detail.counts) < total(first.detail.counts),
    `${total(second.detail.counts)} lines after raising the threshold, ${total(first.detail.counts)} before`,
  );

  const exported = await page.evaluate(async () => {
    const v = document.getElementById('v');
    const png = await v.toPNG({ width: 960 });
    const glb = await v.toGLB();
    const glbJson = JSON.parse(
      new TextDecoder().decode(new Uint8Array(await glb.arrayBuffer(), 20, new DataView(await glb.arrayBuffer()).getUint32(12, true))),
    );
    return {
      svg: await v.toSVG(),
      outlined: await v.toSVG({ silhouette: '#222222' }),
      obj: await v.toOBJ(),
      json: JSON.parse(await v.toJSON()),
      png: [png.type, png.size],
      glb: glbJson.meshes.map((m) => m.name ?? m.primitives[0].mode),
      label: v.shadowRoot.querySelector('canvas').getAttribute('aria-label'),
    };
  });
  // The core's SVG writer, with the widget's camera and size.
  // Fandisk's smooth lines stop at its creases: the first drawn group may be the creases.
  assert.match(
    exported.svg,
    /<g id="(ridges|valleys|creases)" fill="none" stroke="#[0-9a-f]{6}" stroke-width="[\d.]+"[^>]*>\n<path (class="convex" )?d="M[\d.]+,[\d.]+ L/,
  );
  assert.match(exported.svg, /viewBox="0 0 480\.00 320\.00"/);
  assert.doesNotMatch(exported.svg, /silhouette/);
  assert.match(exported.outlined, /<g id="silhouette" fill="none" stroke="#222222" stroke-width="[\d.]+"[^>]*>\n<path d="M/);
  assert.match(exported.obj, /^v /m);
  assert.equal(exported.json.ridges.length + exported.json.valleys.length, total(second.detail.counts));
  assert.equal(exported.png[0], 'image/png');
  assert.ok(exported.png[1] > 1000);
  // The CLI's --with-mesh GLB: the surface, then a mesh per shown group.
  assert.ok(exported.glb.length >= 2, `GLB meshes: ${exported.glb}`);
  assert.equal(exported.glb[0], 'surface');
  assert.equal(exported.label, 'A fan disk');
  if (process.env.CRESTLINE_SHOTS) {
    writeFileSync(join(ROOT, 'test-results/widget.svg'), exported.svg);
    await page.screenshot({ path: join(ROOT, 'test-results/widget-one.png') });
  }
  // Display attributes change the drawing without a re-run.
  const hidden = await page.evaluate(async () => {
    const v = document.getElementById('v');
    v.ridges = false;
    await new Promise(requestAnimationFrame);
    return { attribute: v.getAttribute('ridges'), svg: await v.toSVG() };
  });
  assert.equal(hidden.attribute, 'false');
  assert.doesNotMatch(hidden.svg, /id="ridges"/);
  assert.equal((await eventsOf(page, 'v', 'lines')).length, 2);
  assert.deepEqual(problems, []);
  await page.close();
});

test('20 viewers share one WebGL context, load without context loss and redraw after one', async () => {
  const body = Array.from(
    { length: 20 },
    (_, i) =>
      `<crestline-viewer id="v${i}" src="${i % 2 ? SECOND_MESH : MAIN_MESH}" style="width:190px;height:120px" ${i % 3 ? '' : 'auto-rotate'}></crestline-viewer>`,
  ).join('');
  const { page, problems } = await openPage('twenty.html', `<div style="display:flex;flex-wrap:wrap">${body}</div>`, { width: 1000, height: 700 });
  await page.waitForFunction(() => new Set(window.events.filter((e) => e.type === 'lines' || e.type === 'error').map((e) => e.id)).size === 20, null, {
    timeout: 60000,
  });
  const errors = await page.evaluate(() => window.events.filter((e) => e.type === 'error'));
  assert.deepEqual(errors, []);
  // Every viewer has drawn something into its canvas.
  const blankViewers = () =>
    page.evaluate(() =>
      [...document.querySelectorAll('crestline-viewer')]
        .filter((v) => {
          const canvas = v.shadowRoot.querySelector('canvas');
          const { data } = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height);
          for (let i = 3; i < data.length; i += 4) if (data[i]) return false;
          return true;
        })
        .map((v) => v.id),
    );
  await page.waitForTimeout(300);
  const blank = await blankViewers();
  assert.deepEqual(blank, []);
  assert.equal(await page.evaluate(() => window.webglCanvases.size), 1, 'one WebGL context for all viewers');
  assert.deepEqual(problems, []);
  // When the browser takes the context away, every viewer draws again (on a new one).
  await page.evaluate(async () => {
    const [canvas] = window.webglCanvases;
    const lose = canvas.getContext('webgl2').getExtension('WEBGL_lose_context');
    const lost = new Promise((resolve) => canvas.addEventListener('webglcontextlost', resolve, { once: true }));
    lose.loseContext();
    await lost;
    for (const v of document.querySelectorAll('crestline-viewer')) {
      const c = v.shadowRoot.querySelector('canvas');
      c.getContext('2d').clearRect(0, 0, c.width, c.height);
    }
  });
  let redrawn = false;
  for (let wait = 0; wait < 10000 && !redrawn; wait += 250) {
    await page.waitForTimeout(250);
    redrawn = (await blankViewers()).length === 0;
  }
  assert.ok(redrawn, `still blank after the context was lost: ${await blankViewers()}`);
  if (process.env.CRESTLINE_SHOTS) await page.screenshot({ path: join(ROOT, 'test-results/widget-twenty.png') });
  await page.close();
});

test('a glTF with its .bin and an OBJ load; a bad src fires error with a clear message', async () => {
  const good = haveMeshes
    ? `
    <crestline-viewer id="gltf" src="/meshes/gltf/Duck/Duck.gltf"></crestline-viewer>
    <crestline-viewer id="obj" src="/meshes/cad/fandisk-quads.obj"></crestline-viewer>`
    : '';
  const { page } = await openPage(
    'sources.html',
    `${good}
    <crestline-viewer id="missing" src="/meshes/no-such-mesh.glb"></crestline-viewer>
    <crestline-viewer id="garbage" src="/pages/garbage.glb"></crestline-viewer>`,
  );
  for (const id of haveMeshes ? ['gltf', 'obj'] : []) {
    await waitForEvents(page, id, 'lines', 1);
    assert.deepEqual(await eventsOf(page, id, 'error'), []);
  }
  await waitForEvents(page, 'missing', 'error', 1);
  await waitForEvents(page, 'garbage', 'error', 1);
  const [missing] = await eventsOf(page, 'missing', 'error');
  const [garbage] = await eventsOf(page, 'garbage', 'error');
  assert.match(missing.detail.message, /^no-such-mesh\.glb: could not be fetched \(HTTP 404/);
  assert.match(garbage.detail.message, /^garbage\.glb: the file is neither a GLB \(which starts with the bytes 'glTF'\) nor glTF JSON\./);
  assert.equal(await page.evaluate(() => document.getElementById('missing').shadowRoot.querySelector('[part=error]').textContent), missing.detail.message);
  await page.close();
});

test("cancel() stops a viewer's computation (event cancel); it and its neighbour on the same worker compute again", async () => {
  const { page } = await openPage(
    'cancel.html',
    `
    <crestline-viewer id="a" src="${MAIN_MESH}"></crestline-viewer>
    <crestline-viewer id="b" src="${MAIN_MESH}"></crestline-viewer>`,
  );
  await waitForEvents(page, 'a', 'lines', 1);
  await waitForEvents(page, 'b', 'lines', 1);
  await page.evaluate(() => {
    const a = document.getElementById('a');
    a.smoothing = 9;
    // The change applies in a microtask; cancel after it was sent.
    setTimeout(() => a.cancel(), 0);
  });
  await waitForEvents(page, 'a', 'cancel', 1);
  assert.equal((await eventsOf(page, 'a', 'lines')).length, 1, 'the cancelled run delivered no lines');
  // Without shared memory the worker was restarted: both viewers send their meshes again.
  await page.evaluate(() => {
    document.getElementById('b').threshold = 0;
    document.getElementById('a').smoothing = 2;
  });
  await waitForEvents(page, 'b', 'lines', 2);
  await waitForEvents(page, 'a', 'lines', 2);
  assert.deepEqual(await eventsOf(page, 'a', 'error'), []);
  assert.deepEqual(await eventsOf(page, 'b', 'error'), []);
  await page.close();
});

test('the iframe embed shows one mesh full-frame with the fragment parameters', async () => {
  const src = `${siteUrl}${MAIN_MESH}`;
  const { page } = await openPage(
    'embed.html',
    `<iframe id="frame" style="width:400px;height:300px;border:0" src="${cdnUrl}/embed.html#src=${encodeURIComponent(src)}&threshold=0&ridge-color=%2300aa00"></iframe>`,
  );
  const frame = page.frames().find((f) => f.url().startsWith(cdnUrl));
  await frame.waitForFunction(() => document.querySelector('crestline-viewer')?.lines, null, { timeout: 30000 });
  const state = await frame.evaluate(() => {
    const v = document.querySelector('crestline-viewer');
    const { width, height } = v.getBoundingClientRect();
    return { width, height, threshold: v.threshold, ridgeColor: v.ridgeColor, lines: v.lines.types.length };
  });
  assert.deepEqual({ ...state, lines: state.lines > 0 }, { width: 400, height: 300, threshold: 0, ridgeColor: '#00aa00', lines: true });
  await page.close();
});

test('lazy loading waits for the viewport; keyboard orbit; reduced motion stops auto-rotate', async () => {
  const { page } = await openPage(
    'lazy.html',
    `
    <crestline-viewer id="near" src="${MAIN_MESH}" interaction="orbit" auto-rotate poster="data:image/gif;base64,R0lGODlhAQABAAAAACw="></crestline-viewer>
    <crestline-viewer id="still" src="${MAIN_MESH}" interaction="none" threshold="0" style="--crestline-ridge-color: #00ff00; --crestline-valley-color: #ff00ff"></crestline-viewer>
    <div style="height:3000px"></div>
    <crestline-viewer id="far" src="${MAIN_MESH}" loading="lazy"></crestline-viewer>
    <script>
      // A property set before the definition arrives still reaches the attribute.
      const early = document.createElement('crestline-viewer');
      early.id = 'early';
      early.threshold = 2.5;
      document.body.append(early);
    </script>`,
  );
  await page.emulateMedia({ reducedMotion: 'reduce' });
  await waitForEvents(page, 'near', 'lines', 1);
  await waitForEvents(page, 'still', 'lines', 1);
  const camera = (id) => page.evaluate((id) => document.getElementById(id).view.camera.position.toArray(), id);
  const state = await page.evaluate(() => {
    const near = document.getElementById('near');
    const canvas = near.shadowRoot.querySelector('canvas');
    const { width, height } = near.getBoundingClientRect();
    return {
      size: [width, height],
      tabIndex: canvas.tabIndex,
      label: canvas.getAttribute('aria-label'),
      posterHidden: near.shadowRoot.querySelector('[part=poster]').hidden,
    };
  });
  assert.equal(await page.getAttribute('#early', 'threshold'), '2.5');
  assert.deepEqual(state, { size: [300, 150], tabIndex: 0, label: 'A 3D model with its ridge and valley lines', posterHidden: true });
  // Reduced motion: auto-rotate is off, so the camera stands still.
  const before = await camera('near');
  // Coming near the viewport again (scrolling) does not re-run anything.
  assert.equal((await eventsOf(page, 'near', 'lines')).length, 1);
  await page.waitForTimeout(300);
  assert.deepEqual(await camera('near'), before);
  // Arrow keys orbit an interactive viewer, and nothing else.
  await page.focus('#near >> canvas');
  await page.keyboard.press('ArrowLeft');
  assert.notDeepEqual(await camera('near'), before);
  const still = await camera('still');
  // CSS custom properties colour the lines (and so the SVG).
  assert.match(await page.evaluate(() => document.getElementById('still').toSVG()), /stroke="#00ff00"[^]*stroke="#ff00ff"/);
  await page.evaluate(() =>
    document
      .getElementById('still')
      .shadowRoot.querySelector('canvas')
      .dispatchEvent(new KeyboardEvent('keydown', { key: 'ArrowLeft' })),
  );
  assert.deepEqual(await camera('still'), still);
  // A removed viewer frees its worker session; put back, it loads again.
  await page.evaluate(async () => {
    const still = document.getElementById('still');
    still.remove();
    await new Promise((resolve) => setTimeout(resolve, 50));
    document.body.prepend(still);
  });
  await waitForEvents(page, 'still', 'lines', 2);
  assert.equal(
    (await eventsOf(page, 'still', 'load')).length,
    2,
    JSON.stringify(await page.evaluate(() => window.events.filter((e) => e.id === 'still').map((e) => e.type + ' ' + (e.detail.threshold ?? '')))),
  );
  // A worker that lost the mesh (as after a WebAssembly abort) gets it sent
  // again by the client on the next change; the viewer keeps its picture (no new 'load').
  await page.evaluate(() => {
    const still = document.getElementById('still');
    still.session.connection.worker.postMessage({ type: 'dispose', id: still.session.id });
    still.threshold = 0.5;
  });
  await waitForEvents(page, 'still', 'lines', 3);
  assert.equal(
    (await eventsOf(page, 'still', 'load')).length,
    2,
    JSON.stringify(await page.evaluate(() => window.events.filter((e) => e.id === 'still').map((e) => e.type + ' ' + (e.detail.threshold ?? '')))),
  );
  assert.deepEqual(await eventsOf(page, 'still', 'error'), []);
  // Without reduced motion, auto-rotate turns the model.
  await page.emulateMedia({ reducedMotion: 'no-preference' });
  const turned = await camera('near');
  await page.waitForFunction(
    (p) =>
      document
        .getElementById('near')
        .view.camera.position.toArray()
        .some((v, i) => Math.abs(v - p[i]) > 1e-6),
    turned,
    { timeout: 5000 },
  );
  // The lazy viewer three screens down has not even fetched its mesh.
  await page.waitForTimeout(300);
  assert.deepEqual(await eventsOf(page, 'far', 'load'), []);
  await page.evaluate(() => document.getElementById('far').scrollIntoView());
  await waitForEvents(page, 'far', 'lines', 1);
  await page.close();
});

test('up-axis: the polar angle of camera-orbit is measured from Y (default) or Z', async () => {
  const { page, problems } = await openPage(
    'up.html',
    `
    <crestline-viewer id="y" src="/pages/sine.glb" camera-orbit="0deg 30deg 100%"></crestline-viewer>
    <crestline-viewer id="z" src="/pages/sine.glb" camera-orbit="0deg 30deg 100%" up-axis="z"></crestline-viewer>`,
  );
  await waitForEvents(page, 'y', 'lines', 1);
  await waitForEvents(page, 'z', 'lines', 1);
  const view = (id) =>
    page.evaluate((id) => {
      const { camera, controls } = document.getElementById(id).view;
      return { direction: camera.position.clone().sub(controls.target).normalize().toArray(), up: camera.up.toArray() };
    }, id);
  const near = (a, b, what) =>
    assert.ok(
      a.every((x, i) => Math.abs(x - b[i]) < 1e-6),
      `${what}: ${a} ≠ ${b}`,
    );
  const [sin, cos] = [Math.sin(Math.PI / 6), Math.cos(Math.PI / 6)];
  const y = await view('y');
  near(y.direction, [0, cos, sin], 'Y up: 30° from +Y, towards +Z');
  near(y.up, [0, 1, 0], 'Y up');
  const z = await view('z');
  near(z.direction, [0, -sin, cos], 'Z up: 30° from +Z, towards −Y');
  near(z.up, [0, 0, 1], 'Z up');
  assert.equal(await page.evaluate(() => document.getElementById('z').upAxis), 'z');
  await page.evaluate(() => (document.getElementById('z').upAxis = 'y'));
  await page.waitForFunction(() => document.getElementById('z').view.camera.up.y === 1);
  near((await view('z')).direction, [0, cos, sin], 'back to Y up');
  assert.deepEqual(problems, []);
  await page.close();
});

test('creases: shown in crease-color (attribute over --crestline-crease-color), creases="false" hides them, in toSVG/toOBJ/toJSON', async () => {
  const { page, problems } = await openPage(
    'creases.html',
    `
    <crestline-viewer id="c" src="/pages/box.obj" crease-color="#00aa44" style="width:400px;height:300px;--crestline-crease-color:#aa0000"></crestline-viewer>
    <crestline-viewer id="d" src="/pages/box.obj" creases="false" style="width:400px;height:300px;--crestline-crease-color:#123456"></crestline-viewer>`,
  );
  await waitForEvents(page, 'c', 'lines', 1);
  await waitForEvents(page, 'd', 'lines', 1);
  const state = (id) =>
    page.evaluate((id) => {
      const v = document.getElementById(id);
      return {
        creases: v.creases,
        creaseColor: v.creaseColor,
        count: v.stats.creases,
        visible: v.view.creases.objects.map((o) => o.visible),
        segments: v.view.creases.objects.map((o) => o.userData.segments),
        colour: `#${v.view.creases.objects[0].material.color.getHexString()}`,
      };
    }, id);
  const c = await state('c');
  const d = await state('d');
  // The box: 12 convex edges of 24 segments each, no concave ones.
  assert.deepEqual(c, { creases: true, creaseColor: '#00aa44', count: 12, visible: [true, false], segments: [288, 0], colour: '#00aa44' });
  assert.deepEqual(d, { creases: false, creaseColor: null, count: 12, visible: [false, false], segments: [288, 0], colour: '#123456' });

  const exports = (id) =>
    page.evaluate(async (id) => {
      const v = document.getElementById(id);
      return { svg: await v.toSVG(), obj: await v.toOBJ(), json: JSON.parse(await v.toJSON()) };
    }, id);
  const shown = await exports('c');
  assert.match(shown.svg, /<g id="creases" fill="none" stroke="#00aa44"[^>]*>\n<path class="convex" d="M/);
  assert.doesNotMatch(shown.svg, /class="concave"/);
  assert.match(shown.obj, /^o creases$/m);
  assert.equal(shown.json.creases.length, c.count);
  assert.doesNotMatch((await exports('d')).svg, /creases/, 'hidden creases are not in the SVG');

  // The property reflects to the attribute and hides them.
  await page.evaluate(() => (document.getElementById('c').creases = false));
  assert.equal(await page.getAttribute('#c', 'creases'), 'false');
  assert.deepEqual((await state('c')).visible, [false, false]);
  assert.deepEqual(problems, []);
  await page.close();
});
