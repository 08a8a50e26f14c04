// A browser that cannot compile the engine (no WebAssembly SIMD, or a broken
// .wasm): the page shows one sentence saying so, and the worker is not
// restarted in a loop. The server answers the module's .wasm with bytes that
// are no WebAssembly, so the glue's compile fails as it would without SIMD.
// Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { mkdtempSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { launch } from './browser.mjs';
import { serve } from './server.mjs';
import { ROOT } from '../node/helpers.mjs';

let browser, server, page, wasm;
const pageErrors = [];
/** Fetches of the module's .wasm, the worker's included. */
let wasmFetches = 0;

before(async () => {
  const dist = join(ROOT, 'web/dist');
  // Both builds: the plain one and the threaded one (crestline-mt, which the isolated page tries first).
  const modules = readdirSync(join(dist, 'assets')).filter((f) => /^crestline-.*\.wasm$/.test(f));
  wasm = modules.find((f) => !f.startsWith('crestline-mt'));
  assert.ok(wasm && modules.length === 2, `web/dist has both modules: ${modules}`);
  const broken = mkdtempSync(join(tmpdir(), 'crestline-no-engine-'));
  writeFileSync(join(broken, 'index.html'), 'not WebAssembly');
  // The app's modules, and the widget's (beside crestline-viewer.js).
  const brokenModules = Object.fromEntries(modules.map((f) => [`/assets/${f}`, broken]));
  server = await serve({ ...brokenModules, '/crestline.wasm': broken, '/crestline-mt.wasm': broken, '/': dist });
  browser = await launch();
  page = await browser.newPage();
  page.on('pageerror', (error) => pageErrors.push(error.message));
  page.context().on('request', (request) => {
    if (request.url().endsWith(wasm)) wasmFetches += 1;
  });
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
});

after(async () => {
  await browser?.close();
  server?.close();
});

test('an engine that cannot start: one sentence on the page naming WebAssembly SIMD, no restart loop', async () => {
  await page.waitForFunction(() => document.body.dataset.state === 'error', null, { timeout: 30000 });
  const error = await page.textContent('#error');
  assert.match(error, /^The WebAssembly module failed to start \(.*CompileError.*\)\. This browser may lack WebAssembly SIMD/);
  assert.ok(await page.isVisible('#error'), 'the error line is shown');
  // The worker was started once: the glue fetches the module at most twice
  // (streaming, then as bytes); a restart loop would fetch it again and again.
  await page.waitForTimeout(1000);
  console.log(`# fetches of the module: ${wasmFetches}`);
  assert.ok(wasmFetches >= 1 && wasmFetches <= 2, `${wasmFetches} fetches of the module`);
  assert.equal(await page.textContent('#error'), error, 'the sentence stays');
  assert.ok(
    pageErrors.every((m) => m.includes('failed to start')),
    `only the engine's failure is uncaught: ${pageErrors.join(' | ')}`,
  );
});

test('the widget: the same sentence in its error line and as an error event', async () => {
  const widget = await browser.newPage();
  await widget.goto(`http://127.0.0.1:${server.address().port}/embed.html`);
  await widget.waitForFunction(() => document.querySelector('crestline-viewer')?.shadowRoot?.querySelector('[part="error"]')?.textContent, null, {
    timeout: 30000,
  });
  const error = await widget.evaluate(() => document.querySelector('crestline-viewer').shadowRoot.querySelector('[part="error"]').textContent);
  assert.match(error, /^The WebAssembly module failed to start \(.*CompileError.*\)\. This browser may lack WebAssembly SIMD/);
  await widget.close();
});
