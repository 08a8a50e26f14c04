// The line layer's geometry in node (three.js without a renderer): the
// segments' end points on their vertices, the index's triangles and the
// bounding sphere, against what they are defined to be.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { JOINED_INDICES, SEGMENT_INDEX, SEGMENT_VERTICES, SegmentGeometry, segmentPositions, segmentTextureWidth } from '../../web/src/three/line-layer.js';

// An open ridge of 3 points, a closed valley of 3 points, an open ridge of 2.
const LINES = {
  points: Float64Array.from([0, 0, 0, 1, 0, 0, 1, 2, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5, -1, -1, -1, -2, -1, -1]),
  offsets: Uint32Array.from([0, 3, 6, 8]),
  types: Uint8Array.from([0, 1, 0]),
  closed: Uint8Array.from([0, 1, 0]),
};

test('segmentPositions: each segment’s two end points minus the origin, a closed line’s last back to its first', () => {
  const origin = [1, 0, 0];
  assert.deepEqual([...segmentPositions(LINES, 0, origin)], [-1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, -2, -1, -1, -3, -1, -1]);
  assert.deepEqual([...segmentPositions(LINES, 1, origin)], [4, 5, 5, 5, 5, 5, 5, 5, 5, 4, 6, 5, 4, 6, 5, 4, 5, 5]);
});

test('SegmentGeometry: the end points in its texture (two texels a segment), a start cap only where an open line starts', () => {
  const positions = segmentPositions(LINES, 0, [0, 0, 0]);
  // Runs: the 2-segment line (its first segment degenerate: the cap goes with the next), then the 1-segment one.
  positions.set([0, 0, 0, 0, 0, 0], 0);
  const geometry = new SegmentGeometry(positions, [
    [0, 2, false],
    [2, 1, false],
  ]);
  // Segment s's end points are texels 2s and 2s + 1 (RGB floats, whole rows); its 8 vertices carry only the shown flag.
  const { data, width, height } = geometry.ends.image;
  assert.equal(width, segmentTextureWidth(3));
  assert.equal(height, 1);
  assert.equal(data.length, 3 * width * height);
  assert.deepEqual([...data.subarray(0, 18)], [...positions]);
  assert.ok(data.subarray(18).every((x) => x === 0));
  assert.deepEqual(Object.keys(geometry.attributes), ['instanceShown']);
  assert.equal(geometry.getAttribute('instanceShown').count, 3 * SEGMENT_VERTICES);
  // SegmentGeometry stores SEGMENT_INDEX's quads itself: they must be the table's, offset by the segment's first vertex.
  const triangles = (s, withStart) => SEGMENT_INDEX.slice(0, withStart ? SEGMENT_INDEX.length : JOINED_INDICES).map((k) => s * SEGMENT_VERTICES + k);
  assert.deepEqual([...geometry.index.array], [...triangles(0, true), ...triangles(1, true), ...triangles(2, true)]);
  assert.deepEqual([...geometry.runEnds], [36, 54]);
  const closed = new SegmentGeometry(segmentPositions(LINES, 1, [0, 0, 0]), [[0, 3, true]]);
  assert.deepEqual([...closed.index.array], [...triangles(0, false), ...triangles(1, false), ...triangles(2, false)]);
});

test('segmentTextureWidth: even, at least 2,048 texels, rows for every segment within the width', () => {
  for (const count of [0, 1, 1024, 1025, 2_097_152, 2_097_153, 30_000_000]) {
    const width = segmentTextureWidth(count);
    const rows = Math.ceil((2 * count) / width);
    assert.equal(width % 2, 0, `${count}`);
    assert.ok(width >= 2048 && rows <= width, `${count}: ${width} × ${rows}`);
  }
  // Up to 2,097,152 segments (1,024 a row) the texture is 2,048 wide, WebGL 2's least maximum, and as many rows high.
  assert.equal(segmentTextureWidth(2_097_152), 2048);
  assert.equal(segmentTextureWidth(2_097_153), 2050);
});

test('SegmentGeometry: the bounding sphere is LineSegmentsGeometry’s, to the bit', () => {
  let seed = 7;
  const random = () => ((seed = (seed * 16807) % 2147483647) / 2147483647) * 9 - 3;
  for (const count of [0, 1, 4, 5000]) {
    const positions = Float32Array.from({ length: 6 * count }, random);
    const geometry = new SegmentGeometry(positions);
    geometry.computeBoundingSphere();
    const reference = new LineSegmentsGeometry();
    reference.setPositions(positions);
    reference.computeBoundingSphere();
    const got = [...geometry.boundingSphere.center.toArray(), geometry.boundingSphere.radius];
    const want = [...reference.boundingSphere.center.toArray(), reference.boundingSphere.radius];
    assert.deepEqual(got, want, `${count} segments`);
  }
});
