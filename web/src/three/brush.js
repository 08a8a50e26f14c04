// Paper §6 / Fig. 6, inhomogeneous smoothing: a brush that paints a
// per-vertex smoothing strength on the surface (1 = the global time step,
// 0 = frozen, >1 = stronger). A stroke ends on pointer-up; the app then
// re-runs the pipeline from the smoothing stage with the new weights.
// A pointer move picks through a BVH, measures the radius along the surface
// (surface-index.js: a thin part's far side is not painted) and recolours
// only the vertices it touched.
import { Raycaster, Vector2 } from 'three';
import { SurfaceIndex } from './surface-index.js';

const raycaster = new Raycaster();
const pointer = new Vector2();

/** The weights' colour map saturates at ±1 around the normal weight 1 (0 = frozen, 2 = twice). */
export const WEIGHT_SCALE = 1;

export class WeightBrush {
  /** @param {import('./viewer.js').Viewer} viewer  @param {{onStroke: (weights) => void}} handlers */
  constructor(viewer, { onStroke }) {
    this.viewer = viewer;
    this.onStroke = onStroke;
    this.enabled = false;
    this.radius = 0.05; // fraction of the bounding-sphere radius
    this.value = 0;
    this.weights = null;
    this.painting = false;
    const canvas = viewer.renderer.domElement;
    canvas.addEventListener('pointerdown', (e) => this.down(e));
    canvas.addEventListener('pointermove', (e) => this.painting && this.paintAt(e));
    canvas.addEventListener('pointerup', () => this.up());
    canvas.addEventListener('pointerleave', () => this.up());
  }

  /** Weights for a surface of `count` vertices, reset to 1 when the mesh changed. */
  reset(count) {
    if (this.weights?.length !== count) this.weights = new Float64Array(count).fill(1);
    this.index = null; // built again for the new surface on first use
  }

  /** The picking and distance structure of the surface shown (built on first use: ~1 s for a million triangles). */
  surfaceIndex() {
    const geometry = this.viewer.surface.mesh.geometry;
    if (this.index?.geometry !== geometry) {
      this.index = new SurfaceIndex(geometry.getAttribute('position').array, geometry.index.array);
      this.index.geometry = geometry;
      this.touched = new Uint32Array(1024);
    }
    return this.index;
  }

  clear() {
    this.weights?.fill(1);
  }

  /** Null when every weight is 1 (homogeneous smoothing). */
  current() {
    return this.weights && this.weights.some((w) => w !== 1) ? this.weights : null;
  }

  setEnabled(on) {
    this.enabled = on;
    this.viewer.controls.enabled = !on; // dragging paints instead of orbiting
  }

  down(event) {
    if (!this.enabled || event.button !== 0 || !this.weights) return;
    this.painting = true;
    this.changed = false;
    this.paintAt(event);
  }

  up() {
    if (!this.painting) return;
    this.painting = false;
    if (this.changed) this.onStroke(this.weights);
  }

  /** One pointer position: paints within the radius (along the surface) of the point hit; returns the vertices touched. */
  paintAt(event) {
    const { viewer } = this;
    const rect = viewer.renderer.domElement.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, viewer.camera);
    return this.paintRay(raycaster.ray.origin, raycaster.ray.direction);
  }

  /** Paints where the ray (in the surface's coordinates) hits; returns how many vertices changed. */
  paintRay(origin, direction) {
    const index = this.surfaceIndex();
    const hit = index.raycast(origin, direction);
    if (!hit) return 0;
    const geometry = this.viewer.surface.mesh.geometry;
    const radius = this.radius * geometry.boundingSphere.radius;
    let count = 0;
    index.within(hit.triangle, hit.point, radius, (v, d) => {
      // Smooth falloff: full value in the centre, unchanged at the rim.
      const t = 1 - d / radius;
      const blend = t * t * (3 - 2 * t);
      this.weights[v] += (this.value - this.weights[v]) * blend;
      if (count === this.touched.length) {
        const grown = new Uint32Array(2 * count);
        grown.set(this.touched);
        this.touched = grown;
      }
      this.touched[count++] = v;
    });
    if (!count) return 0;
    this.changed = true;
    const surface = this.viewer.surface;
    if (!surface.mesh.geometry.getAttribute('color')) surface.setColors(this.weights.map((w) => w - 1), WEIGHT_SCALE);
    else surface.updateColors(this.touched, count, (v) => this.weights[v] - 1, WEIGHT_SCALE);
    this.viewer.render();
    return count;
  }
}
