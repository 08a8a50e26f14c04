// The app on a phone (390×844, issue 17): the panel starts collapsed, the
// info box is a compact strip clear of it, and "fit to view" uses both fields
// of view, so the portrait canvas shows the whole model. Needs web/dist.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { assertUncovered, framing, useApp } from './app-page.mjs';

const app = useApp({}, { viewport: { width: 390, height: 844 } });

/** The 2D bounding box of the model's vertices projected to normalised device coordinates, after the next frame. */
function projectedBox() {
  return app.page.evaluate(async () => {
    const { viewer } = window.crestline;
    await new Promise((resolve) => requestAnimationFrame(resolve));
    const mesh = viewer.surface.mesh;
    const positions = mesh.geometry.attributes.position;
    viewer.camera.updateMatrixWorld();
    const box = [Infinity, Infinity, -Infinity, -Infinity];
    const p = viewer.camera.position.clone();
    for (let i = 0; i < positions.count; i++) {
      p.fromBufferAttribute(positions, i).applyMatrix4(mesh.matrixWorld).project(viewer.camera);
      box[0] = Math.min(box[0], p.x);
      box[1] = Math.min(box[1], p.y);
      box[2] = Math.max(box[2], p.x);
      box[3] = Math.max(box[3], p.y);
    }
    return { box, count: positions.count, aspect: viewer.camera.aspect };
  });
}

function assertInside({ box, count, aspect }) {
  assert.ok(count > 1000, `the sample is loaded (${count} vertices)`);
  assert.ok(aspect < 0.6, `a portrait canvas (aspect ${aspect})`);
  const [x0, y0, x1, y1] = box;
  assert.ok(x0 >= -1 && x1 <= 1 && y0 >= -1 && y1 <= 1, `the projected box [${box.map((v) => v.toFixed(3))}] lies inside the canvas`);
  assert.ok(x1 - x0 > 0.8, `the model fills the width (${(x1 - x0).toFixed(2)} of 2), not a speck`);
}

test('390×844: the panel starts collapsed; the info box is compact and clear of it', async () => {
  const layout = await app.page.evaluate(() => {
    const { gui } = window.crestline;
    const panel = gui.domElement.getBoundingClientRect();
    const hud = document.getElementById('hud').getBoundingClientRect();
    const overlap = !(hud.right <= panel.left || panel.right <= hud.left || hud.bottom <= panel.top || panel.bottom <= hud.top);
    return { closed: gui._closed, details: document.getElementById('details').open, panelHeight: panel.height, hudHeight: hud.height, overlap, innerHeight };
  });
  assert.equal(layout.closed, true, 'lil-gui is collapsed');
  assert.ok(layout.panelHeight < 60, `the collapsed panel is a title bar (${layout.panelHeight} px)`);
  assert.equal(layout.details, false, 'the statistics are folded away');
  assert.ok(layout.hudHeight < 0.25 * layout.innerHeight, `the info box is compact (${layout.hudHeight} px of ${layout.innerHeight})`);
  assert.equal(layout.overlap, false, 'the info box does not cover the panel');
});

test('390×844: the framed model\'s projected bounding box lies inside the canvas, also after orbiting and "fit to view"', async () => {
  assertInside(await projectedBox());
  await app.page.evaluate(() => {
    const { viewer, gui } = window.crestline;
    viewer.camera.position.set(5, 1, 0.5); // orbit to the side, far off
    viewer.controls.update();
    gui
      .controllersRecursive()
      .find((c) => c.property === 'fit')
      .$button.click();
  });
  assertInside(await projectedBox());
});

test('390×844: the model is clear of the info strip and the collapsed panel', async () => {
  assertUncovered(await framing(app.page));
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
