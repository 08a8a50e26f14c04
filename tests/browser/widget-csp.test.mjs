// <crestline-viewer> from another origin on a page served with a strict
// Content-Security-Policy: nothing by default, and for each directive only
// what the widget needs. No 'unsafe-eval' and no 'unsafe-inline' anywhere, so
// an eval, a new Function, an inline <style> (in its shadow root too) or an
// inline script in the widget would be refused and reported. Needs wasm/dist.
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { launch } from './browser.mjs';
import { sineHeightField } from '../node/helpers.mjs';
import { glbFromSoup } from './widget-glb.mjs';
import { serveWidgetSite } from './widget-site.mjs';

/** The policy for a page at `siteUrl` that embeds the widget from `cdnUrl`. */
const policy = (cdnUrl) =>
  [
    "default-src 'none'",
    // The element's module comes from the CDN; compiling crestline.wasm (in
    // the worker, which inherits this policy) needs 'wasm-unsafe-eval', and
    // nothing more: no 'unsafe-eval'.
    `script-src ${cdnUrl} 'wasm-unsafe-eval'`,
    // client/browser.js starts the worker from a blob: module (a Worker's URL must be
    // same-origin with the page) that imports the worker script from the CDN;
    // the imports of a module worker are checked against worker-src too.
    `worker-src blob: ${cdnUrl}`,
    // The worker fetches the meshes (here, the site's own) and the Emscripten
    // glue fetches crestline.wasm from the CDN.
    `connect-src 'self' ${cdnUrl}`,
    // The page's stylesheet (the widget's own styles are a constructed sheet).
    "style-src 'self'",
    // The favicon the browser asks for.
    "img-src 'self'",
    "base-uri 'none'",
    "form-action 'none'",
  ].join('; ');

let servers, browser, pages;

before(async () => {
  pages = mkdtempSync(join(tmpdir(), 'crestline-widget-csp-'));
  writeFileSync(join(pages, 'sine.glb'), glbFromSoup(sineHeightField({ n: 40 })));
  writeFileSync(join(pages, 'page.css'), 'body { margin: 0; }\ncrestline-viewer { width: 480px; height: 320px; }\n');
  servers = await serveWidgetSite({ '/pages/': pages }, (cdnUrl) => ({ 'Content-Security-Policy': policy(cdnUrl) }));
  const { cdnUrl } = servers;
  writeFileSync(
    join(pages, 'csp.html'),
    `<!doctype html>
<html><head><meta charset="utf-8"><title>Crestline under a strict CSP</title>
<link rel="stylesheet" href="page.css">
<script type="module" src="${cdnUrl}/crestline-viewer.js"></script>
</head><body><crestline-viewer id="v" alt="A sine height field" src="/pages/sine.glb"></crestline-viewer></body></html>`,
  );
  browser = await launch();
});

after(async () => {
  await browser?.close();
  servers?.close();
  if (pages) rmSync(pages, { recursive: true, force: true });
});

test('the widget computes lines under a strict CSP, with no violation', async () => {
  const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
  const problems = [];
  const watch = (source) => (message) => {
    if (/Content[- ]Security[- ]Policy|unsafe-eval|unsafe-inline/i.test(message.text())) problems.push(`${source} console: ${message.text()}`);
  };
  page.on('console', watch('page'));
  page.on('worker', (worker) => worker.on('console', watch('worker')));
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  // Injected by the test, not by the page: the policy does not apply to it.
  await page.addInitScript(() => {
    window.events = [];
    document.addEventListener('securitypolicyviolation', (e) => window.events.push({ type: 'violation', detail: `${e.violatedDirective}: ${e.blockedURI}` }));
    for (const type of ['lines', 'error']) {
      document.addEventListener(
        type,
        (e) => {
          if (e.target.localName === 'crestline-viewer') window.events.push({ type, detail: type === 'lines' ? e.detail.counts : e.detail.message });
        },
        true,
      );
    }
  });
  const response = await page.goto(`${servers.siteUrl}/pages/csp.html`);
  assert.equal(response.headers()['content-security-policy'], policy(servers.cdnUrl));
  await page.waitForFunction(() => window.events.some((e) => e.type === 'lines' || e.type === 'error'), null, { timeout: 60000 });
  const events = await page.evaluate(() => window.events);
  const lines = events.find((e) => e.type === 'lines');
  assert.ok(lines, `no lines: ${JSON.stringify(events)} ${problems}`);
  assert.ok(lines.detail.ridges + lines.detail.valleys > 0, `line counts ${JSON.stringify(lines.detail)}`);
  // The shadow root's styles apply (an inline <style> would have been refused).
  const styled = await page.evaluate(() => {
    const v = document.getElementById('v');
    return { display: getComputedStyle(v).display, error: getComputedStyle(v.shadowRoot.querySelector('[part=error]')).display };
  });
  assert.deepEqual(styled, { display: 'inline-block', error: 'none' });
  assert.deepEqual(
    events.filter((e) => e.type !== 'lines'),
    [],
  );
  assert.deepEqual(problems, []);
  await page.close();
});
