// Framing on a desktop screen (issue 17): the model is fitted into the part
// of the canvas that the info box and the panel leave free; view presets
// relative to the up axis (Y or Z); a colour scale for the curvature maps
// with the value the colours saturate at. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { assertUncovered, framing, useApp } from './app-page.mjs';

const app = useApp({}, { viewport: { width: 1280, height: 800 } });

const near = (a, b, message) =>
  assert.ok(
    a.every((x, i) => Math.abs(x - b[i]) < 1e-3),
    `${message}: ${a.map((x) => x.toFixed(4))} ≠ ${b}`,
  );
const camera = (partial) => app.page.evaluate((p) => window.crestline.update(p), partial);

test('1280×800: the bunny is framed clear of the info box and the panel', async () => {
  const f = await framing(app.page);
  assert.ok(f.count > 1000);
  assert.ok(f.free.right - f.free.left < f.width || f.free.bottom - f.free.top < f.height, 'the covers leave a smaller free area');
  assertUncovered(f);
  // Opening the statistics makes the info box taller: "fit to view" avoids it again.
  await app.page.evaluate(() => {
    document.getElementById('details').open = true;
    window.crestline.gui
      .controllersRecursive()
      .find((c) => c.property === 'fit')
      .$button.click();
  });
  assertUncovered(await framing(app.page));
});

test('1280×800: the panel fits the window as it opens; with every folder open it scrolls inside it', async () => {
  const panel = () =>
    app.page.evaluate(() => {
      const root = window.crestline.gui.domElement;
      const children = root.querySelector(':scope > .lil-children');
      return {
        bottom: root.getBoundingClientRect().bottom,
        content: children.scrollHeight,
        shown: children.clientHeight,
        overflow: getComputedStyle(children).overflowY,
      };
    });
  const start = await panel();
  assert.ok(start.bottom <= 800, `the panel ends at ${start.bottom}`);
  assert.ok(start.content <= start.shown, `its controls (${start.content} px) fit without scrolling (${start.shown} px)`);
  const folders = await app.page.evaluate(() => window.crestline.gui.foldersRecursive().map((f) => [f._title, f._closed]));
  await app.page.evaluate(() => window.crestline.gui.foldersRecursive().forEach((f) => f.open()));
  await app.page.waitForTimeout(400); // lil-gui's opening transition
  const open = await panel();
  assert.ok(open.bottom <= 800 && open.content > open.shown && open.overflow === 'auto', `all open: ${JSON.stringify(open)}: scrolls inside the window`);
  await app.page.evaluate((folders) => {
    for (const f of window.crestline.gui.foldersRecursive()) if (folders.find(([title]) => title === f._title)[1]) f.close();
  }, folders);
});

test('view presets with Y up, then with Z up', async () => {
  const s = 1 / Math.sqrt(3);
  const yUp = { front: [0, 0, 1], back: [0, 0, -1], left: [-1, 0, 0], right: [1, 0, 0], top: [0, 1, 0], bottom: [0, -1, 0], iso: [s, s, s] };
  for (const [preset, direction] of Object.entries(yUp)) {
    await camera({ preset });
    const f = await framing(app.page);
    near(f.direction, direction, `${preset} (Y up)`);
    near(f.up, [0, 1, 0], 'up');
    assertUncovered(f, 0.4);
  }
  const zUp = { front: [0, -1, 0], right: [1, 0, 0], top: [0, 0, 1], iso: [s, -s, s] };
  await camera({ upAxis: 'z' });
  for (const [preset, direction] of Object.entries(zUp)) {
    await camera({ preset });
    const f = await framing(app.page);
    near(f.direction, direction, `${preset} (Z up)`);
    near(f.up, [0, 0, 1], 'up');
    assertUncovered(f, 0.4);
  }
  await camera({ upAxis: 'y', preset: 'front' });
  near((await framing(app.page)).up, [0, 1, 0], 'back to Y up');
});

test('colour scale: κ max from −s to +s, |e max| from 0, s the 95th percentile of the values; hidden when shaded', async () => {
  const scale = () =>
    app.page.evaluate(() => {
      const text = (id) => document.getElementById(id).textContent;
      return {
        hidden: document.getElementById('scale').hidden,
        name: text('scale-name'),
        min: text('scale-min'),
        max: text('scale-max'),
        bar: getComputedStyle(document.getElementById('scale-bar')).backgroundImage,
      };
    });
  /** The 95th percentile of |values| (every value: the sample mesh is small). */
  const percentile = (field) =>
    app.page.evaluate((field) => {
      const values = Array.from(window.crestline.fields[field], Math.abs).sort((a, b) => a - b);
      return values[Math.floor(0.95 * (values.length - 1))];
    }, field);
  await camera({ view: 'kappaMax' });
  await app.page.waitForFunction(() => window.crestline.fields && !document.getElementById('scale').hidden);
  const kappa = await scale();
  const s = Number((await percentile('kappaMax')).toPrecision(3));
  assert.equal(kappa.name, 'κ max (1/L)');
  assert.equal(kappa.min, `−${s}`);
  assert.equal(kappa.max, `+${s}`);
  assert.match(kappa.bar, /linear-gradient/);
  await camera({ view: 'eMax' });
  const e = await scale();
  assert.equal(e.name, '|e max| (1/L²)');
  assert.equal(e.min, '0');
  assert.equal(e.max, String(Number((await percentile('eMax')).toPrecision(3))));
  await camera({ view: 'shaded' });
  assert.equal((await scale()).hidden, true);
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
