// Ridges and valleys as wide lines (LineSegments2's look), one object per
// type; a second layer draws the creases (convex and concave as its two types).
// The geometry holds every faired line; a threshold change only shows or
// hides line ranges (a per-segment flag the vertex shader reads), so it
// uploads one flag per changed segment vertex and rebuilds nothing.
//
// The segments are not instanced: each one is 8 vertices of its own (the
// LineSegmentsGeometry template's, told apart by gl_VertexID % 8), drawn
// with LineMaterial's own shaders; one instanced draw of 141k segments costs
// WebGL on the CPU (SwiftShader) about three times as much as this one. The
// vertices carry no end points: segment s's two are texels 2s and 2s + 1 of
// a float texture (the segments' positions as they are, 24 bytes a segment),
// which the vertex shader reads by gl_VertexID / 8. Copying them onto each
// of the 8 vertices instead (192 bytes a segment) made the dragon's 141k
// segments 27 MB to build and upload on the main thread. A segment draws its
// start cap (a half disc) only where its line starts: elsewhere the previous
// segment's body and end cap cover that half disc already, so the line
// covers the same pixels as LineSegments2's, with two of each segment's six
// triangles and eight vertices fewer to draw. Only where the dropped cap's
// depth (its start point's) decided a depth test against another object may
// a pixel differ (tests/browser/line-layer.test.mjs bounds it).
//
// A layer draws its lines at a level of detail (line-detail.js): every
// point unless the viewer calls fitDetail(camera) before its frames, which
// then draws the points that keep each line within DETAIL_PIXELS of all of
// them (the dragon seen whole: 98k shown segments -> 16k). Each level is an
// index and a geometry of its own, made when first drawn; a threshold
// change writes the flags of the level drawn, and of another level when it
// is drawn again.
import {
  BufferAttribute,
  BufferGeometry,
  Color,
  DataTexture,
  FloatType,
  Group,
  InstancedInterleavedBuffer,
  InterleavedBufferAttribute,
  NearestFilter,
  RGBFormat,
  Sphere,
  Vector3,
} from 'three';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { LINE_COLORS } from './colors.js';
import { DETAIL_PIXELS, pointImportance, worldPerPixel } from './line-detail.js';

export const RIDGE = 0;
export const VALLEY = 1;
/** In a crease layer (creaseLayer): type 0 convex, 1 concave. */
export const CONVEX = 0;
export const CONCAVE = 1;

/** The concave creases' shade of the crease colour: darker, so the two kinds stay apart. */
export const concaveShade = (color) => new Color(color).multiplyScalar(0.55);

/** Session.creases() as Lines whose types are CONVEX / CONCAVE (for a LineLayer). */
export const creasesAsLines = (creases) => ({ ...creases, types: Uint8Array.from(creases.convex, (c) => (c ? CONVEX : CONCAVE)) });

/**
 * Segments of line l (of its points with mask[p] set, if a mask is given): a
 * closed line also joins its last point to its first.
 */
const segmentCount = (lines, l, mask) => {
  let n = lines.offsets[l + 1] - lines.offsets[l];
  if (mask) for (let p = lines.offsets[l], end = lines.offsets[l + 1]; p < end; p++) n -= mask[p] ? 0 : 1;
  return lines.closed[l] ? n : Math.max(0, n - 1);
};

/**
 * Segment end points (x,y,z pairs, float32, minus `origin`) of the lines of
 * one type; with a `mask`, between the points it keeps (mask[p] set) only,
 * which must include each line's first and last.
 */
export function segmentPositions(lines, type, origin, mask = null) {
  const { points, offsets, types } = lines;
  let count = 0;
  for (let l = 0; l < types.length; l++) if (types[l] === type) count += segmentCount(lines, l, mask);
  const out = new Float32Array(count * 6);
  let o = 0;
  for (let l = 0; l < types.length; l++) {
    if (types[l] !== type) continue;
    const first = offsets[l];
    const end = offsets[l + 1];
    if (first === end) continue;
    let a = 3 * first;
    for (let p = first + 1; p < end; p++) {
      if (mask && !mask[p]) continue;
      o = storeSegment(out, o, points, a, 3 * p, origin);
      a = 3 * p;
    }
    if (lines.closed[l]) o = storeSegment(out, o, points, a, 3 * first, origin);
  }
  return out;
}

/** Points a and b (float indices into points) minus origin at out[o…o + 5]; returns o + 6. */
function storeSegment(out, o, points, a, b, origin) {
  out[o] = points[a] - origin[0];
  out[o + 1] = points[a + 1] - origin[1];
  out[o + 2] = points[a + 2] - origin[2];
  out[o + 3] = points[b] - origin[0];
  out[o + 4] = points[b + 1] - origin[1];
  out[o + 5] = points[b + 2] - origin[2];
  return o + 6;
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
 * Texels a row of the texture of `count` segments (two texels each): 2,048
 * (1,024 segments), WebGL 2's least maximum size, up to 2,048 rows; beyond,
 * as many texels a row as rows, rounded up to even.
 */
export function segmentTextureWidth(count) {
  const side = Math.ceil(Math.sqrt(2 * count));
  return Math.max(2048, side + (side % 2));
}

/**
 * The segments `positions` (end point pairs, as segmentPositions makes them)
 * as a plain indexed geometry: 8 vertices per segment, each with the
 * segment's shown flag (instanceShown, 0 until setKept) and nothing else;
 * the end points are `ends`, an RGB float texture (segment s: texels 2s and
 * 2s + 1, rows of segmentTextureWidth texels) that segmentLineMaterial's
 * shader reads. `runs` ([first segment, count, closed] triples covering
 * every segment once, by default each segment alone) are the lines, each
 * segment's end the next one's start (and the last one's the first one's
 * when closed), in the order of the triangles in the index: a draw range
 * over its start up to runEnds[r] draws runs 0…r only. An open run's start
 * cap goes with its first segment of any length.
 */
export class SegmentGeometry extends BufferGeometry {
  constructor(positions = new Float32Array(0), runs = Array.from({ length: positions.length / 6 }, (_, s) => [s, 1, false])) {
    super();
    this.type = 'SegmentGeometry';
    const count = positions.length / 6;
    this.segmentCount = count;
    // The texture's rows are whole; the floats past the segments' are 0 and never read.
    const width = segmentTextureWidth(count);
    const height = Math.max(1, Math.ceil((2 * count) / width));
    const texels = new Float32Array(3 * width * height);
    texels.set(positions);
    // The end points for the raycast and the bounds: the texture's own floats, not a second copy.
    this.positions = texels.subarray(0, positions.length);
    this.ends = new DataTexture(texels, width, height, RGBFormat, FloatType);
    this.ends.internalFormat = 'RGB32F'; // three names none for RGB floats itself
    this.ends.minFilter = this.ends.magFilter = NearestFilter;
    this.ends.needsUpdate = true;
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
    this.setAttribute('instanceShown', new BufferAttribute(new Uint8Array(count * SEGMENT_VERTICES), 1));
    // One entry per segment over the positions, for LineSegments2's raycast.
    const perSegment = new InstancedInterleavedBuffer(this.positions, 6, 1);
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
    const floats = this.positions;
    const min = new Vector3(Infinity, Infinity, Infinity);
    const max = new Vector3(-Infinity, -Infinity, -Infinity);
    for (let f = 0; f < floats.length; f += 3) {
      min.set(Math.min(min.x, floats[f]), Math.min(min.y, floats[f + 1]), Math.min(min.z, floats[f + 2]));
      max.set(Math.max(max.x, floats[f]), Math.max(max.y, floats[f + 1]), Math.max(max.z, floats[f + 2]));
    }
    const center = floats.length ? min.add(max).multiplyScalar(0.5) : new Vector3();
    let radiusSq = 0;
    for (let f = 0; f < floats.length; f += 3) {
      const dx = center.x - floats[f];
      const dy = center.y - floats[f + 1];
      const dz = center.z - floats[f + 2];
      radiusSq = Math.max(radiusSq, dx * dx + dy * dy + dz * dz);
    }
    this.boundingSphere = new Sphere(center, Math.sqrt(radiusSq));
  }

  /** Shows (1) or hides (0) segments [first, first + count); the caller marks the upload range. */
  setShown(first, count, shown) {
    const attribute = this.getAttribute('instanceShown');
    attribute.array.fill(shown, first * SEGMENT_VERTICES, (first + count) * SEGMENT_VERTICES);
  }

  dispose() {
    this.ends.dispose();
    super.dispose();
  }
}

/**
 * LineSegments2 drawn from a SegmentGeometry (not instanced), its material
 * reading the geometry's end points; picks as LineSegments2 does, one hit
 * per segment.
 */
class SegmentLines extends LineSegments2 {
  onBeforeRender(renderer, scene, camera, geometry, material) {
    // The renderer uploads a material's uniforms at its first draw in a frame (each object has a material of its own).
    material.uniforms.segmentEnds.value = geometry.ends;
  }

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
 * uv come from gl_VertexID % 8 instead of attributes, the end points
 * (instanceStart, instanceEnd) from the geometry's texture, and a hidden
 * segment (instanceShown = 0) leaves the vertex shader at once, outside the
 * clip volume.
 */
export function segmentLineMaterial(parameters) {
  const material = new LineMaterial(parameters);
  material.uniforms.segmentEnds = { value: null };
  const shader = material.vertexShader;
  const replaced = shader
    .replace(
      /attribute vec3 instanceStart;\s*attribute vec3 instanceEnd;/,
      'uniform highp sampler2D segmentEnds; // segment s: texels 2s, 2s + 1\n\t\tattribute float instanceShown;',
    )
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
			vec2 segmentUv = vec2( segmentCorner.x, row > 0.5 ? row : row - 1.0 );
			int texel = 2 * ( gl_VertexID / ${SEGMENT_VERTICES} );
			int width = textureSize( segmentEnds, 0 ).x; // even: a segment's two texels share a row
			ivec2 at = ivec2( texel % width, texel / width );
			vec3 instanceStart = texelFetch( segmentEnds, at, 0 ).xyz;
			vec3 instanceEnd = texelFetch( segmentEnds, at + ivec2( 1, 0 ), 0 ).xyz;`,
    )
    .replace(/\bposition\.([xy])\b/g, 'segmentCorner.$1')
    .replace('vUv = uv;', 'vUv = segmentUv;');
  if (
    !replaced.includes('segmentUv;') ||
    /attribute vec3 instance(Start|End)/.test(replaced) ||
    /\bposition\b/.test(replaced.slice(replaced.indexOf('void main()')))
  )
    throw new Error('LineMaterial: its vertex shader is not the one segmentLineMaterial adapts');
  material.vertexShader = replaced;
  return material;
}

/** The bounding sphere of the lines' points minus `origin`: the box's centre, the farthest point. */
function linesSphere({ points, offsets }, origin) {
  const end = 3 * (offsets.length ? offsets[offsets.length - 1] : 0);
  if (!end) return new Sphere(new Vector3(), 0);
  const low = [Infinity, Infinity, Infinity];
  const high = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < end; i += 3)
    for (let k = 0; k < 3; k++) {
      const x = points[i + k];
      if (x < low[k]) low[k] = x;
      if (x > high[k]) high[k] = x;
    }
  const center = [0, 1, 2].map((k) => (low[k] + high[k]) / 2);
  let radius2 = 0;
  for (let i = 0; i < end; i += 3) {
    const dx = points[i] - center[0],
      dy = points[i + 1] - center[1],
      dz = points[i + 2] - center[2];
    radius2 = Math.max(radius2, dx * dx + dy * dy + dz * dz);
  }
  return new Sphere(new Vector3(center[0] - origin[0], center[1] - origin[1], center[2] - origin[2]), Math.sqrt(radius2));
}

/** The `q` quantile of the finite importances (the points a level may leave out), from every k-th point (4096 or so); Infinity if none. */
function importanceQuantile(importance, q) {
  const stride = Math.max(1, Math.floor(importance.length / 4096));
  const sample = [];
  for (let p = 0; p < importance.length; p += stride) if (importance[p] < Infinity) sample.push(importance[p]);
  if (!sample.length) return Infinity;
  sample.sort((a, b) => a - b);
  return sample[Math.min(sample.length - 1, Math.floor(q * sample.length))];
}

const worldCenter = new Vector3();

/** The level of detail with every point (LineLayer.setDetail). */
export const FULL_DETAIL = 'full';
/** The coarser levels a layer keeps beside the one shown, at most this many segments (times its full count) in all. */
const CACHED_LEVEL_SEGMENTS = 2;

export class LineLayer {
  constructor({ ridgeColor = LINE_COLORS.ridge, valleyColor = LINE_COLORS.valley, width = 2.5 } = {}) {
    this.group = new Group();
    this.objects = [ridgeColor, valleyColor].map((color) => {
      const material = segmentLineMaterial({ color, linewidth: width, worldUnits: false });
      const object = new SegmentLines(new SegmentGeometry(), material);
      object.frustumCulled = false;
      object.renderOrder = 1;
      object.userData.segments = 0; // the lines' segments at full detail
      object.userData.empty = object.geometry; // drawn until fitDetail chooses a level for new lines
      this.group.add(object);
      return object;
    });
    this.lines = null;
    this.lineCount = 0;
    this.types = new Uint8Array(0);
    this.kept = new Uint8Array(0); // line → shown (1) or not
    /** Levels of detail made (FULL_DETAIL, or a level number: see detailFor), the one drawn is `level`. */
    this.levels = new Map();
    this.level = null;
    /** Whether setDetail chooses the level (fitDetail was called); else every point is drawn. */
    this.autoDetail = false;
    this.height = 0; // the view's CSS pixels, for fitDetail
  }

  /**
   * Every line of the mesh (Session.lines(true)); `kept` (Uint32Array of line
   * indices, or undefined for all) says which are shown. The geometry of a
   * level of detail is made when it is first drawn: every point's now unless
   * fitDetail chose the levels before.
   */
  setLines(lines, origin, kept) {
    const count = lines.types.length;
    this.disposeLevels();
    this.lines = lines;
    this.origin = [...origin];
    this.lineCount = count;
    this.types = lines.types.slice();
    // The worker's (the core's point_importance, the same numbers), else pointImportance's when a coarser level is first asked for.
    this.importance = lines.importance?.length === (lines.offsets[count] ?? 0) ? lines.importance : null;
    const full = [0, 0];
    for (let l = 0; l < count; l++) if (this.types[l] === RIDGE || this.types[l] === VALLEY) full[this.types[l]] += segmentCount(lines, l);
    this.objects.forEach((o, type) => (o.userData.segments = full[type]));
    // The lines in order of decreasing strength: the lines a threshold keeps (filter.cpp: strength at least the
    // threshold, but short weak ones) come first, and a draw range ends at the weakest one kept. The hidden
    // segments past it cost nothing; drawn and hidden, they cost SwiftShader about as much as shown.
    const strengths = lines.strengths;
    this.byStrength = Array.from({ length: count }, (_, l) => l).sort((a, b) => (strengths ? strengths[b] - strengths[a] : 0) || a - b);
    this.sphere = linesSphere(lines, this.origin);
    this.kept = new Uint8Array(count);
    this.setKept(kept ?? Uint32Array.from({ length: count }, (_, l) => l));
    if (!this.autoDetail) this.setDetail(FULL_DETAIL);
    else for (const o of this.objects) o.geometry = o.userData.empty; // fitDetail's level, at the next draw
  }

  /**
   * Shows the lines in `kept` (indices into the lines of setLines) and hides
   * the others: only the flags of lines that changed are written and uploaded
   * (those of the level drawn; another level's when it is drawn again).
   */
  setKept(kept) {
    const next = new Uint8Array(this.lineCount);
    for (const l of kept) next[l] = 1;
    this.kept = next;
    if (this.level) this.applyKept(this.level);
    this.applyVisibility();
  }

  /** The flags of `level`'s segments as this.kept says, only those of lines that changed since it last took them. */
  applyKept(level) {
    const { firstSegment, segments, drawEnd, geometries } = level;
    const ranges = [
      [Infinity, -1],
      [Infinity, -1],
    ];
    for (let l = 0; l < this.lineCount; l++) {
      if (this.kept[l] === level.kept[l] || !segments[l]) continue;
      const type = this.types[l];
      const first = firstSegment[l];
      geometries[type].setShown(first, segments[l], this.kept[l]);
      ranges[type][0] = Math.min(ranges[type][0], first);
      ranges[type][1] = Math.max(ranges[type][1], first + segments[l]);
    }
    level.kept = this.kept;
    const ends = [0, 0];
    for (let l = 0; l < this.lineCount; l++) if (this.kept[l] && segments[l]) ends[this.types[l]] = Math.max(ends[this.types[l]], drawEnd[l]);
    for (const type of [RIDGE, VALLEY]) {
      const geometry = geometries[type];
      geometry.setDrawRange(0, ends[type]);
      const [start, end] = ranges[type];
      if (end < 0) continue;
      const attribute = geometry.getAttribute('instanceShown');
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(start * SEGMENT_VERTICES, (end - start) * SEGMENT_VERTICES);
      attribute.needsUpdate = true;
    }
  }

  /**
   * Draws the lines at the level of detail that looks like every point in
   * `camera`'s view, `height` pixels high (setResolution's CSS pixels by
   * default; the viewers pass the image's device pixels): no drawn line
   * more than DETAIL_PIXELS of a pixel off its points. The viewers call it
   * before each frame.
   */
  fitDetail(camera, height = this.height) {
    this.autoDetail = true;
    if (this.lines) this.setDetail(this.detailFor(camera, height));
  }

  /** fitDetail's level: FULL_DETAIL, or k for the points of importance above radius · 2^(k/2). */
  detailFor(camera, height) {
    const { center, radius } = this.sphere;
    if (!(radius > 0) || !(height > 1)) return FULL_DETAIL;
    this.group.updateWorldMatrix(true, false);
    const matrix = this.group.matrixWorld;
    const scale = matrix.getMaxScaleOnAxis();
    const tolerance = (DETAIL_PIXELS * worldPerPixel(camera, worldCenter.copy(center).applyMatrix4(matrix), radius * scale, height)) / scale;
    this.importance ??= pointImportance(this.lines);
    this.fullBelow ??= importanceQuantile(this.importance, 0.1);
    // Where all but a tenth of the points would be kept, all are: not a level of its own.
    if (!(tolerance > this.fullBelow)) return FULL_DETAIL;
    return Math.floor(2 * Math.log2(tolerance / radius));
  }

  /** Draws `key`'s level of detail (FULL_DETAIL or detailFor's number), made now if it is not kept. */
  setDetail(key) {
    if (!this.lines) return;
    let level = this.levels.get(key);
    const made = !level;
    if (made) level = this.makeLevel(key);
    // Most recently drawn last.
    this.levels.delete(key);
    this.levels.set(key, level);
    if (level !== this.level) {
      this.level = level;
      this.objects.forEach((o, type) => (o.geometry = level.geometries[type]));
    }
    // A frame with the same lines kept writes nothing.
    if (level.kept !== this.kept) this.applyKept(level);
    if (made) this.evictLevels();
  }

  makeLevel(key) {
    const lines = this.lines;
    let mask = null;
    if (key !== FULL_DETAIL) {
      this.importance ??= pointImportance(lines);
      const tolerance = this.sphere.radius * 2 ** (key / 2);
      mask = new Uint8Array(this.importance.length);
      for (let p = 0; p < mask.length; p++) mask[p] = this.importance[p] > tolerance ? 1 : 0;
    }
    const count = this.lineCount;
    const firstSegment = new Uint32Array(count); // line → its first segment in its type's geometry
    const segments = new Uint32Array(count); // line → its segment count
    const next = [0, 0];
    for (let l = 0; l < count; l++) {
      const type = this.types[l];
      if (type !== RIDGE && type !== VALLEY) continue;
      segments[l] = segmentCount(lines, l, mask);
      firstSegment[l] = next[type];
      next[type] += segments[l];
    }
    const drawEnd = new Uint32Array(count); // line → the indices drawn up to and with it, in its type's order
    const runs = [[], []];
    const runLines = [[], []];
    for (const l of this.byStrength) {
      const type = this.types[l];
      if (type !== RIDGE && type !== VALLEY) continue;
      runs[type].push([firstSegment[l], segments[l], lines.closed[l] === 1]);
      runLines[type].push(l);
    }
    const geometries = [RIDGE, VALLEY].map((type) => {
      const geometry = new SegmentGeometry(segmentPositions(lines, type, this.origin, mask), runs[type]);
      runLines[type].forEach((l, r) => (drawEnd[l] = geometry.runEnds[r]));
      return geometry;
    });
    // No flag set yet (SegmentGeometry's are 0): applyKept sets those of the lines kept.
    return { key, firstSegment, segments, drawEnd, geometries, kept: new Uint8Array(count), segmentCount: next[0] + next[1] };
  }

  /** Frees the least recently drawn levels but the one drawn while those kept have more segments than allowed. */
  evictLevels() {
    const allowed = CACHED_LEVEL_SEGMENTS * (this.objects[0].userData.segments + this.objects[1].userData.segments);
    let total = 0;
    for (const level of this.levels.values()) total += level.segmentCount;
    for (const [key, level] of this.levels) {
      if (total <= allowed) break;
      if (level === this.level) continue;
      for (const geometry of level.geometries) geometry.dispose();
      this.levels.delete(key);
      total -= level.segmentCount;
    }
  }

  disposeLevels() {
    for (const level of this.levels.values()) for (const geometry of level.geometries) geometry.dispose();
    this.levels.clear();
    this.level = null;
    this.fullBelow = undefined;
  }

  setShown(ridges, valleys) {
    this.shown = [ridges, valleys];
    this.applyVisibility();
  }

  applyVisibility() {
    // A line with a segment has one at every level of detail (its first and last points are in each).
    const shown = [false, false];
    for (let l = 0; l < this.lineCount; l++)
      if (this.kept[l] && (this.types[l] === RIDGE || this.types[l] === VALLEY)) shown[this.types[l]] ||= segmentCount(this.lines, l) > 0;
    this.objects.forEach((o, type) => (o.visible = this.shown?.[type] !== false && shown[type]));
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
    this.height = height;
  }

  dispose() {
    this.disposeLevels();
    for (const o of this.objects) {
      o.userData.empty.dispose();
      o.material.dispose();
    }
  }
}
