// Levels of detail for drawing lines. A faired line has a point at every
// edge it crosses, so on a large mesh seen whole its segments are shorter
// than a pixel, and each one costs its vertices to draw (the dragon's 98k
// shown segments: 0.55 s of CPU in headless Chromium's SwiftShader). Drawn
// with the points whose leaving out would move the line by more than a
// fraction of a pixel, it looks the same with a fraction of the segments.
// Which points those are follows Douglas–Peucker: a point's importance is
// the largest tolerance at which Douglas–Peucker keeps it, so one pass gives
// every level, each the points whose importance exceeds its tolerance.
import { Vector3 } from 'three';

/**
 * Per point of `lines` (points x,y,z, offsets: line l is points
 * offsets[l]…offsets[l+1]−1), its importance in the points' units: a line's
 * first and last points Infinity, every other one its distance to the chord
 * of the interval of Douglas–Peucker's recursion it splits, capped by that
 * interval's own splitting point's (so a point is kept at tolerance ε,
 * importance > ε, exactly when Douglas–Peucker at ε keeps it). Dropping the
 * points of importance ≤ ε moves no point of the line by more than ε from
 * the line drawn (the Hausdorff bound of Douglas–Peucker). A closed line
 * keeps its closing segment, last point back to first, as it is.
 */
export function pointImportance({ points, offsets }) {
  const lineCount = offsets.length - 1;
  const total = lineCount >= 0 ? offsets[lineCount] : 0;
  const importance = new Float32Array(total); // 0: a point no interval splits (collinear, or too few)
  let longest = 0;
  for (let l = 0; l < lineCount; l++) longest = Math.max(longest, offsets[l + 1] - offsets[l]);
  // Intervals to split: first, last and the cap, at most one per point of the longest line.
  const stack = new Float64Array(3 * Math.max(1, longest));
  for (let l = 0; l < lineCount; l++) {
    const first = offsets[l];
    const last = offsets[l + 1] - 1;
    if (last < first) continue;
    importance[first] = importance[last] = Infinity;
    let top = 0;
    stack[top++] = first;
    stack[top++] = last;
    stack[top++] = Infinity;
    while (top) {
      const cap = stack[--top];
      const j = stack[--top];
      const i = stack[--top];
      if (j - i < 2) continue;
      const ax = points[3 * i],
        ay = points[3 * i + 1],
        az = points[3 * i + 2];
      const dx = points[3 * j] - ax,
        dy = points[3 * j + 1] - ay,
        dz = points[3 * j + 2] - az;
      const length2 = dx * dx + dy * dy + dz * dz;
      let farthest = -1;
      let distance2 = -1;
      for (let k = i + 1; k < j; k++) {
        const px = points[3 * k] - ax,
          py = points[3 * k + 1] - ay,
          pz = points[3 * k + 2] - az;
        // The distance to the chord as a segment (to its nearer end beyond it).
        const t = length2 > 0 ? Math.min(1, Math.max(0, (px * dx + py * dy + pz * dz) / length2)) : 0;
        const ex = px - t * dx,
          ey = py - t * dy,
          ez = pz - t * dz;
        const d2 = ex * ex + ey * ey + ez * ez;
        if (d2 > distance2) ((distance2 = d2), (farthest = k));
      }
      const value = Math.min(Math.sqrt(distance2), cap);
      importance[farthest] = value;
      stack[top++] = i;
      stack[top++] = farthest;
      stack[top++] = value;
      stack[top++] = farthest;
      stack[top++] = j;
      stack[top++] = value;
    }
  }
  return importance;
}

/** How much of a pixel a drawn line may be off its points: a fifth (less than a line's antialiased rim shows). */
export const DETAIL_PIXELS = 0.2;

const eye = new Vector3();
const forward = new Vector3();

/**
 * The smallest length in world units that a pixel of `camera`'s view
 * `height` pixels high spans anywhere on a sphere (`center` in world
 * coordinates, `radius`): at the sphere's nearest depth, or the near plane's
 * if the sphere reaches it. A perspective view's pixel grows with depth.
 */
export function worldPerPixel(camera, center, radius, height) {
  if (camera.isOrthographicCamera) return (camera.top - camera.bottom) / camera.zoom / height;
  camera.getWorldDirection(forward);
  const depth = eye.subVectors(center, camera.getWorldPosition(eye)).dot(forward);
  const nearest = Math.max(depth - radius, camera.near);
  return (2 * nearest * Math.tan(((camera.fov / 2) * Math.PI) / 180)) / camera.zoom / height;
}
