// The app under a strict Content-Security-Policy: no 'unsafe-eval' (only
// 'wasm-unsafe-eval', which compiling WebAssembly needs), so any eval or
// new Function in the shipped bundle, the Emscripten glue or the worker
// would be refused and reported. Draco and meshopt GLBs dropped on it are
// decompressed in the worker by the npm decoders (as wasm/cli.mjs does) and
// give the native CLI's lines. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { dropFiles, nextResult } from './app-page.mjs';
import { launch } from './browser.mjs';
import { serve } from './server.mjs';
import { MESHES, NATIVE_CLI, ROOT, haveMeshes, haveNativeCli } from '../node/helpers.mjs';

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
  server = await serve({ ...(haveMeshes ? { '/meshes/': MESHES } : {}), '/': join(ROOT, 'web/dist') }, { 'Content-Security-Policy': CSP });
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

const noCompressed = (!haveMeshes && `SKIPPED: ${MESHES} is absent`) || (!haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built`);

test("Draco and meshopt GLBs: decompressed in the worker under the strict CSP, the native CLI's lines", { skip: noCompressed }, async () => {
  const dir = mkdtempSync(join(tmpdir(), 'crestline-csp-'));
  try {
    for (const file of ['glb/pmndrs-bunny-draco.glb', 'glb/pirate-meshopt.glb']) {
      const result = await nextResult(page, () => dropFiles(page, [file]));
      const native = JSON.parse(execFileSync(NATIVE_CLI, [join(MESHES, file), '-o', join(dir, 'lines.obj'), '--stats', '-q'], { encoding: 'utf8' }));
      console.log(`${file}: page ${result.stats.ridges} ridges, ${result.stats.valleys} valleys; native ${native.ridges}, ${native.valleys}`);
      assert.deepEqual([result.stats.triangles, result.stats.ridges, result.stats.valleys], [native.triangles, native.ridges, native.valleys], file);
      assert.ok(native.triangles > 1000, `${file}: ${native.triangles} triangles`);
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
  assert.deepEqual(await page.evaluate(() => window.__cspViolations ?? []), []);
  assert.deepEqual(violations, []);
  assert.deepEqual(pageErrors, []);
});
