// What the app's browser tests share: the app (web/dist) opened in a fresh
// Chromium, files dropped on it as a user would, the result of an action.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { launch } from './browser.mjs';
import { serve } from './server.mjs';
import { ROOT } from '../node/helpers.mjs';

/**
 * Serves web/dist at / (and `roots`, prefix → folder, beside it) and opens
 * the app; `pageOptions` go to browser.newPage. Returns {page, pageErrors,
 * close()}; pageErrors collects the page's uncaught errors.
 */
export async function openApp(roots = {}, pageOptions = {}) {
  assert.ok(existsSync(join(ROOT, 'web/dist/index.html')), 'web/dist is missing: run web/build.sh');
  const server = await serve({ ...roots, '/': join(ROOT, 'web/dist') });
  const browser = await launch();
  const page = await browser.newPage({ viewport: { width: 1000, height: 750 }, ...pageOptions });
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
  return {
    page,
    pageErrors,
    async close() {
      await browser.close();
      server.close();
    },
  };
}

/** Waits until the built-in sample has its lines and the page is ready. */
export function sampleReady(page) {
  return page.waitForFunction(() => window.crestline?.lastResult && document.body.dataset.state === 'ready', null, { timeout: 60000 });
}

/** Waits for the next result (or an error) after `action`; asserts no error; returns the result. */
export async function nextResult(page, action, timeout = 60000) {
  const count = await page.evaluate(() => window.crestline?.results.length ?? 0);
  await action();
  await page.waitForFunction(
    (n) => window.crestline.results.length > n || document.body.dataset.state === 'error',
    count,
    { timeout },
  );
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
