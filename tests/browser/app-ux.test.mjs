// The page as a new user meets it (issue 17): broken files give one clean
// sentence, several dropped files load the mesh with its companions and name
// the ignored ones, the picker's formats; a legend and a tooltip per control. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { dropFiles, nextResult, useApp } from './app-page.mjs';
import { MESHES, haveMeshes } from '../node/helpers.mjs';

const noMeshes = !haveMeshes && `SKIPPED: ${MESHES} is absent`;
const app = useApp({ '/meshes/': MESHES });

/** Drops `files` (name + bytes given as numbers) and returns the error sentence. */
async function errorFor(name, bytes) {
  await app.page.evaluate(
    ({ name, bytes }) => {
      const transfer = new DataTransfer();
      transfer.items.add(new File([new Uint8Array(bytes)], name));
      document.getElementById('error').textContent = '';
      document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
    },
    { name, bytes },
  );
  await app.page.waitForFunction(() => document.body.dataset.state === 'error' && document.getElementById('error').textContent);
  return app.page.textContent('#error');
}

/** One sentence naming the file, printable ASCII/Latin text only (no binary junk). */
function assertCleanSentence(message, name) {
  assert.ok(message.startsWith(`${name}: `), `names the file: ${message}`);
  assert.doesNotMatch(message, /[^\x20-\x7e\u00a0-\u024f\u2010-\u2027]/u, `printable: ${JSON.stringify(message)}`);
  assert.equal(message.split(/[.!?](\s|$)/).filter((s) => s && s.trim()).length, 1, `one sentence: ${message}`);
}

test('a random blob named x.glb and a zero-byte x.stl: one clean sentence each naming the file', async () => {
  let seed = 17;
  const random = Array.from({ length: 4096 }, () => ((seed = (seed * 1103515245 + 12345) >>> 0) >>> 16) & 255);
  const glb = await errorFor('x.glb', random);
  const stl = await errorFor('x.stl', []);
  console.log(`${glb} / ${stl}`);
  assertCleanSentence(glb, 'x.glb');
  assert.equal(glb, "x.glb: the file is neither a GLB (which starts with the bytes 'glTF') nor glTF JSON.");
  assertCleanSentence(stl, 'x.stl');
  // The page recovers: the bunny is still loaded and re-filters.
  const result = await nextResult(app.page, () =>
    app.page.evaluate(() => window.crestline.update({ autoThreshold: false, threshold: window.crestline.lastResult.stats.threshold * 0.9 })),
  );
  assert.deepEqual(result.ran, ['filter']);
  await nextResult(app.page, () => app.page.evaluate(() => window.crestline.update({ autoThreshold: true })));
});

test('the file picker accepts only the formats read (and their companions)', async () => {
  const accept = (await app.page.getAttribute('#picker', 'accept')).split(',');
  for (const ext of ['.gltf', '.glb', '.bin', '.obj', '.mtl', '.ply', '.stl', '.off']) assert.ok(accept.includes(ext), `accepts ${ext}`);
  for (const ext of ['.txt', '.fbx', '.blend', '.zip']) assert.ok(!accept.includes(ext), `refuses ${ext}`);
});

test('OBJ + its .mtl + an unrelated STL and a text file: the OBJ loads, one sentence names the ignored files', async () => {
  const obj = 'mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl red\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n';
  const result = await nextResult(app.page, () =>
    dropFiles(app.page, [
      { name: 'notes.txt', text: 'hello' },
      { name: 'other.stl', text: 'solid x\nendsolid x\n' },
      { name: 'tetra.obj', text: obj },
      { name: 'cube.mtl', text: 'newmtl red\nKd 1 0 0\n' },
    ]),
  );
  assert.equal(result.name, 'tetra.obj');
  assert.equal(result.stats.triangles, 4);
  const notes = await app.page.textContent('#notes');
  assert.match(notes, /ignored notes\.txt and other\.stl \(/);
  assert.doesNotMatch(notes, /cube\.mtl/, 'the .mtl is a companion, not ignored');
});

test('glTF + .bin + texture + an unrelated OBJ: the glTF loads with its buffers, the OBJ is ignored', { skip: noMeshes }, async () => {
  const result = await nextResult(app.page, () =>
    dropFiles(app.page, ['gltf/Duck/Duck.gltf', 'gltf/Duck/Duck0.bin', 'gltf/Duck/DuckCM.png', { name: 'stray.obj', text: 'v 0 0 0\n' }]),
  );
  assert.equal(result.name, 'Duck.gltf');
  assert.ok(result.stats.triangles > 1000);
  const notes = await app.page.textContent('#notes');
  assert.match(notes, /ignored stray\.obj \(/);
  assert.doesNotMatch(notes, /Duck0\.bin|DuckCM\.png/);
});

test('a legend names ridges and valleys in their colours and follows the panel', async () => {
  const legend = () =>
    app.page.evaluate(() =>
      ['ridge', 'valley'].map((k) => {
        const entry = document.getElementById(`legend-${k}`);
        const box = entry.getBoundingClientRect();
        return {
          text: entry.textContent.trim(),
          color: getComputedStyle(entry.querySelector('.swatch')).backgroundColor,
          off: entry.classList.contains('off'),
          visible: box.width > 0 && box.height > 0,
          title: entry.title,
        };
      }),
    );
  const [ridge, valley] = await legend();
  assert.equal(ridge.text, 'ridges');
  assert.equal(valley.text, 'valleys');
  assert.ok(ridge.visible && valley.visible);
  assert.equal(ridge.color, 'rgb(214, 45, 32)', 'the default ridge colour #d62d20');
  assert.equal(valley.color, 'rgb(31, 95, 191)', 'the default valley colour #1f5fbf');
  assert.ok(ridge.title && valley.title);
  await app.page.evaluate(() => window.crestline.update({ ridgeColor: '#00ff00', showValleys: false }));
  const [ridge2, valley2] = await legend();
  assert.equal(ridge2.color, 'rgb(0, 255, 0)');
  assert.equal(valley2.off, true, 'hidden valleys are struck through');
  await app.page.evaluate(() => window.crestline.update({ ridgeColor: '#d62d20', showValleys: true }));
});

test("every panel control has a plain-words tooltip; the pipeline ones are the parameter table's help", async () => {
  const problems = await app.page.evaluate(() => {
    const { gui, parameters } = window.crestline;
    const out = [];
    for (const c of gui.controllersRecursive()) {
      const title = c.domElement.title;
      if (!title || title.length < 12) out.push(`${c._name}: no tooltip`);
      const p = parameters
        .filter((q) => q.group === 'pipeline' && q.stage)
        .find((q) => q.key === c.property || `auto${q.key[0].toUpperCase()}${q.key.slice(1)}` === c.property);
      if (p && !title.startsWith(p.help)) out.push(`${c._name}: "${title}" is not the table's help "${p.help}"`);
      if (p && p.unit && !title.includes(p.unit)) out.push(`${c._name}: no unit ${p.unit}`);
    }
    return out;
  });
  assert.deepEqual(problems, []);
});

test('a GLB export logs no warnings (the core writer makes it, not GLTFExporter)', async () => {
  const warnings = [];
  const listener = (message) => ['warning', 'error'].includes(message.type()) && warnings.push(message.text());
  app.page.on('console', listener);
  const saved = await app.page.evaluate(async () => {
    const result = await window.crestline.save('glb');
    return result && { fileName: result.fileName, magic: new TextDecoder().decode((await result.blob.arrayBuffer()).slice(0, 4)) };
  });
  app.page.off('console', listener);
  assert.equal(saved?.magic, 'glTF');
  assert.deepEqual(warnings, []);
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
