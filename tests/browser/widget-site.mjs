// The set-up the widget tests share: <crestline-viewer> built afresh
// (web/vite.widget.config.js, as web/build.sh does) into a private folder,
// since web/dist is rebuilt by other work while tests run, and served from a
// "CDN" origin while the pages and meshes come from the site's. Needs wasm/dist.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { serve } from './server.mjs';
import { ROOT } from '../node/helpers.mjs';

// Neither origin is cross-origin isolated: the widget must work on ordinary pages.
const SITE_HEADERS = {
  'Cross-Origin-Opener-Policy': null,
  'Cross-Origin-Embedder-Policy': null,
  'Cross-Origin-Resource-Policy': null,
  'Access-Control-Allow-Origin': '*',
};
const CDN_HEADERS = { ...SITE_HEADERS, 'Cross-Origin-Resource-Policy': 'cross-origin' };

/**
 * Builds the widget and starts the two servers: the CDN serves the widget,
 * the site serves `roots` (prefix → folder) with the headers that
 * `siteHeaders(cdnUrl)` returns added. Returns {siteUrl, cdnUrl, close()}.
 */
export async function serveWidgetSite(roots, siteHeaders = () => ({})) {
  assert.ok(existsSync(join(ROOT, 'wasm/dist/crestline.wasm')), 'wasm/dist is missing: run wasm/build.sh');
  const dist = mkdtempSync(join(tmpdir(), 'crestline-widget-dist-'));
  execFileSync(join(ROOT, 'node_modules/.bin/vite'), ['build', '--config', join(ROOT, 'web/vite.widget.config.js'), '--outDir', dist, '--logLevel', 'error'], {
    cwd: ROOT,
    stdio: ['ignore', 'ignore', 'inherit'],
  });
  const cdn = await serve({ '/': dist }, CDN_HEADERS);
  // "localhost" vs "127.0.0.1": another origin even on the same port range.
  const cdnUrl = `http://localhost:${cdn.address().port}`;
  const site = await serve(roots, { ...SITE_HEADERS, ...siteHeaders(cdnUrl) });
  return {
    siteUrl: `http://127.0.0.1:${site.address().port}`,
    cdnUrl,
    close() {
      site.close();
      cdn.close();
      rmSync(dist, { recursive: true, force: true });
    },
  };
}
