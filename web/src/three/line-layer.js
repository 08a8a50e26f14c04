// Ridges and valleys as wide lines (LineSegments2), one object per type.
import { Group } from 'three';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';

export const RIDGE = 0;
export const VALLEY = 1;

/** Segment end points (x,y,z pairs, float32, minus `origin`) of the lines of one type. */
export function segmentPositions(lines, type, origin) {
  const { points, offsets, types, closed } = lines;
  let count = 0;
  for (let l = 0; l < types.length; l++) {
    if (types[l] !== type) continue;
    const n = offsets[l + 1] - offsets[l];
    count += closed[l] ? n : Math.max(0, n - 1);
  }
  const out = new Float32Array(count * 6);
  let o = 0;
  for (let l = 0; l < types.length; l++) {
    if (types[l] !== type) continue;
    const first = offsets[l];
    const last = offsets[l + 1] - 1;
    const segments = closed[l] ? last - first + 1 : last - first;
    for (let s = 0; s < segments; s++) {
      const a = first + s;
      const b = a === last ? first : a + 1;
      for (const p of [a, b]) {
        out[o++] = points[3 * p] - origin[0];
        out[o++] = points[3 * p + 1] - origin[1];
        out[o++] = points[3 * p + 2] - origin[2];
      }
    }
  }
  return out;
}

export class LineLayer {
  constructor({ ridgeColor = '#d62d20', valleyColor = '#1f5fbf', width = 2.5 } = {}) {
    this.group = new Group();
    this.objects = [ridgeColor, valleyColor].map((color) => {
      const material = new LineMaterial({ color, linewidth: width, worldUnits: false });
      const object = new LineSegments2(new LineSegmentsGeometry(), material);
      object.frustumCulled = false;
      object.renderOrder = 1;
      this.group.add(object);
      return object;
    });
  }

  setLines(lines, origin) {
    for (const type of [RIDGE, VALLEY]) {
      const object = this.objects[type];
      object.geometry.dispose();
      const geometry = new LineSegmentsGeometry();
      const positions = segmentPositions(lines, type, origin);
      if (positions.length) geometry.setPositions(positions);
      object.geometry = geometry;
      object.visible = positions.length > 0 && this.shown?.[type] !== false;
      object.userData.segments = positions.length / 6;
    }
  }

  setShown(ridges, valleys) {
    this.shown = [ridges, valleys];
    this.objects.forEach((o, type) => (o.visible = this.shown[type] && o.userData.segments > 0));
  }

  setColors(ridge, valley) {
    this.objects[RIDGE].material.color.set(ridge);
    this.objects[VALLEY].material.color.set(valley);
  }

  setWidth(pixels) {
    for (const o of this.objects) o.material.linewidth = pixels;
  }

  setResolution(width, height) {
    for (const o of this.objects) o.material.resolution.set(width, height);
  }

  dispose() {
    for (const o of this.objects) {
      o.geometry.dispose();
      o.material.dispose();
    }
  }
}
