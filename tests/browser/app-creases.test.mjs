// The page's creases (issue 16): a box generated here and the fandisk CAD
// mesh show as many creases as the native CLI's --stats, drawn in their own
// layer (convex and concave in two shades), with a panel toggle and a legend
// entry; moving the crease angle re-runs the creases stage only. Needs
// web/dist (web/build.sh) and, for the counts, the native CLI.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';
import { boxObj } from './box-obj.mjs';
import { dropFiles, nextResult as waitForResult, useApp } from './app-page.mjs';
import { MESHES, NATIVE_CLI, ROOT, haveNativeCli } from '../node/helpers.mjs';

const OUT = join(ROOT, 'test-results');
const FANDISK = join(MESHES, 'cad/fandisk.obj');
const noFandisk = !existsSync(FANDISK) && `SKIPPED: ${FANDISK} is absent`;
const noCli = !haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built`;
const app = useApp({ '/meshes/': MESHES });

const nextResult = (action) => waitForResult(app.page, action);

/** The native CLI's --stats for a file, with extra flags. */
function nativeStats(file, flags = []) {
  mkdirSync(OUT, { recursive: true });
  return JSON.parse(execFileSync(NATIVE_CLI, [file, '-o', join(OUT, 'native-creases.obj'), '--stats', '-q', ...flags], { encoding: 'utf8' }));
}

/** What the page shows of the creases: the stats line's count, the layer, the legend. */
function shownCreases() {
  return app.page.evaluate(() => {
    const { viewer } = window.crestline;
    const stats = document.getElementById('stats').textContent;
    const legend = document.getElementById('legend-crease');
    return {
      statsCount: Number(/^creases (\d+)/m.exec(stats)?.[1] ?? NaN),
      types: [...(viewer.creaseLines?.types ?? [])],
      visible: viewer.creases.objects.map((o) => o.visible),
      segments: viewer.creases.objects.map((o) => o.userData.segments),
      legendShown: Boolean(legend && legend.offsetWidth > 0 && legend.textContent.includes('creases')),
      legendOff: legend?.classList.contains('off'),
      swatch: legend?.querySelector('.swatch').style.background,
    };
  });
}

test('a generated box: its 12 convex edges as creases, as many as the native CLI finds', async () => {
  const text = boxObj();
  const result = await nextResult(() => dropFiles(app.page, [{ name: 'box.obj', text }]));
  assert.ok(result.ran.includes('creases'), `ran ${result.ran}`);
  const shown = await shownCreases();
  console.log(`box: ${result.stats.creases} creases, ${shown.types.length} drawn, segments ${shown.segments}`);
  assert.equal(result.stats.creases, 12, 'a box has 12 sharp edges');
  assert.equal(shown.statsCount, result.stats.creases, 'the stats line shows the count');
  assert.equal(shown.types.length, result.stats.creases, 'every crease is drawn');
  assert.ok(
    shown.types.every((t) => t === 0),
    'a box has only convex creases',
  );
  // Each box edge is 24 segments long: 12 edges, 288 segments, all convex.
  assert.deepEqual(shown.segments, [288, 0]);
  if (noCli) return console.log(`# ${noCli}`);
  const file = join(OUT, 'box.obj');
  writeFileSync(file, text);
  assert.equal(result.stats.creases, nativeStats(file).creases, 'crease count: page = native CLI');
});

test('fandisk: the crease count shown matches the native CLI; the toggle hides them; the legend shows them', { skip: noFandisk }, async () => {
  const result = await nextResult(() => dropFiles(app.page, ['cad/fandisk.obj']));
  const shown = await shownCreases();
  console.log(`fandisk: ${result.stats.creases} creases (angle ${result.stats.creaseAngle}°), convex/concave segments ${shown.segments}`);
  assert.ok(result.stats.creases > 10, 'a CAD part has many creases');
  assert.equal(shown.statsCount, result.stats.creases);
  assert.equal(result.creaseCount, result.stats.creases);
  assert.ok(shown.segments[0] > 0 && shown.segments[1] > 0, 'fandisk has convex and concave creases');
  assert.deepEqual(shown.visible, [true, true]);
  if (noCli) console.log(`# ${noCli}`);
  else assert.equal(result.stats.creases, nativeStats(FANDISK).creases, 'crease count: page = native CLI');

  // The legend: an entry in the crease colour and its concave shade.
  const params = await app.page.evaluate(() => window.crestline.params);
  assert.ok(shown.legendShown, 'the legend has a creases entry');
  assert.equal(shown.legendOff, false);
  assert.match(shown.swatch, /linear-gradient/);

  // The toggle hides both kinds and strikes the legend entry through.
  await app.page.evaluate(() => window.crestline.update({ showCreases: false }));
  let hidden = await shownCreases();
  assert.deepEqual(hidden.visible, [false, false]);
  assert.equal(hidden.legendOff, true);
  await app.page.evaluate(() => window.crestline.update({ showCreases: true, creaseColor: '#00aa44' }));
  hidden = await shownCreases();
  assert.deepEqual(hidden.visible, [true, true]);
  const colours = await app.page.evaluate(() => window.crestline.viewer.creases.objects.map((o) => `#${o.material.color.getHexString()}`));
  assert.equal(colours[0], '#00aa44', 'convex creases in the chosen colour');
  assert.notEqual(colours[1], colours[0], 'concave creases in another shade');
  await app.page.evaluate((c) => window.crestline.update({ creaseColor: c }), params.creaseColor);

  // The crease angle is a selection: only the creases stage runs, and the
  // count follows the CLI at that angle.
  const angle = 60;
  const steeper = await nextResult(() => app.page.evaluate((a) => window.crestline.update({ autoCreaseAngle: false, creaseAngle: a }), angle));
  assert.deepEqual(steeper.ran, ['creases']);
  assert.ok(
    steeper.stats.creases !== result.stats.creases || steeper.stats.creaseLength < result.stats.creaseLength,
    'a steeper angle selects fewer crease edges',
  );
  assert.equal((await shownCreases()).statsCount, steeper.stats.creases);
  if (!noCli) assert.equal(steeper.stats.creases, nativeStats(FANDISK, ['--crease-angle', String(angle)]).creases);
  await nextResult(() => app.page.evaluate(() => window.crestline.update({ autoCreaseAngle: true })));
});
