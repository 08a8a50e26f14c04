// The surface layer's culling of back faces (web/src/three/surface-layer.js):
// the camera test of cullHiddenFaces, and the worker's answer it relies on
// (Session.surface()'s view.closed, C++ is_closed_outward, whose own cases —
// scale, numbering, nested parts, holes, stray triangles — are in
// tests/unit/mesh/topology_test.cpp) on repaired meshes.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { DoubleSide, FrontSide, PerspectiveCamera } from 'three';
import { loadCrestline } from '../../wasm/node.mjs';
import { SurfaceLayer } from '../../web/src/three/surface-layer.js';

/** The unit cube's 8 corners and 12 triangles facing out. */
const CUBE = {
  positions: [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1],
  indices: [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7],
};

/** A UV sphere about `center` (closed: poles as single vertices), its triangles facing out. */
function sphere(center = [0, 0, 0], radius = 1, rings = 12, sectors = 20) {
  const positions = [...center.map((c, i) => c + (i === 2 ? radius : 0))];
  for (let r = 1; r < rings; r++)
    for (let s = 0; s < sectors; s++) {
      const [theta, phi] = [(Math.PI * r) / rings, (2 * Math.PI * s) / sectors];
      positions.push(
        center[0] + radius * Math.sin(theta) * Math.cos(phi),
        center[1] + radius * Math.sin(theta) * Math.sin(phi),
        center[2] + radius * Math.cos(theta),
      );
    }
  positions.push(center[0], center[1], center[2] - radius);
  const ring = (r, s) => 1 + (r - 1) * sectors + (s % sectors);
  const south = positions.length / 3 - 1;
  const indices = [];
  for (let s = 0; s < sectors; s++) {
    indices.push(0, ring(1, s), ring(1, s + 1));
    for (let r = 1; r < rings - 1; r++) indices.push(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    indices.push(south, ring(rings - 1, s + 1), ring(rings - 1, s));
  }
  return { positions, indices };
}

/** Several meshes as one (indices shifted). */
function joined(...meshes) {
  const positions = [],
    indices = [];
  for (const m of meshes) {
    const base = positions.length / 3;
    positions.push(...m.positions);
    indices.push(...m.indices.map((i) => i + base));
  }
  return { positions, indices };
}

const flipped = (m) => ({ positions: m.positions, indices: m.indices.map((_, i) => m.indices[i - (i % 3) + [0, 2, 1][i % 3]]) });

test('culled only when the camera and its near plane are outside the bounding sphere of a closed surface', () => {
  const layer = new SurfaceLayer();
  const s = sphere();
  const normals = new Float32Array(s.positions.length);
  layer.setMesh({ positions: Float32Array.from(s.positions), normals, radius: 1, closed: true }, Uint32Array.from(s.indices));
  assert.equal(layer.closed, true);
  const camera = new PerspectiveCamera(35, 1.5, 0.05, 100);
  const sideAt = (distance, near = 0.05) => {
    camera.near = near;
    camera.updateProjectionMatrix();
    camera.position.set(0, 0, distance);
    camera.lookAt(0, 0, 0);
    const version = layer.material.version;
    layer.cullHiddenFaces(camera);
    return { side: layer.material.side, changed: layer.material.version !== version };
  };
  assert.deepEqual(sideAt(4), { side: FrontSide, changed: true }, 'outside');
  assert.deepEqual(sideAt(4), { side: FrontSide, changed: false }, 'no change, no new material version');
  assert.equal(sideAt(0.5).side, DoubleSide, 'inside the sphere');
  assert.equal(sideAt(1.04).side, DoubleSide, 'outside, but the near plane reaches into the sphere');
  assert.equal(sideAt(1.04, 0.001).side, FrontSide, 'just outside, with a near plane that does not');
  assert.equal(sideAt(3, 2.5).side, DoubleSide, 'a near plane cutting the model');
  layer.setMesh({ positions: Float32Array.from(s.positions), normals, radius: 1, closed: false }, Uint32Array.from(s.indices.slice(3)));
  assert.equal(layer.closed, false, 'a sphere with a hole');
  assert.equal(sideAt(4).side, DoubleSide, 'an open surface shows both sides');
  layer.setMesh({ positions: Float32Array.from(s.positions), normals, radius: 1 }, Uint32Array.from(s.indices));
  assert.equal(layer.closed, false, 'a view without `closed` counts as open');
  assert.equal(sideAt(4).side, DoubleSide, 'both sides drawn then');
  layer.dispose();
});

test("the WASM Session's view.closed: the repaired mesh's, C++", async () => {
  const module = await loadCrestline();
  const holed = sphere();
  holed.indices = holed.indices.slice(0, -3);
  const cases = [
    ['the cube', CUBE, true],
    ['a sphere far off', sphere([1e5, -2e5, 3e5], 0.01), true],
    ['a sphere facing in (the repair turns it out)', flipped(sphere()), true],
    ['a sphere with a hole', holed, false],
    ['two spheres', joined(sphere(), sphere([3, 0, 0])), true],
  ];
  for (const [name, mesh, expected] of cases) {
    const session = new module.Session();
    const loaded = session.load(Float64Array.from(mesh.positions), Uint32Array.from(mesh.indices), {});
    assert.equal(loaded.ok, true, `${name}: ${loaded.error}`);
    const { indices, view } = session.surface();
    session.delete();
    assert.equal(view.closed, expected, name);
    assert.equal(indices.length, mesh.indices.length, `${name}: every triangle kept`);
  }
});
