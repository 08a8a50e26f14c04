// A new mesh's first lines (issue 14): the info box keeps its size when the
// statistics arrive, so the view framed when the surface came stays (no second
// draw of a large surface); only a box that grew over the model frames it
// again. And the app's worker warms its glTF reader up after the sample's
// lines. A portrait window, where the model is framed below the info box (its
// height matters). Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { assertUncovered, dropFiles, framing, nextResult, useApp } from './app-page.mjs';
import { MESHES, haveMeshes } from '../node/helpers.mjs';
import { WARM_UP_ROUNDS } from '../../web/src/worker/warm-up.js';

const noMeshes = !haveMeshes && `SKIPPED: ${MESHES} is absent`;
const app = useApp({ '/meshes/': MESHES }, { viewport: { width: 700, height: 1000 } });

/** The camera and the info box when the new surface is framed ('loaded'), and again once its lines are shown. */
async function dropAndWatch(file, onLoaded = '') {
  await app.page.evaluate((onLoaded) => {
    const { viewer, hooks } = window.crestline;
    const snap = () => ({
      camera: [...viewer.camera.matrixWorld.elements, ...viewer.camera.projectionMatrix.elements],
      hud: document.getElementById('hud').getBoundingClientRect().height,
    });
    window.__watch = {};
    window.__snap = snap;
    hooks.loaded = () => {
      viewer.camera.updateMatrixWorld();
      window.__watch.loaded = snap();
      // A test's way to make the box grow when the lines come.
      if (onLoaded) window.crestline.state.notes = [onLoaded];
      hooks.loaded = null;
    };
  }, onLoaded);
  await nextResult(app.page, () => dropFiles(app.page, [file]));
  // Two frames after the one that shows the lines: a refit would have happened by then.
  return app.page.evaluate(async () => {
    for (let i = 0; i < 3; i++) await new Promise((resolve) => requestAnimationFrame(resolve));
    window.crestline.viewer.camera.updateMatrixWorld();
    return { ...window.__watch, lines: window.__snap() };
  });
}

test("the app's worker warms its glTF reader and the pipeline up, in rounds, once the sample has its lines", async () => {
  // crestline-mt's idle pthreads never answer an evaluate: ask every worker, each for 2 s at most.
  const ask = () =>
    Promise.all(
      app.page
        .workers()
        .map((w) =>
          Promise.race([w.evaluate(() => self.crestlineWarmedUp?.rounds).catch(() => undefined), new Promise((resolve) => setTimeout(resolve, 2000))]),
        ),
    );
  let answers = [];
  for (const start = Date.now(); Date.now() - start < 30000 && !answers.includes(WARM_UP_ROUNDS); await new Promise((r) => setTimeout(r, 200)))
    answers = await ask();
  assert.ok(answers.includes(WARM_UP_ROUNDS), `the warm-up ran its ${WARM_UP_ROUNDS} rounds: ${answers}`);
});

test('the statistics arrive: the info box does not grow and the view stays as framed', { skip: noMeshes }, async () => {
  const watched = await dropAndWatch('classic/spot.obj');
  assert.ok(watched.lines.hud <= watched.loaded.hud, `the box ${watched.loaded.hud} px high when framed, ${watched.lines.hud} px with the statistics`);
  assert.deepEqual(watched.lines.camera, watched.loaded.camera, 'not framed again');
  // Framed for the box with its progress bar, which then goes: a little more room around the model.
  assertUncovered(await framing(app.page), 0.5);
});

test('a box that grew over the model when the lines came: the view is framed again, clear of it', { skip: noMeshes }, async () => {
  const long = 'A note long enough to make the info box taller than the statistics alone. '.repeat(8);
  const watched = await dropAndWatch('classic/bunny-closed.obj', long);
  assert.ok(watched.lines.hud > watched.loaded.hud + 50, `the box grew: ${watched.loaded.hud} → ${watched.lines.hud} px`);
  assert.notDeepEqual(watched.lines.camera, watched.loaded.camera, 'framed again');
  assertUncovered(await framing(app.page));
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
