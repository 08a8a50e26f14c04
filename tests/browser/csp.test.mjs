// The app under a strict Content-Security-Policy: no 'unsafe-eval' (only
// 'wasm-unsafe-eval', which compiling WebAssembly needs), so any eval or
// new Function in the shipped bundle, the Emscripten glue or the worker
// would be refused and reported. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { launch } from './browser.mjs';
import { serve } from './server.mjs';
import { ROOT } from '../node/helpers.mjs';

const CSP = [
  "default-src 'self'",
  "script-src 'self' 'wasm-unsafe-eval' blob:",
  "worker-src 'self' blob:",
  "style-src 'self' 'unsafe-inline'",
  "img-src 'self' data: blob:",
  "font-src 'self' data:",
  "connect-src 'self' data: blob:",
].join('; ');

let server, browser, page;
const violations = [];
const pageErrors = [];

before(async () => {
  assert.ok(existsSync(join(ROOT, 'web/dist/index.html')), 'web/dist is missing: run web/build.sh');
  server = await serve({ '/': join(ROOT, 'web/dist') }, { 'Content-Security-Policy': CSP });
  browser = await launch();
  page = await browser.newPage({ viewport: { width: 800, height: 600 } });
  page.on('pageerror', (error) => pageErrors.push(error.message));
  page.on('console', (message) => {
    if (/Content Security Policy|unsafe-eval/i.test(message.text())) violations.push(message.text());
  });
  await page.addInitScript(() => {
    document.addEventListener('securitypolicyviolation', (e) => {
      window.__cspViolations = (window.__cspViolations ?? []).concat(`${e.violatedDirective}: ${e.blockedURI}`);
    });
  });
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
});

after(async () => {
  await browser?.close();
  server?.close();
});

test('no eval or new Function in the shipped JavaScript', () => {
  const files = [];
  const walk = (dir) => {
    for (const entry of readdirSync(dir, { withFileTypes: true })) {
      const path = join(dir, entry.name);
      if (entry.isDirectory()) walk(path);
      else if (entry.name.endsWith('.js')) files.push(path);
    }
  };
  walk(join(ROOT, 'web/dist'));
  assert.ok(files.length > 0);
  for (const file of files) {
    const text = readFileSync(file, 'utf8');
    assert.doesNotMatch(text, /new Function\s*\(/, `${file} calls new Function`);
    assert.doesNotMatch(text, /[^.\w]eval\s*\(/, `${file} calls eval`);
  }
});

test('the app computes the sample bunny under a strict CSP', async () => {
  await page.waitForFunction(() => (window.crestline?.results.length ?? 0) > 0 || document.body.dataset.state === 'error', null, {
    timeout: 60000,
  });
  assert.equal(await page.textContent('#error'), '', 'the page shows an error');
  const result = await page.evaluate(() => window.crestline.lastResult);
  assert.ok(result.lineCount > 0, 'the bunny has lines');
  assert.deepEqual(await page.evaluate(() => window.__cspViolations ?? []), []);
  assert.deepEqual(violations, []);
  assert.deepEqual(pageErrors, []);
});
