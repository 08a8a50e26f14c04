// The weight brush's answer to "is the smoothing inhomogeneous?"
// (WeightBrush.current, asked by every option change): kept between changes,
// and right after each way the weights change (a stroke, clear(), a new array).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { BufferAttribute, BufferGeometry, Vector3 } from 'three';
import { WeightBrush } from '../../web/src/three/brush.js';

/** A flat n × n grid of unit squares in z = 0, two triangles each. */
function grid(n) {
  const positions = new Float32Array(3 * (n + 1) * (n + 1));
  for (let j = 0, k = 0; j <= n; j++) for (let i = 0; i <= n; i++, k += 3) positions.set([i, j, 0], k);
  const indices = [];
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      const v = j * (n + 1) + i;
      indices.push(v, v + 1, v + n + 2, v, v + n + 2, v + n + 1);
    }
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(positions, 3));
  geometry.setIndex(new BufferAttribute(Uint32Array.from(indices), 1));
  geometry.computeBoundingSphere();
  return geometry;
}

/** A brush over a stand-in viewer: what paintRay reads of it (no renderer, no colours drawn). */
function brushOver(geometry) {
  const viewer = {
    renderer: { domElement: new EventTarget() },
    controls: { enabled: true },
    surface: { mesh: { geometry }, setColors() {}, updateColors() {} },
    render() {},
  };
  const brush = new WeightBrush(viewer, { onStroke() {} });
  brush.reset(geometry.getAttribute('position').count);
  return brush;
}

const down = new Vector3(0, 0, -1);

test('current(): null while every weight is 1, the weights once a stroke changed one, null again after clear()', () => {
  const geometry = grid(8);
  const brush = brushOver(geometry);
  assert.equal(brush.current(), null);
  assert.equal(brush.current(), null, 'asked again without a change');

  brush.value = 0; // freeze
  brush.radius = 0.2;
  const changed = brush.paintRay(new Vector3(4, 4, 1), down);
  assert.ok(changed > 0, 'the stroke hits the grid');
  assert.equal(brush.current(), brush.weights);
  assert.ok(brush.weights[4 * 9 + 4] < 1, 'the centre vertex is frozen towards 0');
  assert.equal(brush.current(), brush.weights, 'asked again without a change');

  brush.clear();
  assert.equal(brush.current(), null);

  // A stroke that misses the surface changes nothing.
  assert.equal(brush.paintRay(new Vector3(40, 40, 1), down), 0);
  assert.equal(brush.current(), null);
});

test('current(): weights put in place from outside (a previous mesh brought back) are scanned', () => {
  const brush = brushOver(grid(4));
  assert.equal(brush.current(), null);
  const painted = new Float64Array(25).fill(1);
  painted[12] = 1.5;
  brush.weights = painted;
  assert.equal(brush.current(), painted);
  brush.weights = new Float64Array(25).fill(1);
  assert.equal(brush.current(), null);
  brush.weights = null;
  assert.equal(brush.current(), null);
});
