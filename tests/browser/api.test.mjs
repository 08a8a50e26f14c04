// The README's JavaScript API example as a web page: bundled by Vite (which
// resolves `from 'crestline'` through package.json "exports" and emits the
// worker and crestline.wasm as files), run in Chromium as written. Needs wasm/dist.
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, test } from 'node:test';
import { build } from 'vite';
import { launch } from './browser.mjs';
import { serve } from './server.mjs';
import { ROOT } from '../node/helpers.mjs';
import { readmeExample } from '../node/readme-example.mjs';

// Inside the package, so that 'crestline' resolves by its own name.
const site = join(ROOT, 'test-results', 'api-example');
let server, browser;
after(async () => {
  await browser?.close();
  server?.close();
  rmSync(site, { recursive: true, force: true });
});

test('the README example, bundled by Vite, runs as written in Chromium', async () => {
  assert.ok(existsSync(join(ROOT, 'wasm/dist/crestline.wasm')), 'wasm/dist is missing: run wasm/build.sh');
  rmSync(site, { recursive: true, force: true });
  mkdirSync(site, { recursive: true });
  writeFileSync(
    join(site, 'index.html'),
    '<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,"><script type="module" src="./main.js"></script>\n',
  );
  writeFileSync(
    join(site, 'main.js'),
    `${readmeExample()}
window.result = {
  ridges: ridges.length, valleys: valleys.length, stats,
  float32: ridges[0].points instanceof Float32Array,
  after: { ridges: lines.ridgeCount, valleys: lines.valleyCount, threshold: lines.stats.threshold },
  segments: lines.layer.objects[0].geometry.getAttribute('instanceShown').count,
};
`,
  );
  await build({
    root: site,
    configFile: false,
    base: './',
    logLevel: 'error',
    worker: { format: 'es' },
    build: { outDir: join(site, 'dist'), target: 'es2022', assetsInlineLimit: 0, chunkSizeWarningLimit: 4000 },
  });
  server = await serve({ '/': join(site, 'dist') });
  browser = await launch();
  const page = await browser.newPage();
  const errors = [];
  const logs = [];
  page.on('pageerror', (error) => errors.push(error.message));
  page.on('console', (message) => logs.push(message.text()));
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
  await page.waitForFunction(() => window.result, null, { timeout: 60000 }).catch(() => assert.fail(`no result; errors: ${errors} logs: ${logs}`));
  const result = await page.evaluate(() => window.result);
  assert.deepEqual(errors, []);
  assert.ok(
    logs.some((l) => l.startsWith(`${result.ridges} ridges, ${result.valleys} valleys, threshold `)),
    `console: ${logs}`,
  );
  assert.ok(result.ridges > 0 && result.float32);
  assert.deepEqual([result.stats.ridges, result.stats.valleys, result.stats.triangles], [result.ridges, result.valleys, 200 * 32 * 2]);
  assert.equal(result.after.threshold, 2 * result.stats.threshold);
  assert.ok(result.segments > 0, 'FeatureLines built its line geometry');
});
