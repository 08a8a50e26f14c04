// What the smoothing brush needs to stay cheap on a mesh of a million
// triangles: a bounding volume hierarchy for picking (one ray costs a few
// dozen box tests instead of a test per triangle) and the vertex adjacency
// for distances measured along the surface (Dijkstra over the edges, bounded
// by the brush radius), so a brush does not paint through a thin part.
// Built once per surface, lazily; in a browser off the main thread, by a
// second instance of the one worker (handler.js, 'surface-index': it sends
// the arrays back, SurfaceIndex.parts); no three.js objects.

const LEAF = 8; // triangles per leaf at most

/** Grows the box [x0, y0, z0, x1, y1, z1] to hold (x, y, z). */
function expand(box, x, y, z) {
  if (x < box[0]) box[0] = x;
  if (x > box[3]) box[3] = x;
  if (y < box[1]) box[1] = y;
  if (y > box[4]) box[4] = y;
  if (z < box[2]) box[2] = z;
  if (z > box[5]) box[5] = z;
}

/** An empty box for expand. */
const emptyBox = (box) => box.set([Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity]);
const scratch = new Float64Array(6);

/** Bounds of the triangles order[start, end) into out[6 * node…]. */
function triangleBounds(positions, indices, order, start, end, out, node) {
  emptyBox(scratch);
  for (let i = start; i < end; i++) {
    const t = 3 * order[i];
    for (let k = 0; k < 3; k++) {
      const v = 3 * indices[t + k];
      expand(scratch, positions[v], positions[v + 1], positions[v + 2]);
    }
  }
  out.set(scratch, 6 * node);
}

/** Reorders order[start, end) so that the k-th smallest key sits at k, smaller ones before (quickselect). */
function select(order, keys, start, end, k) {
  let [lo, hi] = [start, end - 1];
  while (hi > lo) {
    const pivot = keys[order[(lo + hi) >>> 1]];
    let [i, j] = [lo, hi];
    while (i <= j) {
      while (keys[order[i]] < pivot) i++;
      while (keys[order[j]] > pivot) j--;
      if (i <= j) {
        const swap = order[i];
        order[i] = order[j];
        order[j] = swap;
        i++;
        j--;
      }
    }
    if (k <= j) hi = j;
    else if (k >= i) lo = i;
    else return;
  }
}

/** A binary min-heap of (distance, vertex) with lazy deletion. */
class Heap {
  constructor() {
    this.keys = new Float64Array(1024);
    this.values = new Int32Array(1024);
    this.size = 0;
  }

  push(key, value) {
    if (this.size === this.keys.length) {
      const [keys, values] = [new Float64Array(2 * this.size), new Int32Array(2 * this.size)];
      keys.set(this.keys);
      values.set(this.values);
      [this.keys, this.values] = [keys, values];
    }
    let i = this.size++;
    while (i > 0) {
      const parent = (i - 1) >> 1;
      if (this.keys[parent] <= key) break;
      this.keys[i] = this.keys[parent];
      this.values[i] = this.values[parent];
      i = parent;
    }
    this.keys[i] = key;
    this.values[i] = value;
  }

  /** Removes the smallest; its key and value are in this.key / this.value. */
  pop() {
    this.key = this.keys[0];
    this.value = this.values[0];
    const [key, value] = [this.keys[--this.size], this.values[this.size]];
    let i = 0;
    for (;;) {
      let child = 2 * i + 1;
      if (child >= this.size) break;
      if (child + 1 < this.size && this.keys[child + 1] < this.keys[child]) child++;
      if (this.keys[child] >= key) break;
      this.keys[i] = this.keys[child];
      this.values[i] = this.values[child];
      i = child;
    }
    this.keys[i] = key;
    this.values[i] = value;
  }
}

/**
 * @typedef {{order: Uint32Array, bounds: Float32Array, first: Uint32Array, size: Uint32Array, nodes: number,
 *            offsets: Uint32Array, neighbours: Uint32Array}} SurfaceIndexParts
 */

export class SurfaceIndex {
  /**
   * @param {Float32Array} positions xyz per vertex @param {Uint32Array} indices three per triangle
   * @param {object} [parts] the tree and adjacency built elsewhere (SurfaceIndex.parts of an index of the same surface)
   */
  constructor(positions, indices, parts) {
    this.positions = positions;
    this.indices = indices;
    if (parts) Object.assign(this, parts);
    else {
      this.buildTree();
      this.buildAdjacency();
    }
    const n = positions.length / 3;
    this.distance = new Float64Array(n);
    this.stamp = new Uint32Array(n); // distance[v] is valid when stamp[v] === this.round
    this.round = 0;
    this.heap = new Heap();
  }

  /**
   * What a copy of `index` needs besides the surface (typed arrays, and the node count).
   * @param {SurfaceIndex} index
   * @returns {SurfaceIndexParts}
   */
  static parts({ order, bounds, first, size, nodes, offsets, neighbours }) {
    return { order, bounds, first, size, nodes, offsets, neighbours };
  }

  buildTree() {
    const { positions, indices } = this;
    const count = indices.length / 3;
    const centroids = [new Float32Array(count), new Float32Array(count), new Float32Array(count)];
    for (let t = 0; t < count; t++) {
      for (let axis = 0; axis < 3; axis++) {
        centroids[axis][t] = (positions[3 * indices[3 * t] + axis] + positions[3 * indices[3 * t + 1] + axis] + positions[3 * indices[3 * t + 2] + axis]) / 3;
      }
    }
    const order = new Uint32Array(count);
    for (let t = 0; t < count; t++) order[t] = t;
    const capacity = Math.max(1, Math.ceil((4 * count) / LEAF) + 1);
    const bounds = new Float32Array(6 * capacity);
    const first = new Uint32Array(capacity); // leaf: its first triangle in `order`; inner: its left child
    const size = new Uint32Array(capacity); // leaf: its triangle count; inner: 0
    let nodes = 1;
    const stack = [[0, 0, count]];
    while (stack.length) {
      const [node, start, end] = stack.pop();
      if (end - start <= LEAF) {
        triangleBounds(positions, indices, order, start, end, bounds, node);
        first[node] = start;
        size[node] = end - start;
        continue;
      }
      // Split at the median centroid along the longest side of the centroids' box.
      const [cx, cy, cz] = centroids;
      emptyBox(scratch);
      for (let i = start; i < end; i++) {
        const t = order[i];
        expand(scratch, cx[t], cy[t], cz[t]);
      }
      const extents = [scratch[3] - scratch[0], scratch[4] - scratch[1], scratch[5] - scratch[2]];
      const best = extents.indexOf(Math.max(...extents));
      const middle = (start + end) >>> 1;
      select(order, centroids[best], start, end, middle);
      first[node] = nodes;
      size[node] = 0;
      stack.push([nodes, start, middle], [nodes + 1, middle, end]);
      nodes += 2;
    }
    // Inner boxes from their children's (children come after their parent).
    for (let node = nodes - 1; node >= 0; node--) {
      if (size[node]) continue;
      const [l, r] = [6 * first[node], 6 * (first[node] + 1)];
      for (let k = 0; k < 3; k++) {
        bounds[6 * node + k] = Math.min(bounds[l + k], bounds[r + k]);
        bounds[6 * node + 3 + k] = Math.max(bounds[l + 3 + k], bounds[r + 3 + k]);
      }
    }
    Object.assign(this, { order, bounds, first, size, nodes });
  }

  buildAdjacency() {
    const { indices } = this;
    const n = this.positions.length / 3;
    const offsets = new Uint32Array(n + 1);
    for (let i = 0; i < indices.length; i++) offsets[indices[i] + 1] += 2;
    for (let v = 0; v < n; v++) offsets[v + 1] += offsets[v];
    const neighbours = new Uint32Array(offsets[n]);
    const fill = offsets.slice(0, n);
    for (let t = 0; t < indices.length; t += 3) {
      for (let k = 0; k < 3; k++) {
        const [a, b, c] = [indices[t + k], indices[t + ((k + 1) % 3)], indices[t + ((k + 2) % 3)]];
        neighbours[fill[a]++] = b;
        neighbours[fill[a]++] = c;
      }
    }
    Object.assign(this, { offsets, neighbours });
  }

  /**
   * The nearest triangle the ray origin + t·direction hits (either side).
   * @param {{x: number, y: number, z: number}} o @param {{x: number, y: number, z: number}} d
   * @returns {{triangle: number, t: number, point: number[]} | null}
   */
  raycast(o, d) {
    const { bounds, first, size, order, indices, positions } = this;
    const inv = [1 / d.x, 1 / d.y, 1 / d.z];
    const origin = [o.x, o.y, o.z];
    let nearest = Infinity,
      hit = -1;
    const stack = [0];
    while (stack.length) {
      const node = stack.pop();
      // Slab test of the node's box.
      let near = 0,
        far = nearest;
      for (let axis = 0; axis < 3; axis++) {
        let t0 = (bounds[6 * node + axis] - origin[axis]) * inv[axis];
        let t1 = (bounds[6 * node + 3 + axis] - origin[axis]) * inv[axis];
        if (t0 > t1) [t0, t1] = [t1, t0];
        if (t0 > near) near = t0;
        if (t1 < far) far = t1;
        if (near > far) break;
      }
      if (near > far) continue;
      if (size[node]) {
        for (let i = first[node]; i < first[node] + size[node]; i++) {
          const t = intersect(positions, indices, order[i], o, d);
          if (t < nearest) [nearest, hit] = [t, order[i]];
        }
      } else {
        stack.push(first[node], first[node] + 1);
      }
    }
    if (hit < 0) return null;
    return { triangle: hit, t: nearest, point: [o.x + nearest * d.x, o.y + nearest * d.y, o.z + nearest * d.z] };
  }

  /**
   * Calls visit(vertex, distance) for every vertex within `radius` of
   * `point` on `triangle`, the distance measured along the edges (Dijkstra
   * from the triangle's corners), nearest first.
   */
  within(triangle, point, radius, visit) {
    const { positions, offsets, neighbours, distance, stamp, heap } = this;
    this.round += 1;
    const round = this.round;
    heap.size = 0;
    for (let k = 0; k < 3; k++) {
      const v = this.indices[3 * triangle + k];
      const d = Math.hypot(positions[3 * v] - point[0], positions[3 * v + 1] - point[1], positions[3 * v + 2] - point[2]);
      if (stamp[v] === round && distance[v] <= d) continue;
      stamp[v] = round;
      distance[v] = d;
      heap.push(d, v);
    }
    while (heap.size) {
      heap.pop();
      const [d, v] = [heap.key, heap.value];
      if (d > distance[v] || d > radius) continue;
      visit(v, d);
      distance[v] = -1; // settled
      for (let i = offsets[v]; i < offsets[v + 1]; i++) {
        const w = neighbours[i];
        if (stamp[w] === round && distance[w] < 0) continue;
        const e = d + Math.hypot(positions[3 * w] - positions[3 * v], positions[3 * w + 1] - positions[3 * v + 1], positions[3 * w + 2] - positions[3 * v + 2]);
        if (e > radius || (stamp[w] === round && distance[w] <= e)) continue;
        stamp[w] = round;
        distance[w] = e;
        heap.push(e, w);
      }
    }
  }
}

/** Möller–Trumbore: the ray parameter where it meets triangle t, or Infinity. */
function intersect(p, indices, t, o, d) {
  const [a, b, c] = [3 * indices[3 * t], 3 * indices[3 * t + 1], 3 * indices[3 * t + 2]];
  const e1x = p[b] - p[a],
    e1y = p[b + 1] - p[a + 1],
    e1z = p[b + 2] - p[a + 2];
  const e2x = p[c] - p[a],
    e2y = p[c + 1] - p[a + 1],
    e2z = p[c + 2] - p[a + 2];
  const px = d.y * e2z - d.z * e2y,
    py = d.z * e2x - d.x * e2z,
    pz = d.x * e2y - d.y * e2x;
  const det = e1x * px + e1y * py + e1z * pz;
  if (Math.abs(det) < 1e-20) return Infinity;
  const inv = 1 / det;
  const sx = o.x - p[a],
    sy = o.y - p[a + 1],
    sz = o.z - p[a + 2];
  const u = (sx * px + sy * py + sz * pz) * inv;
  if (u < 0 || u > 1) return Infinity;
  const qx = sy * e1z - sz * e1y,
    qy = sz * e1x - sx * e1z,
    qz = sx * e1y - sy * e1x;
  const v = (d.x * qx + d.y * qy + d.z * qz) * inv;
  if (v < 0 || u + v > 1) return Infinity;
  const hit = (e2x * qx + e2y * qy + e2z * qz) * inv;
  return hit > 0 ? hit : Infinity;
}
