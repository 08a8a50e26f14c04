// Paper §6 / Fig. 6, inhomogeneous smoothing: a brush that paints a
// per-vertex smoothing strength on the surface (1 = the global time step,
// 0 = frozen, >1 = stronger). A stroke ends on pointer-up; the app then
// re-runs the pipeline from the smoothing stage with the new weights.
// A pointer move picks through a BVH, measures the radius along the surface
// (../worker/surface-index.js: a thin part's far side is not painted) and
// recolours only the vertices it touched.
import { Raycaster, Vector2 } from 'three';
import { SurfaceIndex } from '../worker/surface-index.js';

const raycaster = new Raycaster();
const pointer = new Vector2();

/** The weights' colour map saturates at ±1 around the normal weight 1 (0 = frozen, 2 = twice). */
export const WEIGHT_SCALE = 1;

export class WeightBrush {
  /**
   * `buildIndex` builds the surface index's arrays elsewhere (the page: a
   * worker, Connection.surfaceIndex); without it (node) the index is built
   * in place.
   * @param {import('./viewer.js').Viewer} viewer
   * @param {{onStroke: (weights) => void,
   *          buildIndex?: (positions: Float32Array, indices: Uint32Array) => Promise<import('../worker/surface-index.js').SurfaceIndexParts>}} handlers
   */
  constructor(viewer, { onStroke, buildIndex }) {
    this.viewer = viewer;
    this.onStroke = onStroke;
    this.buildIndex = buildIndex;
    this.enabled = false;
    this.radius = 0.05; // fraction of the bounding-sphere radius
    this.value = 0;
    this.weights = null;
    /** The weights current() last scanned (null: scan again) and whether any of them was not 1. */
    this.scanned = null;
    this.painted = false;
    this.painting = false;
    const canvas = viewer.renderer.domElement;
    canvas.addEventListener('pointerdown', (e) => this.down(e));
    canvas.addEventListener('pointermove', (e) => this.painting && this.paintAt(e));
    canvas.addEventListener('pointerup', () => this.up());
    canvas.addEventListener('pointerleave', () => this.up());
  }

  /** Weights for a surface of `count` vertices, reset to 1 when the mesh changed. */
  reset(count) {
    if (this.weights?.length !== count) {
      this.weights = new Float64Array(count).fill(1);
      [this.scanned, this.painted] = [this.weights, false]; // all 1: nothing for current() to scan
    }
    this.index = null; // built again for the new surface on first use
    this.building = null;
  }

  /**
   * The picking and distance structure of the surface shown, or null while
   * it is built: seconds for a million triangles, so in a browser a worker
   * builds it (the page stays responsive; strokes start once it is there).
   * Without workers (node) it is built here and returned at once.
   */
  surfaceIndex() {
    const geometry = this.viewer.surface.mesh.geometry;
    if (this.index?.geometry === geometry) return this.index;
    const positions = geometry.getAttribute('position').array;
    const indices = geometry.index.array;
    if (!this.buildIndex) return this.adopt(new SurfaceIndex(positions, indices), geometry);
    if (this.building?.geometry !== geometry) {
      // Builds run in turn; a stale one's result is dropped.
      const building = this.buildIndex(positions, indices).then(
        (parts) => {
          if (this.building === building) this.adopt(new SurfaceIndex(positions, indices, parts), geometry, true);
          return this.index;
        },
        (error) => Promise.reject(new Error(`the brush's surface index could not be built (${error.message})`)),
      );
      this.building = Object.assign(building, { geometry });
    }
    return null;
  }

  /** Resolves to the surface shown's index once it is built (tests, callers that can wait). */
  ready() {
    return this.surfaceIndex() ?? this.building;
  }

  /** @param {SurfaceIndex} index @param {object} geometry @param {boolean} [offThread] */
  adopt(index, geometry, offThread = false) {
    this.index = Object.assign(index, { geometry, offThread });
    this.building = null;
    this.touched = new Uint32Array(1024);
    return this.index;
  }

  clear() {
    this.weights?.fill(1);
    this.scanned = null;
  }

  /**
   * Null when every weight is 1 (homogeneous smoothing). Every option change
   * asks (a threshold change too), so the answer is kept until a stroke or
   * clear() changes the weights or they are replaced: scanning a million
   * vertices' weights took 3-4 ms of the page's main thread.
   */
  current() {
    const weights = this.weights;
    if (!weights) return null;
    if (this.scanned !== weights) {
      this.painted = weights.some((w) => w !== 1);
      this.scanned = weights;
    }
    return this.painted ? weights : null;
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

  /** Paints where the ray (in the surface's coordinates) hits; returns how many vertices changed (none while the index is built). */
  paintRay(origin, direction) {
    const index = this.surfaceIndex();
    const hit = index?.raycast(origin, direction);
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
    this.scanned = null;
    const surface = this.viewer.surface;
    if (!surface.mesh.geometry.getAttribute('color'))
      surface.setColors(
        this.weights.map((w) => w - 1),
        WEIGHT_SCALE,
      );
    else surface.updateColors(this.touched, count, (v) => this.weights[v] - 1, WEIGHT_SCALE);
    this.viewer.render();
    return count;
  }
}
