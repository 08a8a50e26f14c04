// The page with crease boundaries on (issue 16; on by default): on a
// generated box the creases run along its 12 edges and no ridge or valley
// comes within 2 mean edges of them; with boundaries off (--crease-boundaries=false) the
// smooth lines run along those edges. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { boxObj } from './box-obj.mjs';
import { dropFiles, nextResult, useApp } from './app-page.mjs';

const SIZE = [2, 1, 1];
const N = 24;
const app = useApp();

/** The page's OBJ export: the points of each object's lines (`o ridges`, `o valleys`, `o creases`). */
async function exportedPoints() {
  const text = await app.page.evaluate(async () => (await window.crestline.save('obj')).blob.text());
  const vertices = [];
  const points = { ridges: [], valleys: [], creases: [] };
  let current = null;
  for (const line of text.split('\n')) {
    if (line.startsWith('v ')) vertices.push(line.slice(2).trim().split(/\s+/).map(Number));
    else if (line.startsWith('o ')) current = points[line.slice(2).trim()] ?? null;
    else if (line.startsWith('l ') && current) for (const k of line.slice(2).trim().split(/\s+/)) current.push(vertices[Number(k) - 1]);
  }
  return points;
}

/** Distance from a point on the box's surface to the nearest of its 12 edges. */
function edgeDistance(p) {
  const d = p.map((x, axis) => Math.min(Math.abs(x), Math.abs(SIZE[axis] - x))).sort((a, b) => a - b);
  return Math.hypot(d[0], d[1]);
}

test('a box with crease boundaries (the default): creases on its 12 edges, no smooth line within 2 mean edges of them', async () => {
  const on = await nextResult(app.page, () => dropFiles(app.page, [{ name: 'box.obj', text: boxObj({ size: SIZE, n: N }) }]));
  const h = on.stats.meanEdgeLength;
  assert.ok(h > 0, `mean edge ${h}`);
  const near = (points) => points.filter((p) => edgeDistance(p) < 2 * h).length;
  assert.equal(on.stats.creases, 12, 'the 12 edges are creases');
  const points = await exportedPoints();
  const smooth = [...points.ridges, ...points.valleys];
  console.log(`box, boundaries on: ${on.stats.creases} creases, ${smooth.length} smooth line points, ${near(smooth)} within 2 h of an edge`);
  assert.equal(near(smooth), 0, 'no smooth line within 2 mean edges of a crease');
  // Every crease point lies on an edge of the box.
  assert.ok(points.creases.length >= 12 * N);
  assert.ok(
    points.creases.every((p) => edgeDistance(p) < 1e-4),
    'crease points on the edges',
  );

  // Without boundaries the one-rings on the edges sum the 90° turn as curvature: lines along the edges.
  await nextResult(app.page, () => app.page.evaluate(() => window.crestline.update({ creaseBoundaries: false })));
  const off = await exportedPoints();
  console.log(
    `box, boundaries off: ${off.ridges.length + off.valleys.length} smooth line points, ${near(off.ridges) + near(off.valleys)} within 2 h of an edge`,
  );
  assert.ok(near(off.ridges) + near(off.valleys) > 0, 'without boundaries, smooth lines run along the edges');
  await nextResult(app.page, () => app.page.evaluate(() => window.crestline.update({ creaseBoundaries: true })));
});
