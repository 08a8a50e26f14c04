// Paper §6 / Fig. 6, inhomogeneous smoothing: a brush that paints a
// per-vertex smoothing strength on the surface (1 = the global time step,
// 0 = frozen, >1 = stronger). A stroke ends on pointer-up; the app then
// re-runs the pipeline from the smoothing stage with the new weights.
import { Raycaster, Vector2, Vector3 } from 'three';

const raycaster = new Raycaster();
const pointer = new Vector2();
const hit = new Vector3();

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

  paintAt(event) {
    const { viewer } = this;
    const rect = viewer.renderer.domElement.getBoundingClientRect();
    pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    raycaster.setFromCamera(pointer, viewer.camera);
    const [first] = raycaster.intersectObject(viewer.surface.mesh, false);
    if (!first) return;
    hit.copy(first.point);
    const geometry = viewer.surface.mesh.geometry;
    const positions = geometry.getAttribute('position').array;
    const radius = this.radius * geometry.boundingSphere.radius;
    for (let v = 0; v < this.weights.length; v++) {
      const dx = positions[3 * v] - hit.x, dy = positions[3 * v + 1] - hit.y, dz = positions[3 * v + 2] - hit.z;
      const d2 = dx * dx + dy * dy + dz * dz;
      if (d2 > radius * radius) continue;
      // Smooth falloff: full value in the centre, unchanged at the rim.
      const t = 1 - Math.sqrt(d2) / radius;
      const blend = t * t * (3 - 2 * t);
      this.weights[v] += (this.value - this.weights[v]) * blend;
      this.changed = true;
    }
    viewer.surface.setColors(this.weights.map((w) => w - 1));
    viewer.render();
  }
}
