// WASM threads in headless Chromium: the app served with COOP/COEP (the test
// server's default, as vite preview) runs crestline-mt on every core the
// browser reports (2 on the CI machine), and its lines equal those of the
// same page served without isolation, which runs the plain single-threaded
// module without an error. The widget on a non-isolated site takes the plain
// module, and on an isolated site the threaded one, though the widget comes
// from another origin (its pthread workers start through a blob script).
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { openApp, sampleReady } from './app-page.mjs';
import { launch } from './browser.mjs';
import { sineHeightField } from '../node/helpers.mjs';
import { glbFromSoup } from './widget-glb.mjs';
import { serveWidgetSite } from './widget-site.mjs';

const ISOLATION_OFF = { 'Cross-Origin-Opener-Policy': null, 'Cross-Origin-Embedder-Policy': null };
const ISOLATION_ON = { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' };

/** The threads of the page's pipeline worker (worker.js sets self.crestlineThreads once its module started). */
async function workerThreads(page) {
  for (let tries = 0; tries < 600; tries++) {
    for (const worker of page.workers()) {
      const threads = await worker.evaluate(() => self.crestlineThreads).catch(() => undefined);
      if (threads !== undefined) return threads;
    }
    await new Promise((resolve) => setTimeout(resolve, 100));
  }
  throw new Error(`no pipeline worker reported its threads; workers: ${page.workers().map((w) => w.url())}`);
}

/** The shown lines of the app, as plain arrays, and the page's isolation. */
function shownLines(page) {
  return page.evaluate(() => {
    const { lines } = window.crestline.shown;
    return {
      isolated: crossOriginIsolated,
      sharedArrayBuffer: typeof SharedArrayBuffer === 'function',
      points: Array.from(lines.points),
      offsets: Array.from(lines.offsets),
      types: Array.from(lines.types),
      strengths: Array.from(lines.strengths),
    };
  });
}

/** Opens the app with `headers`, waits for the sample's lines; returns {threads, lines, errors}. */
async function sampleWith(headers) {
  const app = await openApp({}, {}, '/', headers);
  const consoleErrors = [];
  app.page.on('console', (message) => message.type() === 'error' && consoleErrors.push(message.text()));
  try {
    await sampleReady(app.page);
    const lines = await shownLines(app.page);
    const threads = await workerThreads(app.page);
    const cores = await app.page.evaluate(() => navigator.hardwareConcurrency);
    return { threads, cores, lines, errors: [...app.pageErrors, ...consoleErrors], error: await app.page.textContent('#error') };
  } finally {
    await app.close();
  }
}

test('the isolated app computes on every core with crestline-mt; the same lines as one thread without isolation', async () => {
  const isolated = await sampleWith(ISOLATION_ON);
  const plain = await sampleWith(ISOLATION_OFF);
  assert.equal(isolated.lines.isolated, true, 'COOP + COEP isolate the page');
  assert.equal(plain.lines.isolated, false, 'without the headers the page is not isolated');
  assert.equal(plain.lines.sharedArrayBuffer, false, 'and has no SharedArrayBuffer');
  assert.equal(isolated.threads, Math.min(isolated.cores, 8), `crestline-mt runs on the ${isolated.cores} cores Chromium reports`);
  assert.ok(isolated.threads >= 2, `more than one thread on this machine (${isolated.cores} cores); a 1-core machine cannot show threads`);
  assert.equal(plain.threads, 1, 'the plain module without isolation');
  assert.deepEqual([isolated.errors, isolated.error], [[], ''], 'no error with threads');
  assert.deepEqual([plain.errors, plain.error], [[], ''], 'no error without them');
  assert.ok(plain.lines.types.length > 10, `the sample has lines (${plain.lines.types.length})`);
  for (const key of ['offsets', 'types', 'strengths', 'points'])
    assert.deepEqual(isolated.lines[key], plain.lines[key], `${key}: identical with 1 and ${isolated.threads} threads`);
});

let site, browser, pages;

before(async () => {
  pages = mkdtempSync(join(tmpdir(), 'crestline-threads-'));
  writeFileSync(join(pages, 'sine.glb'), glbFromSoup(sineHeightField({ n: 80 })));
  browser = await launch();
});

after(async () => {
  await browser?.close();
  if (pages) rmSync(pages, { recursive: true, force: true });
});

/** The widget from the CDN on a site page with `headers`: its threads and lines event. */
async function widgetWith(headers) {
  site = await serveWidgetSite({ '/pages/': pages }, () => headers);
  try {
    writeFileSync(
      join(pages, 'one.html'),
      `<!doctype html><html><head><meta charset="utf-8"><link rel="icon" href="data:,">
<script type="module" src="${site.cdnUrl}/crestline-viewer.js"></script></head>
<body><crestline-viewer id="v" src="/pages/sine.glb" style="width:300px;height:200px"></crestline-viewer>
<script>window.events = []; for (const type of ['lines', 'error']) document.addEventListener(type, (e) => window.events.push({type, detail: type === 'lines' ? e.detail.counts : e.detail}), true);</script>
</body></html>`,
    );
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (error) => errors.push(error.message));
    page.on('console', (message) => message.type() === 'error' && errors.push(message.text()));
    await page.goto(`${site.siteUrl}/pages/one.html`);
    await page.waitForFunction(() => window.events.length > 0, null, { timeout: 60000 });
    const result = {
      isolated: await page.evaluate(() => crossOriginIsolated),
      events: await page.evaluate(() => window.events),
      threads: await workerThreads(page),
      errors,
    };
    await page.close();
    return result;
  } finally {
    site.close();
  }
}

test('the widget from another origin: one thread on an ordinary page, threads on an isolated one, the same lines', async () => {
  const plain = await widgetWith({});
  const isolated = await widgetWith(ISOLATION_ON);
  assert.deepEqual([plain.isolated, isolated.isolated], [false, true]);
  assert.deepEqual(plain.errors, [], 'no error on an ordinary page');
  assert.deepEqual(isolated.errors, [], 'no error on an isolated page');
  assert.equal(plain.events[0].type, 'lines', JSON.stringify(plain.events));
  assert.equal(plain.threads, 1, 'the plain module on an ordinary page');
  assert.ok(isolated.threads >= 2, `crestline-mt on the isolated page (${isolated.threads} threads)`);
  assert.deepEqual(isolated.events, plain.events, 'the same line counts');
});
