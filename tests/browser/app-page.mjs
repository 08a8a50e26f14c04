// What the app's browser tests share: the app (web/dist) opened in a fresh
// Chromium, files dropped on it as a user would, the result of an action.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { after, before } from 'node:test';
import { launch } from './browser.mjs';
import { serve } from './server.mjs';
import { ROOT } from '../node/helpers.mjs';

/**
 * Serves web/dist at / (and `roots`, prefix → folder, beside it) and opens
 * the app at `path`; `pageOptions` go to browser.newPage; `headers` change
 * the server's (server.mjs: null drops one, e.g. the isolation headers). Returns {page,
 * pageErrors, origin, close()}; pageErrors collects the page's uncaught errors.
 */
export async function openApp(roots = {}, pageOptions = {}, path = '/', headers = {}) {
  assert.ok(existsSync(join(ROOT, 'web/dist/index.html')), 'web/dist is missing: run web/build.sh');
  const server = await serve({ ...roots, '/': join(ROOT, 'web/dist') }, headers);
  const browser = await launch();
  const page = await browser.newPage({ viewport: { width: 1000, height: 750 }, ...pageOptions });
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));
  const origin = `http://127.0.0.1:${server.address().port}`;
  await page.goto(`${origin}${path}`);
  return {
    page,
    pageErrors,
    origin,
    async close() {
      await browser.close();
      server.close();
    },
  };
}

/**
 * The set-up of a test file that works on one page of the app: openApp(roots,
 * pageOptions, path) before its first test, then (unless `sample` is false)
 * the built-in sample's lines; the browser closes after its last test.
 * Returns the app, whose page, pageErrors and origin are set once the tests run.
 */
export function useApp(roots = {}, pageOptions = {}, { path = '/', sample = true } = {}) {
  const app = { page: null, pageErrors: [], origin: '', close: async () => {} };
  before(async () => {
    Object.assign(app, await openApp(roots, pageOptions, path));
    if (sample) await sampleReady(app.page);
  });
  after(() => app.close());
  return app;
}

/** Waits until the built-in sample has its lines and the page is ready. */
export function sampleReady(page) {
  return page.waitForFunction(() => window.crestline?.lastResult && document.body.dataset.state === 'ready', null, { timeout: 60000 });
}

/** Waits for the next result (or an error) after `action`; asserts no error; returns the result. */
export async function nextResult(page, action, timeout = 60000) {
  const count = await page.evaluate(() => window.crestline?.results.length ?? 0);
  await action();
  await page.waitForFunction((n) => window.crestline.results.length > n || document.body.dataset.state === 'error', count, { timeout });
  const error = await page.textContent('#error');
  assert.equal(error, '', `the page shows an error: ${error}`);
  return page.evaluate(() => window.crestline.lastResult);
}

/** Drops files (paths under ../shared/meshes, {name, url} or {name, text}) on the page. */
export function dropFiles(page, files) {
  const items = files.map((f) => (typeof f === 'string' ? { url: `/meshes/${f}`, name: f.split('/').pop() } : f));
  return page.evaluate(async (items) => {
    const transfer = new DataTransfer();
    for (const item of items) {
      const body = item.url ? await (await fetch(item.url)).arrayBuffer() : item.text;
      transfer.items.add(new File([body], item.name));
    }
    document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, items);
}

/**
 * The model's projected bounding box in the canvas's CSS pixels (after the
 * next frame), the rectangles the info box and the panel cover, the canvas
 * size and the camera's direction (from the orbit centre) and up vector.
 */
export function framing(page) {
  return page.evaluate(async () => {
    const { viewer, gui } = window.crestline;
    await new Promise((resolve) => requestAnimationFrame(resolve));
    const canvas = viewer.renderer.domElement.getBoundingClientRect();
    const mesh = viewer.surface.mesh;
    const positions = mesh.geometry.attributes.position;
    viewer.camera.updateMatrixWorld();
    const box = { left: Infinity, top: Infinity, right: -Infinity, bottom: -Infinity };
    const p = viewer.camera.position.clone();
    for (let i = 0; i < positions.count; i++) {
      p.fromBufferAttribute(positions, i).applyMatrix4(mesh.matrixWorld).project(viewer.camera);
      const [x, y] = [((p.x + 1) / 2) * canvas.width, ((1 - p.y) / 2) * canvas.height];
      Object.assign(box, { left: Math.min(box.left, x), top: Math.min(box.top, y), right: Math.max(box.right, x), bottom: Math.max(box.bottom, y) });
    }
    const covers = [document.getElementById('hud'), gui.domElement].map((e) => {
      const r = e.getBoundingClientRect();
      return { left: r.left - canvas.left, top: r.top - canvas.top, right: r.right - canvas.left, bottom: r.bottom - canvas.top };
    });
    const direction = viewer.camera.position.clone().sub(viewer.controls.target).normalize().toArray();
    return {
      box,
      covers,
      width: canvas.width,
      height: canvas.height,
      count: positions.count,
      direction,
      up: viewer.camera.up.toArray(),
      free: viewer.uncovered(),
    };
  });
}

/** The projected model lies in the canvas, clear of the info box and the panel, and fills a good part of the free area. */
export function assertUncovered({ box, covers, width, height, free }, fill = 0.6) {
  const b = box;
  const inside = b.left >= -1 && b.top >= -1 && b.right <= width + 1 && b.bottom <= height + 1;
  assert.ok(inside, `the model [${[b.left, b.top, b.right, b.bottom].map(Math.round)}] lies inside the ${width}×${height} canvas`);
  for (const c of covers) {
    const overlaps = b.left < c.right - 1 && c.left < b.right - 1 && b.top < c.bottom - 1 && c.top < b.bottom - 1;
    assert.ok(
      !overlaps,
      `the model [${[b.left, b.top, b.right, b.bottom].map(Math.round)}] is clear of [${[c.left, c.top, c.right, c.bottom].map(Math.round)}]`,
    );
  }
  const filled = Math.max((b.right - b.left) / (free.right - free.left), (b.bottom - b.top) / (free.bottom - free.top));
  assert.ok(filled > fill, `the model fills ${filled.toFixed(2)} of the free area's limiting side`);
}
