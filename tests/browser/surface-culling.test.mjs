// The surface's back faces are culled where they are hidden (web/src/three/surface-layer.js):
// a closed mesh seen from outside, from every preset (a closed part, and 11
// thin ones), draws what both sides draw but where a back face won a sample
// by rounding (where the surface turns away: the front face shows there
// now); an open one (the Stanford bunny) keeps both sides, and so does a
// closed one once the camera is inside it, where its inside shows. Needs
// web/dist (web/build.sh) and the shared meshes.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { dropFiles, nextResult, useApp } from './app-page.mjs';
import { ROOT } from '../node/helpers.mjs';

const MESHES = join(ROOT, '../shared/meshes');
const app = useApp({ '/meshes/': MESHES });
const skip = !existsSync(join(MESHES, 'classic/mannequin.obj'));

/** The side of the surface's material after the next frame: 'front' (culled) or 'double'. */
const sideAfterFrame = () =>
  app.page.evaluate(async () => {
    const { viewer } = window.crestline;
    await new Promise((resolve) => viewer.afterFrame(resolve));
    return viewer.surface.material.side === 0 ? 'front' : viewer.surface.material.side === 2 ? 'double' : 'back';
  });

/**
 * From each preset: the plain render (renderer.render, lines hidden) with the
 * back faces culled as the viewer culls them against both sides drawn, and
 * a picture of which side won each sample with both drawn (front green,
 * back red): pixels differing, those of them where no back face won a
 * sample, the largest difference (any channel), and the surface's pixels.
 */
function compareSides(presets) {
  return app.page.evaluate(
    async ({ presets }) => {
      const { viewer } = window.crestline;
      // three's classes from the page's own objects (the app's bundle exports none).
      const ShaderMaterial = viewer.surfaceCache.material.constructor;
      const DoubleSide = 2;
      const gl = viewer.renderer.getContext();
      const read = () => {
        const pixels = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
        gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
        return pixels;
      };
      const material = viewer.surface.material;
      const facing = new ShaderMaterial({
        vertexShader: 'void main() { gl_Position = projectionMatrix * modelViewMatrix * vec4( position, 1.0 ); }',
        fragmentShader: 'void main() { gl_FragColor = gl_FrontFacing ? vec4( 0.0, 1.0, 0.0, 1.0 ) : vec4( 1.0, 0.0, 0.0, 1.0 ); }',
        side: DoubleSide,
        polygonOffset: true,
        polygonOffsetFactor: material.polygonOffsetFactor,
        polygonOffsetUnits: material.polygonOffsetUnits,
        toneMapped: false,
      });
      const render = (side, override = null) => {
        material.side = side;
        material.needsUpdate = true;
        const background = viewer.scene.background;
        viewer.scene.overrideMaterial = override;
        if (override) viewer.scene.background = null; // black
        viewer.renderer.render(viewer.scene, viewer.camera);
        viewer.scene.overrideMaterial = null;
        viewer.scene.background = background;
        return read();
      };
      viewer.lines.group.visible = viewer.creases.group.visible = false;
      const out = {};
      for (const preset of presets) {
        viewer.setPreset(preset);
        viewer.surface.cullHiddenFaces(viewer.camera);
        const culled = material.side;
        const [one, both, sides] = [render(culled), render(DoubleSide), render(DoubleSide, facing)];
        let differ = 0,
          unexplained = 0,
          most = 0,
          surface = 0;
        for (let i = 0; i < one.length; i += 4) {
          const d = Math.max(Math.abs(one[i] - both[i]), Math.abs(one[i + 1] - both[i + 1]), Math.abs(one[i + 2] - both[i + 2]));
          if (d) differ++;
          if (d && !sides[i]) unexplained++;
          most = Math.max(most, d);
          if (sides[i] || sides[i + 1]) surface++;
        }
        out[preset] = { culled: culled !== DoubleSide, differ, unexplained, most, surface };
      }
      facing.dispose();
      viewer.lines.group.visible = viewer.creases.group.visible = true;
      viewer.setPreset('front');
      return out;
    },
    { presets },
  );
}

for (const [mesh, note] of [
  ['classic/mannequin.obj', 'one closed part'],
  ['cad/cessna.obj', '11 closed parts, thin ones'],
]) {
  test(`${mesh} (${note}): culled from outside, from every preset; only pixels where a back face won a sample change`, { skip }, async () => {
    await nextResult(app.page, () => dropFiles(app.page, [mesh]));
    assert.equal(await app.page.evaluate(() => window.crestline.viewer.surface.closed), true);
    assert.equal(await sideAfterFrame(), 'front');
    const sides = await compareSides(['front', 'back', 'left', 'top', 'bottom', 'iso']);
    console.log(`# ${mesh}: ${JSON.stringify(sides)}`);
    for (const [preset, { culled, differ, unexplained, surface }] of Object.entries(sides)) {
      assert.ok(culled, `${preset}: culled`);
      assert.ok(surface > 3000, `${preset}: ${surface} surface pixels`);
      // Where the surface turns away, its back faces lie within rounding of the front ones in depth and won
      // some samples with both sides drawn: those pixels now show the front face. (A few more, one in a
      // hundred, where the picture of the sides rounded a tie the other way.)
      assert.ok(unexplained <= differ / 100, `${preset}: ${unexplained} pixels changed where no back face won a sample`);
      assert.ok(differ > 0 && differ < 0.15 * surface, `${preset}: ${differ} of ${surface} surface pixels changed`);
    }
  });
}

test('the camera inside a closed mesh: both sides again, and its inside shows', { skip }, async () => {
  await nextResult(app.page, () => dropFiles(app.page, ['classic/mannequin.obj']));
  assert.equal(await sideAfterFrame(), 'front');
  const inside = await app.page.evaluate(() => {
    const { viewer } = window.crestline;
    // Next to the centre of the bounding sphere (inside this head).
    viewer.camera.position.copy(viewer.controls.target).add(viewer.camera.position.clone().sub(viewer.controls.target).setLength(0.01));
    viewer.controls.update();
    return viewer.camera.position.distanceTo(viewer.controls.target) / viewer.surface.mesh.geometry.boundingSphere.radius;
  });
  assert.ok(inside < 0.1, `${inside} radii from the centre`);
  assert.equal(await sideAfterFrame(), 'double');
  const sides = await app.page.evaluate(() => {
    const { viewer } = window.crestline;
    viewer.lines.group.visible = viewer.creases.group.visible = false;
    const gl = viewer.renderer.getContext();
    viewer.renderer.render(viewer.scene, viewer.camera);
    const pixels = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
    gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    const red = viewer.scene.background.getHex() >> 16;
    let surface = 0;
    for (let i = 0; i < pixels.length; i += 4) if (Math.abs(pixels[i] - red) > 6) surface++;
    viewer.lines.group.visible = viewer.creases.group.visible = true;
    return { surface, pixels: pixels.length / 4 };
  });
  assert.ok(sides.surface > 0.5 * sides.pixels, `the inside fills the view: ${JSON.stringify(sides)}`);
  await app.page.evaluate(() => window.crestline.viewer.fitView());
  assert.equal(await sideAfterFrame(), 'front', 'framed again from outside');
});

test('an open scan (the Stanford bunny, holes at its base) is drawn with both sides', { skip }, async () => {
  await nextResult(app.page, () => dropFiles(app.page, ['classic/stanford-bunny.obj']));
  assert.equal(await app.page.evaluate(() => window.crestline.viewer.surface.closed), false);
  assert.equal(await sideAfterFrame(), 'double');
  assert.deepEqual(app.pageErrors, []);
});
