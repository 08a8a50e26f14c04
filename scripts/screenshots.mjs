// The README's pictures of the page: the app (web/dist) in headless
// Chromium on the built-in sample, at a desktop and a phone size, written to
// docs/. Run after web/build.sh: `node scripts/screenshots.mjs`.
import { join } from 'node:path';
import { openApp, sampleReady } from '../tests/browser/app-page.mjs';
import { ROOT } from '../tests/node/helpers.mjs';

const SIZES = [
  { file: 'page-desktop.png', viewport: { width: 1280, height: 800 } },
  { file: 'page-phone.png', viewport: { width: 390, height: 844 } },
];

for (const { file, viewport } of SIZES) {
  const app = await openApp({}, { viewport });
  try {
    await sampleReady(app.page);
    await app.page.waitForTimeout(300); // the last frame
    await app.page.screenshot({ path: join(ROOT, 'docs', file) });
    console.log(`docs/${file}: ${viewport.width}×${viewport.height}`);
  } finally {
    await app.close();
  }
}
