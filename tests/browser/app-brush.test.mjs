// The smoothing brush measures its radius along the surface (issue 17): on a
// thin slab, a stroke on the top face with a radius many times the slab's
// thickness paints top vertices only, where a straight-line radius would
// reach through to the bottom face. A move recolours only the vertices it
// touched. Needs web/dist (web/build.sh). Its speed: bench/brush.mjs.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { dropFiles, nextResult, useApp } from './app-page.mjs';
import { boxObj } from './box-obj.mjs';

const app = useApp({}, { viewport: { width: 1000, height: 750 } });

test('a thin slab: the brush paints the top face only, and only the touched colours are sent', async () => {
  // 2 × 2 × 0.05, 40×40 quads a face: the top face at z = +0.025 faces the front view.
  const slab = boxObj({ size: [2, 2, 0.05], n: 40 });
  const result = await nextResult(app.page, () => dropFiles(app.page, [{ name: 'slab.obj', text: slab }]));
  assert.equal(result.name, 'slab.obj');
  // Switching the brush on starts the surface index in a worker: the page does not wait for it.
  const switchedOn = await app.page.evaluate(async () => {
    const { brush, update } = window.crestline;
    const started = performance.now();
    update({ brush: true, brushRadius: 0.2, brushValue: 0 });
    const notes = () => document.getElementById('notes').textContent;
    const afterSwitch = { ms: performance.now() - started, index: brush.index, notes: notes() };
    const index = await brush.ready();
    await new Promise((resolve) => setTimeout(resolve, 0));
    return { ...afterSwitch, offThread: index.offThread, nodes: index.nodes, adjacency: index.neighbours.length, notesAfter: notes() };
  });
  assert.equal(switchedOn.index, null, 'no index built on the main thread when the brush is switched on');
  assert.equal(switchedOn.notes, 'Brush: preparing the surface (a few seconds on a large mesh); strokes paint once it is ready.');
  assert.equal(switchedOn.notesAfter, '', 'the note goes once the index is there');
  assert.equal(switchedOn.offThread, true, 'the index came from the worker');
  // 2 × 41² vertices… the slab's 6 faces: 6 × 2 × 40² triangles, each adds 6 neighbour entries.
  assert.equal(switchedOn.adjacency, 6 * 6 * 2 * 40 * 40);
  assert.ok(switchedOn.nodes >= (6 * 2 * 40 * 40) / 8, `${switchedOn.nodes} BVH nodes`);
  const canvas = await app.page.locator('#view canvas').boundingBox();
  // The screen point of the slab's centre (the orbit centre: the free area's centre).
  const centre = await app.page.evaluate(() => {
    const { viewer } = window.crestline;
    const p = viewer.controls.target.clone().project(viewer.camera);
    const r = viewer.renderer.domElement.getBoundingClientRect();
    return [r.left + ((p.x + 1) / 2) * r.width, r.top + ((1 - p.y) / 2) * r.height];
  });
  assert.ok(centre[0] > canvas.x && centre[0] < canvas.x + canvas.width);
  const count = await app.page.evaluate(() => window.crestline.results.length);
  // Record what each move sends of the colour buffer.
  await app.page.evaluate(() => {
    const attribute = window.crestline.viewer.surface.mesh.geometry.getAttribute('color');
    const add = attribute.addUpdateRange.bind(attribute);
    window.colourUpload = { attribute, ranges: [] };
    attribute.addUpdateRange = (start, count) => (window.colourUpload.ranges.push(count), add(start, count));
  });
  await app.page.mouse.move(centre[0], centre[1]);
  await app.page.mouse.down();
  await app.page.mouse.move(centre[0] + 20, centre[1] + 10, { steps: 3 });
  const colours = await app.page.evaluate(() => {
    const { attribute, ranges } = window.colourUpload;
    const now = window.crestline.viewer.surface.mesh.geometry.getAttribute('color');
    return { same: now === attribute, ranges, length: attribute.array.length };
  });
  await app.page.mouse.up();
  await app.page.waitForFunction((n) => window.crestline.results.length > n, count, { timeout: 30000 });
  // One recompute per stroke, not per move: no second result follows.
  await app.page.waitForTimeout(500);
  assert.equal(await app.page.evaluate(() => window.crestline.results.length), count + 1, 'one result for a stroke of 4 moves');
  const painted = await app.page.evaluate(() => {
    const { viewer, brush } = window.crestline;
    const positions = viewer.surface.mesh.geometry.getAttribute('position').array;
    const radius = brush.radius * viewer.surface.mesh.geometry.boundingSphere.radius;
    let top = 0,
      bottom = 0,
      bottomInStraightReach = 0;
    brush.weights.forEach((w, v) => {
      const [x, y, z] = [positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]];
      if (w < 1) z > 0 ? top++ : bottom++;
      // Bottom vertices a straight-line radius from the centre would have reached.
      if (z < 0 && Math.hypot(x, y) < radius) bottomInStraightReach++;
    });
    return { top, bottom, bottomInStraightReach, radius, ran: window.crestline.lastResult.ran };
  });
  console.log(
    `# slab: ${painted.top} top vertices painted, ${painted.bottom} bottom; a straight-line radius would reach ${painted.bottomInStraightReach} bottom ones; 4 moves sent ${colours.ranges.length} colour ranges (${colours.ranges.reduce((a, b) => a + b, 0)} of ${colours.length} floats)`,
  );
  assert.ok(painted.radius > 4 * 0.05, `the radius ${painted.radius} is several times the thickness`);
  assert.ok(painted.top > 50, `top vertices painted: ${painted.top}`);
  assert.ok(painted.bottomInStraightReach > 50, 'a straight-line radius would paint through');
  assert.equal(painted.bottom, 0, 'no bottom vertex painted');
  assert.equal(painted.ran[0], 'smoothing', 'one recompute per stroke, from smoothing');
  const sent = colours.ranges.reduce((a, b) => a + b, 0);
  assert.equal(colours.same, true, 'the moves update the colour buffer in place');
  assert.ok(
    colours.ranges.length >= 4 && sent < colours.length,
    `4 moves send only the touched colours (${sent} floats in ${colours.ranges.length} ranges; the buffer has ${colours.length})`,
  );
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
