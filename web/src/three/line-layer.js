// Ridges and valleys as wide lines (LineSegments2), one object per type;
// a second layer draws the creases (convex and concave as its two types).
// The geometry holds every faired line; a threshold change only shows or
// hides line ranges (a per-segment flag the vertex shader reads), so it
// uploads one flag per changed segment vertex and rebuilds nothing.
//
// The segments are not instanced: each one is 8 vertices of its own (the
// LineSegmentsGeometry template's, told apart by gl_VertexID % 8) carrying
// its two end points, drawn with LineMaterial's own shaders; one instanced
// draw of 141k segments costs WebGL on the CPU (SwiftShader) about three
// times as much as this one. A segment draws its start cap (a half disc)
// only where its line starts: elsewhere the previous segment's body and end
// cap cover that half disc already, so the line covers the same pixels as
// LineSegments2's, with two of each segment's six triangles and eight
// vertices fewer to draw. Only where the dropped cap's depth (its start
// point's) decided a depth test against another object may a pixel differ
// (tests/browser/line-layer.test.mjs bounds it).
import {
  BufferAttribute,
  BufferGeometry,
  Color,
  Group,
  InstancedInterleavedBuffer,
  InterleavedBuffer,
  InterleavedBufferAttribute,
  Sphere,
  Vector3,
} from 'three';
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
    for (let s = 0; s < segments; s++, o += 6) {
      const a = 3 * (first + s);
      const b = first + s === last ? 3 * first : a + 3;
      out[o] = points[a] - origin[0];
      out[o + 1] = points[a + 1] - origin[1];
      out[o + 2] = points[a + 2] - origin[2];
      out[o + 3] = points[b] - origin[0];
      out[o + 4] = points[b + 1] - origin[1];
      out[o + 5] = points[b + 2] - origin[2];
    }
  }
  return out;
}

/**
 * The two triangles of the template's quad whose vertices are v…v + 3 (a
 * row pair of LineSegmentsGeometry's template), written at index[i…i + 5].
 * Straight stores, not a loop over a table: a loop over SEGMENT_INDEX took
 * 1.4× as long for 141k segments in node.
 * @param {Uint32Array | number[]} index @param {number} i @param {number} v
 */
function storeQuad(index, i, v) {
  index[i] = v;
  index[i + 1] = v + 2;
  index[i + 2] = v + 1;
  index[i + 3] = v + 2;
  index[i + 4] = v + 3;
  index[i + 5] = v + 1;
}

/**
 * The vertices of a segment (LineSegmentsGeometry's template) and its
 * triangles: end cap, body, start cap, the quads at vertices 0, 2 and 4
 * (storeQuad, which SegmentGeometry calls the same way).
 */
export const SEGMENT_VERTICES = 8;
export const SEGMENT_INDEX = Object.freeze(
  [0, 2, 4].flatMap((v) => {
    const quad = [];
    storeQuad(quad, 0, v);
    return quad;
  }),
);
/** The indices of a segment without its start cap (rows 0 and -1 of the template: vertices 4-7). */
export const JOINED_INDICES = 12;

const START_CAP = SEGMENT_INDEX.length - JOINED_INDICES;

/** Whether segment s of `positions` has the same two end points (no direction: LineMaterial draws nothing of it). */
const degenerate = (positions, s) =>
  positions[6 * s] === positions[6 * s + 3] && positions[6 * s + 1] === positions[6 * s + 4] && positions[6 * s + 2] === positions[6 * s + 5];

/**
 * The segments `positions` (end point pairs, as segmentPositions makes them)
 * as a plain indexed geometry: 8 vertices per segment, each with both end
 * points (instanceStart, instanceEnd: one interleaved buffer) and the
 * segment's shown flag (instanceShown, 0 until setKept). `runs` ([first
 * segment, count, closed] triples covering every segment once, by default
 * each segment alone) are the lines, each segment's end the next one's start
 * (and the last one's the first one's when closed), in the order of the
 * triangles in the index: a draw range over its start up to runEnds[r]
 * draws runs 0…r only. An open run's start cap goes with its first segment
 * of any length.
 */
export class SegmentGeometry extends BufferGeometry {
  constructor(positions = new Float32Array(0), runs = Array.from({ length: positions.length / 6 }, (_, s) => [s, 1, false])) {
    super();
    this.type = 'SegmentGeometry';
    const count = positions.length / 6;
    this.segmentCount = count;
    const ends = new Float32Array(count * SEGMENT_VERTICES * 6);
    for (let s = 0, o = 0; s < count; s++) {
      // The segment's end points (6 floats) on each of its vertices.
      const p = 6 * s;
      for (let k = 0; k < SEGMENT_VERTICES; k++, o += 6) {
        ends[o] = positions[p];
        ends[o + 1] = positions[p + 1];
        ends[o + 2] = positions[p + 2];
        ends[o + 3] = positions[p + 3];
        ends[o + 4] = positions[p + 4];
        ends[o + 5] = positions[p + 5];
      }
    }
    // An open run's start caps: its first segment's, and its first non-degenerate one's after degenerate ones.
    let caps = 0;
    for (const [start, length, closed] of runs) {
      if (closed || !length) continue;
      let s = start;
      while (s < start + length - 1 && degenerate(positions, s)) s++;
      caps += s - start + 1;
    }
    const index = new Uint32Array(JOINED_INDICES * count + START_CAP * caps);
    /** Run r's last index + 1. */
    this.runEnds = new Uint32Array(runs.length);
    let i = 0,
      covered = 0;
    runs.forEach(([start, length, closed], r) => {
      let capped = closed;
      for (let s = start; s < start + length; s++) {
        // SEGMENT_INDEX's quads (see there): the end cap and the body, then the start cap where the line starts.
        const v = s * SEGMENT_VERTICES;
        storeQuad(index, i, v);
        storeQuad(index, i + 6, v + 2);
        i += JOINED_INDICES;
        if (!capped) {
          storeQuad(index, i, v + 4);
          i += START_CAP;
          capped = !degenerate(positions, s);
        }
      }
      covered += length;
      this.runEnds[r] = i;
    });
    if (covered !== count) throw new Error('SegmentGeometry: the runs do not cover every segment once');
    this.setIndex(new BufferAttribute(index, 1));
    const buffer = new InterleavedBuffer(ends, 6);
    this.setAttribute('instanceStart', new InterleavedBufferAttribute(buffer, 3, 0));
    this.setAttribute('instanceEnd', new InterleavedBufferAttribute(buffer, 3, 3));
    this.setAttribute('instanceShown', new BufferAttribute(new Uint8Array(count * SEGMENT_VERTICES), 1));
    // One entry per segment over the same floats (every 8th vertex), for LineSegments2's raycast.
    const perSegment = new InstancedInterleavedBuffer(ends, 6 * SEGMENT_VERTICES, 1);
    this.segments = new LineSegmentsGeometry();
    this.segments.setAttribute('instanceStart', new InterleavedBufferAttribute(perSegment, 3, 0));
    this.segments.setAttribute('instanceEnd', new InterleavedBufferAttribute(perSegment, 3, 3));
  }

  computeBoundingBox() {
    this.segments.computeBoundingBox();
    this.boundingBox = this.segments.boundingBox.clone();
  }

  /**
   * LineSegmentsGeometry's sphere (the box's centre, the farthest end point),
   * the same numbers by one loop over the floats instead of its attribute
   * accessors (the renderer asks for it at the first draw: 141k segments).
   */
  computeBoundingSphere() {
    // A segment's end points: the first 6 of its vertices' 8 × 6 floats.
    const floats = this.getAttribute('instanceStart').data.array;
    const stride = 6 * SEGMENT_VERTICES;
    const min = new Vector3(Infinity, Infinity, Infinity);
    const max = new Vector3(-Infinity, -Infinity, -Infinity);
    for (let s = 0; s < floats.length; s += stride) {
      for (let f = s; f < s + 6; f += 3) {
        min.set(Math.min(min.x, floats[f]), Math.min(min.y, floats[f + 1]), Math.min(min.z, floats[f + 2]));
        max.set(Math.max(max.x, floats[f]), Math.max(max.y, floats[f + 1]), Math.max(max.z, floats[f + 2]));
      }
    }
    const center = floats.length ? min.add(max).multiplyScalar(0.5) : new Vector3();
    let radiusSq = 0;
    for (let s = 0; s < floats.length; s += stride) {
      for (let f = s; f < s + 6; f += 3) {
        const dx = center.x - floats[f];
        const dy = center.y - floats[f + 1];
        const dz = center.z - floats[f + 2];
        radiusSq = Math.max(radiusSq, dx * dx + dy * dy + dz * dz);
      }
    }
    this.boundingSphere = new Sphere(center, Math.sqrt(radiusSq));
  }

  /** Shows (1) or hides (0) segments [first, first + count); the caller marks the upload range. */
  setShown(first, count, shown) {
    const attribute = this.getAttribute('instanceShown');
    attribute.array.fill(shown, first * SEGMENT_VERTICES, (first + count) * SEGMENT_VERTICES);
  }
}

/** LineSegments2 drawn from a SegmentGeometry (not instanced); picks as LineSegments2 does, one hit per segment. */
class SegmentLines extends LineSegments2 {
  raycast(raycaster, intersects) {
    const geometry = this.geometry;
    if (!geometry.segmentCount) return;
    this.geometry = geometry.segments;
    try {
      super.raycast(raycaster, intersects);
    } finally {
      this.geometry = geometry;
    }
  }
}

/**
 * LineMaterial for a SegmentGeometry: the template's corner (position) and
 * uv come from gl_VertexID % 8 instead of attributes, and a hidden segment
 * (instanceShown = 0) leaves the vertex shader at once, outside the clip volume.
 */
export function segmentLineMaterial(parameters) {
  const material = new LineMaterial(parameters);
  const shader = material.vertexShader;
  const replaced = shader
    .replace('attribute vec3 instanceEnd;', 'attribute vec3 instanceEnd;\n\t\tattribute float instanceShown;')
    .replace(
      'void main() {',
      `void main() {
			if ( instanceShown < 0.5 ) {
				gl_Position = vec4( 2.0, 2.0, 2.0, 1.0 );
				return;
			}
			int corner = gl_VertexID % ${SEGMENT_VERTICES};
			float row = float( 2 - corner / 2 );
			vec2 segmentCorner = vec2( ( corner % 2 ) == 1 ? 1.0 : - 1.0, row );
			vec2 segmentUv = vec2( segmentCorner.x, row > 0.5 ? row : row - 1.0 );`,
    )
    .replace(/\bposition\.([xy])\b/g, 'segmentCorner.$1')
    .replace('vUv = uv;', 'vUv = segmentUv;');
  if (!replaced.includes('segmentUv;') || /\bposition\b/.test(replaced.slice(replaced.indexOf('void main()'))))
    throw new Error('LineMaterial: its vertex shader is not the one segmentLineMaterial adapts');
  material.vertexShader = replaced;
  return material;
}

export class LineLayer {
  constructor({ ridgeColor = LINE_COLORS.ridge, valleyColor = LINE_COLORS.valley, width = 2.5 } = {}) {
    this.group = new Group();
    this.objects = [ridgeColor, valleyColor].map((color) => {
      const material = segmentLineMaterial({ color, linewidth: width, worldUnits: false });
      const object = new SegmentLines(new SegmentGeometry(), material);
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
    this.drawEnd = new Uint32Array(0);
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
    // The triangles in order of decreasing strength: the lines a threshold keeps (filter.cpp: strength at
    // least the threshold, but short weak ones) come first, and a draw range ends at the weakest one kept.
    // The hidden segments past it cost nothing; drawn and hidden, they cost SwiftShader about as much as shown.
    const strengths = lines.strengths;
    const byStrength = Array.from({ length: count }, (_, l) => l).sort((a, b) => (strengths ? strengths[b] - strengths[a] : 0) || a - b);
    this.drawEnd = new Uint32Array(count); // line → the indices drawn up to and with it, in its type's order
    const runs = [[], []];
    const runLines = [[], []];
    for (const l of byStrength) {
      const type = lines.types[l];
      if (type !== RIDGE && type !== VALLEY) continue;
      runs[type].push([this.firstSegment[l], this.segments[l], lines.closed[l] === 1]);
      runLines[type].push(l);
    }
    for (const type of [RIDGE, VALLEY]) {
      const object = this.objects[type];
      object.geometry.dispose();
      const geometry = new SegmentGeometry(segmentPositions(lines, type, origin), runs[type]);
      runLines[type].forEach((l, r) => (this.drawEnd[l] = geometry.runEnds[r]));
      object.geometry = geometry;
      object.userData.segments = geometry.segmentCount;
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
      const first = this.firstSegment[l];
      this.objects[type].geometry.setShown(first, this.segments[l], next[l]);
      ranges[type][0] = Math.min(ranges[type][0], first);
      ranges[type][1] = Math.max(ranges[type][1], first + this.segments[l]);
    }
    this.kept = next;
    this.shownSegments = [0, 0];
    const ends = [0, 0];
    for (let l = 0; l < this.lineCount; l++) {
      if (!next[l]) continue;
      this.shownSegments[this.types[l]] += this.segments[l];
      ends[this.types[l]] = Math.max(ends[this.types[l]], this.drawEnd[l]);
    }
    for (const type of [RIDGE, VALLEY]) this.objects[type].geometry.setDrawRange(0, ends[type]);
    for (const type of [RIDGE, VALLEY]) {
      const [start, end] = ranges[type];
      if (end < 0) continue;
      const attribute = this.objects[type].geometry.getAttribute('instanceShown');
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(start * SEGMENT_VERTICES, (end - start) * SEGMENT_VERTICES);
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
