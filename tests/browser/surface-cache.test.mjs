// The viewer's surface cache (web/src/three/surface-cache.js) in the app: the
// kept picture plus the lines draws what the plain render draws (pixels
// compared, at pixel ratio 1 and 2), a threshold change or a line toggle
// does not draw the surface again, and a camera move, a resize, the
// background and a colour map do. Surface draws are counted by the surface
// mesh's own onBeforeRender, not by the cache. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { assertUncovered, dropFiles, framing, nextResult, useApp } from './app-page.mjs';
import { ROOT } from '../node/helpers.mjs';

const MESHES = join(ROOT, '../shared/meshes');
const app = useApp({ '/meshes/': MESHES });

/**
 * Installs the counters; the sample (6k triangles) goes through the cache as
 * a large mesh would, its picture multisampled as on a GPU (`multisample`:
 * true) or as on this software rasterizer (null: one sample a pixel).
 */
function instrument(multisample = true) {
  return app.page.evaluate((multisample) => {
    const { viewer } = window.crestline;
    viewer.surfaceCache.multisample = multisample;
    viewer.cacheMinTriangles = 0;
    window.surfaceDraws = 0;
    viewer.surface.mesh.onBeforeRender = () => window.surfaceDraws++;
  }, multisample);
}

/** Surface draws and frames drawn during `action` and the two animation frames after it; `value`: what it returned. */
async function counted(action) {
  const before = await app.page.evaluate(() => [window.surfaceDraws, window.crestline.viewer.renderCount]);
  const value = await action();
  const after = await app.page.evaluate(async () => {
    for (let i = 0; i < 2; i++) await new Promise((resolve) => requestAnimationFrame(resolve));
    return [window.surfaceDraws, window.crestline.viewer.renderCount];
  });
  return { surface: after[0] - before[0], frames: after[1] - before[1], value };
}

/**
 * The plain render's pixels (scene and camera through renderer.render)
 * against those of a frame that fills the cache and of one drawn from it,
 * each read in the task that drew it, with and without the lines: how many
 * pixels differ from the plain render's, by how much at most (any channel),
 * and how many show a line colour in each.
 */
function comparePictures() {
  return app.page.evaluate(() => {
    const { viewer, params } = window.crestline;
    const source = viewer.renderer.domElement;
    const read = () => {
      const canvas = new OffscreenCanvas(source.width, source.height);
      const context = canvas.getContext('2d');
      context.drawImage(source, 0, 0);
      return context.getImageData(0, 0, source.width, source.height).data;
    };
    const rgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
    const lineColors = [rgb(params.ridgeColor), rgb(params.valleyColor)];
    const linePixels = (picture) => {
      let count = 0;
      for (let i = 0; i < picture.length; i += 4)
        if (lineColors.some((t) => Math.abs(picture[i] - t[0]) + Math.abs(picture[i + 1] - t[1]) + Math.abs(picture[i + 2] - t[2]) < 40)) count++;
      return count;
    };
    const compare = (plain, picture) => {
      let differ = 0,
        most = 0;
      for (let i = 0; i < plain.length; i += 4) {
        const d = Math.max(...[0, 1, 2].map((c) => Math.abs(picture[i + c] - plain[i + c])));
        if (d) differ++;
        most = Math.max(most, d);
      }
      return { differ, most, lines: linePixels(picture), plainLines: linePixels(plain) };
    };
    const pictures = (lines) => {
      viewer.lines.group.visible = viewer.creases.group.visible = lines;
      viewer.renderer.render(viewer.scene, viewer.camera);
      const plain = read();
      viewer.surfaceCache.invalidate();
      viewer.draw();
      const filled = compare(plain, read());
      const draws = window.surfaceDraws;
      viewer.draw();
      return { filled, kept: compare(plain, read()), keptDrewSurface: window.surfaceDraws - draws };
    };
    const result = { pixels: source.width * source.height, surface: pictures(false), lines: pictures(true) };
    viewer.lines.group.visible = viewer.creases.group.visible = true;
    return result;
  });
}

function assertSamePicture({ pixels, surface, lines }, label) {
  for (const [name, { filled, kept, keptDrewSurface }] of Object.entries({ surface, lines })) {
    assert.equal(keptDrewSurface, 0, `${label}, ${name}: the second frame draws the picture kept`);
    assert.deepEqual(kept, filled, `${label}, ${name}: the picture kept draws what the frame that kept it drew`);
  }
  // Without the lines: the plain render's pixels, every one.
  assert.equal(surface.filled.differ, 0, `${label}: surface pixels differing from the plain render's (max ${surface.filled.most})`);
  // With them: only line edges may differ (see surface-cache.js), and the lines keep their pixels within 10 % (6 % more here: fewer line edges hidden).
  const { differ, most, lines: shown, plainLines } = lines.filled;
  assert.ok(plainLines > 500 * (pixels / 750000), `${label}: ${plainLines} line pixels in view`);
  assert.ok(Math.abs(shown - plainLines) <= 0.1 * plainLines, `${label}: ${shown} line pixels, the plain render ${plainLines}`);
  assert.ok(differ <= 0.6 * plainLines, `${label}: ${differ} pixels differ from the plain render's (max ${most}), ${plainLines} line pixels`);
}

test('the cached surface and the lines draw the plain render’s pixels, at pixel ratio 1 and 2', async () => {
  await instrument();
  const one = await comparePictures();
  console.log(`# pixel ratio 1: ${JSON.stringify(one)}`);
  assertSamePicture(one, 'pixel ratio 1');
  await app.page.evaluate(() => {
    const { viewer } = window.crestline;
    viewer.renderer.setPixelRatio(2);
    viewer.resize();
  });
  const two = await comparePictures();
  console.log(`# pixel ratio 2: ${JSON.stringify(two)}`);
  assert.equal(two.pixels, 4 * one.pixels);
  assertSamePicture(two, 'pixel ratio 2');
  await app.page.evaluate(() => {
    const { viewer } = window.crestline;
    viewer.renderer.setPixelRatio(1);
    viewer.resize();
  });
});

test('on this software rasterizer the picture has one sample a pixel: the plain render’s pixels but at the surface’s edges', async () => {
  await instrument(null);
  const software = await app.page.evaluate(() => {
    const { viewer } = window.crestline;
    const gl = viewer.renderer.getContext();
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return { name: gl.getParameter(info.UNMASKED_RENDERER_WEBGL), samples: viewer.surfaceCache.samples(viewer.renderer) };
  });
  assert.match(software.name, /SwiftShader/, 'headless Chromium rasterises with SwiftShader');
  assert.equal(software.samples, 0);
  const one = await comparePictures();
  console.log(`# one sample a pixel: ${JSON.stringify(one)}`);
  for (const [name, { filled, kept, keptDrewSurface }] of Object.entries({ surface: one.surface, lines: one.lines })) {
    assert.equal(keptDrewSurface, 0, `${name}: the second frame draws the picture kept`);
    assert.deepEqual(kept, filled, `${name}: the picture kept draws what the frame that kept it drew`);
  }
  // Without the lines: the pixels on the surface's silhouette and folds differ, the rest are the plain render's.
  const { surface, lines, pixels } = one;
  assert.ok(surface.filled.differ > 0, 'no pixel differs: the picture was multisampled');
  assert.ok(surface.filled.differ < 0.02 * pixels, `${surface.filled.differ} of ${pixels} pixels differ`);
  // With them, the lines keep their pixels within 10 %, as multisampled.
  assert.ok(Math.abs(lines.filled.lines - lines.filled.plainLines) <= 0.1 * lines.filled.plainLines, JSON.stringify(lines.filled));
  // Told to, the picture is multisampled again (a new target).
  await instrument(true);
  assert.equal((await comparePictures()).surface.filled.differ, 0);
});

test('a threshold change (shaded or over a colour map) and a line toggle draw the lines over the picture kept', async () => {
  await instrument();
  await counted(() => app.page.evaluate(() => window.crestline.viewer.render())); // the picture is current
  const threshold = await app.page.evaluate(() => window.crestline.lastResult.stats.threshold);
  const rethreshold = await counted(() =>
    nextResult(app.page, () => app.page.evaluate((t) => window.crestline.update({ autoThreshold: false, threshold: 2 * t }), threshold)),
  );
  assert.deepEqual(rethreshold.value.ran, ['filter']);
  assert.ok(rethreshold.frames >= 1, `a frame showed the new lines: ${JSON.stringify(rethreshold)}`);
  assert.equal(rethreshold.surface, 0, 'surface draws for a threshold change');
  const toggle = await counted(() => app.page.evaluate(() => window.crestline.update({ showRidges: false })));
  assert.ok(toggle.frames >= 1);
  assert.equal(toggle.surface, 0, 'surface draws for hiding the ridges');
  await counted(() => app.page.evaluate(() => window.crestline.update({ showRidges: true })));
  // A colour map stays on the surface through a threshold change: the surface is not drawn again either.
  await counted(async () => {
    await app.page.evaluate(() => window.crestline.update({ view: 'kappaMax' }));
    await app.page.waitForFunction(() => window.crestline.fields);
  });
  const mapped = await counted(() =>
    nextResult(app.page, () => app.page.evaluate((t) => window.crestline.update({ autoThreshold: false, threshold: t }), threshold)),
  );
  assert.ok(mapped.frames >= 1);
  assert.equal(mapped.surface, 0, 'surface draws for a threshold change over a colour map');
  await counted(() => app.page.evaluate(() => window.crestline.update({ view: 'shaded' })));
});

test('a camera move, a resize, the background and a colour map draw the surface again, once', async () => {
  await instrument();
  await counted(() => app.page.evaluate(() => window.crestline.viewer.render()));
  const orbit = await counted(() =>
    app.page.evaluate(() => {
      const { camera, controls } = window.crestline.viewer;
      camera.position.applyAxisAngle(camera.up, 0.3);
      controls.update(); // its 'change' asks for a frame
    }),
  );
  assert.equal(orbit.surface, 1, `a camera move: ${JSON.stringify(orbit)}`);
  const still = await counted(() => app.page.evaluate(() => window.crestline.viewer.render()));
  assert.deepEqual([still.surface, still.frames], [0, 1], 'the next frame with the camera still');
  const resize = await counted(async () => {
    const frames = await app.page.evaluate(() => window.crestline.viewer.renderCount);
    await app.page.setViewportSize({ width: 900, height: 700 });
    await app.page.waitForFunction(() => window.crestline.viewer.renderer.domElement.clientWidth === 900);
    // The ResizeObserver asks for its frame after the animation frames of
    // the frame that laid the page out, so counting two frames from here
    // can end before it is drawn: wait for it.
    await app.page.waitForFunction((n) => window.crestline.viewer.renderCount > n, frames);
  });
  assert.equal(resize.surface, 1, `a resize: ${JSON.stringify(resize)}`);
  const dark = await counted(() => app.page.evaluate(() => window.crestline.update({ dark: true })));
  assert.equal(dark.surface, 1, `the dark background: ${JSON.stringify(dark)}`);
  const map = await counted(() => app.page.evaluate(() => window.crestline.update({ view: 'kappaMax' })));
  assert.ok(map.surface >= 1, `a colour map: ${JSON.stringify(map)}`);
  const shaded = await counted(() => app.page.evaluate(() => window.crestline.update({ view: 'shaded' })));
  assert.ok(shaded.surface >= 1, `back to shading: ${JSON.stringify(shaded)}`);
  assert.deepEqual(app.pageErrors, []);
});

test(
  'a new mesh: its first lines are drawn over the surface kept, the view framed again after them',
  { skip: !existsSync(join(MESHES, 'classic/mannequin.obj')) },
  async () => {
    await instrument();
    await app.page.evaluate(() => {
      const { viewer } = window.crestline;
      const draw = viewer.draw.bind(viewer);
      window.frames = [];
      viewer.draw = () => {
        const before = window.surfaceDraws;
        draw();
        window.frames.push({ results: window.crestline.results.length, surface: window.surfaceDraws - before });
      };
    });
    const results = await app.page.evaluate(() => window.crestline.results.length);
    await nextResult(app.page, () => dropFiles(app.page, ['classic/mannequin.obj']));
    const frames = await app.page.evaluate(async () => {
      for (let i = 0; i < 3; i++) await new Promise((resolve) => requestAnimationFrame(resolve));
      return window.frames;
    });
    console.log(`# frames (results, surface draws): ${JSON.stringify(frames)}`);
    const lines = frames.findIndex((f) => f.results > results);
    assert.ok(lines > 0, `frames: ${JSON.stringify(frames)}`);
    assert.equal(frames[lines].surface, 0, `the lines' frame draws the surface kept: ${JSON.stringify(frames)}`);
    // Framed for the info box with its statistics: a fresh fit moves nothing.
    assertUncovered(await framing(app.page), 0.3);
    const refit = await app.page.evaluate(() => {
      const { viewer } = window.crestline;
      const camera = () => [...viewer.camera.position.toArray(), ...viewer.camera.projectionMatrix.elements];
      const before = camera();
      viewer.fitView();
      return camera().map((x, i) => Math.abs(x - before[i]));
    });
    assert.ok(Math.max(...refit) < 1e-9, `a fresh fit moves the camera by ${Math.max(...refit)}`);
  },
);
