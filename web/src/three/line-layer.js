// Ridges and valleys as wide lines (LineSegments2), one object per type;
// a second layer draws the creases (convex and concave as its two types).
// The geometry holds every faired line; a threshold change only shows or
// hides line ranges (a per-segment flag the vertex shader reads), so it
// uploads one byte per changed segment and rebuilds nothing.
import { Color, Group, InstancedBufferAttribute } from 'three';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { LINE_COLORS } from './colors.js';

export const RIDGE = 0;
export const VALLEY = 1;
/** In a crease layer (creaseLayer): type 0 convex, 1 concave. */
export const CONVEX = 0;
export const CONCAVE = 1;

/** The concave creases' shade of the crease colour: darker, so the two kinds stay apart. */
export const concaveShade = (color) => new Color(color).multiplyScalar(0.55);

/** Session.creases() as Lines whose types are CONVEX / CONCAVE (for a LineLayer). */
export const creasesAsLines = (creases) => ({ ...creases, types: Uint8Array.from(creases.convex, (c) => (c ? CONVEX : CONCAVE)) });

/** Segments of line l: a closed line also joins its last point to its first. */
const segmentCount = (lines, l) => {
  const n = lines.offsets[l + 1] - lines.offsets[l];
  return lines.closed[l] ? n : Math.max(0, n - 1);
};

/** Segment end points (x,y,z pairs, float32, minus `origin`) of the lines of one type. */
export function segmentPositions(lines, type, origin) {
  const { points, offsets, types } = lines;
  let count = 0;
  for (let l = 0; l < types.length; l++) if (types[l] === type) count += segmentCount(lines, l);
  const out = new Float32Array(count * 6);
  let o = 0;
  for (let l = 0; l < types.length; l++) {
    if (types[l] !== type) continue;
    const first = offsets[l];
    const last = offsets[l + 1] - 1;
    const segments = segmentCount(lines, l);
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

/** LineMaterial whose segments with instanceShown = 0 are moved outside the clip volume. */
function hidingLineMaterial(parameters) {
  const material = new LineMaterial(parameters);
  material.vertexShader = material.vertexShader
    .replace('attribute vec3 instanceEnd;', 'attribute vec3 instanceEnd;\n\t\tattribute float instanceShown;')
    .replace('gl_Position = clip;', 'gl_Position = instanceShown > 0.5 ? clip : vec4( 2.0, 2.0, 2.0, 1.0 );');
  return material;
}

export class LineLayer {
  constructor({ ridgeColor = LINE_COLORS.ridge, valleyColor = LINE_COLORS.valley, width = 2.5 } = {}) {
    this.group = new Group();
    this.objects = [ridgeColor, valleyColor].map((color) => {
      const material = hidingLineMaterial({ color, linewidth: width, worldUnits: false });
      const object = new LineSegments2(new LineSegmentsGeometry(), material);
      object.frustumCulled = false;
      object.renderOrder = 1;
      this.group.add(object);
      return object;
    });
    this.lineCount = 0;
    this.firstSegment = new Uint32Array(0); // line → its first segment in its type's geometry
    this.segments = new Uint32Array(0); // line → its segment count
    this.types = new Uint8Array(0);
    this.kept = new Uint8Array(0); // line → shown (1) or not
  }

  /**
   * Every line of the mesh (Session.lines(true)); `kept` (Uint32Array of line
   * indices, or undefined for all) says which are shown.
   */
  setLines(lines, origin, kept) {
    const count = lines.types.length;
    this.lineCount = count;
    this.types = lines.types.slice();
    this.firstSegment = new Uint32Array(count);
    this.segments = new Uint32Array(count);
    const next = [0, 0];
    for (let l = 0; l < count; l++) {
      this.segments[l] = segmentCount(lines, l);
      this.firstSegment[l] = next[lines.types[l]];
      next[lines.types[l]] += this.segments[l];
    }
    for (const type of [RIDGE, VALLEY]) {
      const object = this.objects[type];
      object.geometry.dispose();
      const geometry = new LineSegmentsGeometry();
      const positions = segmentPositions(lines, type, origin);
      if (positions.length) {
        geometry.setPositions(positions);
        geometry.setAttribute('instanceShown', new InstancedBufferAttribute(new Uint8Array(positions.length / 6), 1));
      }
      object.geometry = geometry;
      object.userData.segments = positions.length / 6;
    }
    this.kept = new Uint8Array(count);
    this.setKept(kept ?? Uint32Array.from({ length: count }, (_, l) => l));
  }

  /**
   * Shows the lines in `kept` (indices into the lines of setLines) and hides
   * the others: only the flags of lines that changed are written and uploaded.
   */
  setKept(kept) {
    const next = new Uint8Array(this.lineCount);
    for (const l of kept) next[l] = 1;
    const ranges = [
      [Infinity, -1],
      [Infinity, -1],
    ];
    for (let l = 0; l < this.lineCount; l++) {
      if (next[l] === this.kept[l] || !this.segments[l]) continue;
      const type = this.types[l];
      const attribute = this.objects[type].geometry.getAttribute('instanceShown');
      const first = this.firstSegment[l];
      attribute.array.fill(next[l], first, first + this.segments[l]);
      ranges[type][0] = Math.min(ranges[type][0], first);
      ranges[type][1] = Math.max(ranges[type][1], first + this.segments[l]);
    }
    this.kept = next;
    this.shownSegments = [0, 0];
    for (let l = 0; l < this.lineCount; l++) if (next[l]) this.shownSegments[this.types[l]] += this.segments[l];
    for (const type of [RIDGE, VALLEY]) {
      const [start, end] = ranges[type];
      if (end < 0) continue;
      const attribute = this.objects[type].geometry.getAttribute('instanceShown');
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(start, end - start);
      attribute.needsUpdate = true;
    }
    this.applyVisibility();
  }

  setShown(ridges, valleys) {
    this.shown = [ridges, valleys];
    this.applyVisibility();
  }

  applyVisibility() {
    this.objects.forEach((o, type) => (o.visible = this.shown?.[type] !== false && (this.shownSegments?.[type] ?? 0) > 0));
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
