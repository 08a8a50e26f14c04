// The browser's own readers (OBJ, OFF) and the scene merge of three.js loaders.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';
import { BufferAttribute, BufferGeometry, Group, Mesh } from 'three';
import { loadMeshFiles, pickMainFile } from '../../web/src/io/load-files.js';
import { mergeScene } from '../../web/src/io/merge-scene.js';
import { parseObj } from '../../web/src/io/obj.js';
import { parseOff } from '../../web/src/io/off.js';
import { MESHES, haveMeshes } from './helpers.mjs';

const bytes = (text) => new TextEncoder().encode(text).buffer;

test('OBJ: fan-triangulated polygons, negative and slashed indices, double precision', () => {
  const { positions, indices } = parseObj('v 0 0 0\nv 1 0 0\nv 1 1 0.1234567890123\nv 0 1 0\nf 1/1/1 2/2/2 3/3/3 4/4/4\nf -4 -3 -1\n');
  assert.deepEqual(Array.from(indices), [0, 1, 2, 0, 2, 3, 0, 1, 3]);
  assert.equal(positions[8], 0.1234567890123);
});

test('OFF: header variants, polygons and per-face colours', () => {
  const { positions, indices } = parseOff('OFF\n# comment\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n3 0 1 3\n');
  assert.equal(positions.length, 12);
  assert.deepEqual(Array.from(indices), [0, 1, 2, 0, 2, 3, 0, 1, 3]);
  assert.throws(() => parseOff('PLY\n', 'x.off'), /x\.off: not an OFF file/);
  assert.throws(() => parseOff('OFF 3 1 0\n0 0 0\n', 'short.off'), /short\.off: the file ends/);
});

test('merging applies world transforms (and fixes mirrored winding)', () => {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), 3));
  const group = new Group();
  const a = new Mesh(geometry);
  a.position.set(10, 0, 0);
  const b = new Mesh(geometry);
  b.scale.set(-1, 1, 1);
  group.add(a, b);
  const { positions, indices } = mergeScene(group);
  assert.deepEqual(Array.from(positions.slice(0, 6)), [10, 0, 0, 11, 0, 0]);
  assert.deepEqual(Array.from(indices), [0, 1, 2, 3, 5, 4]);
});

test('STL and PLY go through three.js loaders into an indexed soup', async () => {
  const stl = 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n';
  const fromStl = await loadMeshFiles([{ name: 'tri.stl', bytes: bytes(stl) }]);
  assert.deepEqual(Array.from(fromStl.positions), [0, 0, 0, 1, 0, 0, 0, 1, 0]);
  assert.equal(fromStl.indices.length, 3);
  const ply = 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n' +
    'element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n';
  const fromPly = await loadMeshFiles([{ name: 'quad.ply', bytes: bytes(ply) }]);
  assert.equal(fromPly.positions.length, 12);
  assert.equal(fromPly.indices.length, 6);
});

test('unsupported files and broken files name the file in one sentence', async () => {
  assert.throws(() => pickMainFile([{ name: 'notes.txt', bytes: bytes('hello') }]), /notes\.txt: unsupported format/);
  await assert.rejects(loadMeshFiles([{ name: 'broken.glb', bytes: bytes('glTF garbage') }]), /broken\.glb: cannot be read as GLB/);
  await assert.rejects(loadMeshFiles([{ name: 'empty.obj', bytes: bytes('# nothing\n') }]), /empty\.obj: contains no triangles/);
});

test('multi-file glTF: a missing .bin is named', { skip: !haveMeshes && `SKIPPED: ${MESHES} is absent` }, async () => {
  const gltf = readFileSync(join(MESHES, 'gltf/Duck/Duck.gltf'));
  await assert.rejects(loadMeshFiles([{ name: 'Duck.gltf', bytes: gltf.buffer.slice(gltf.byteOffset, gltf.byteOffset + gltf.length) }]),
    /Duck\.gltf: needs its companion file "Duck0\.bin"/);
});

for (const [file, triangles] of [['glb/pirate-meshopt.glb', 5010], ['glb/Duck-quantized.glb', 4212], ['glb/DamagedHelmet.glb', 15452]]) {
  test(`${file} (meshopt / quantized / textured) decodes to ${triangles} triangles`, { skip: !haveMeshes && `SKIPPED: ${MESHES} is absent` }, async () => {
    const glb = readFileSync(join(MESHES, file));
    const soup = await loadMeshFiles([{ name: file, bytes: glb.buffer.slice(glb.byteOffset, glb.byteOffset + glb.length) }]);
    assert.equal(soup.indices.length / 3, triangles);
    assert.ok(soup.positions.every(Number.isFinite));
  });
}
