// The shaded surface. Polygon offset pushes it back in depth so the feature
// lines lying exactly on it win the depth test without showing through it.
// Both sides are drawn (an open scan shows its inside through its holes),
// but the back faces of a closed surface seen from outside are hidden behind
// its front faces: then they are culled, a third of the surface's cost in
// WebGL on the CPU (SwiftShader), with the same pixels.
import { BufferAttribute, BufferGeometry, DoubleSide, FrontSide, Mesh, MeshStandardMaterial, Sphere, Vector3 } from 'three';
import { divergingColor, divergingColors, robustScale } from './colormap.js';

/**
 * Whether `indices` (triangles of `positions`, x,y,z each) bound solids from
 * which they face outwards: every directed edge a→b is matched by one b→a
 * (closed and consistently oriented), and the signed volume is positive.
 * The repair turns each closed component outwards (core/src/mesh/repair.cpp);
 * the volume is a check on that for the whole, not for each part.
 * The edges are matched through the signed area of the triangles in two
 * pseudo-random integer maps of the vertices to the plane, modulo 2^32: each
 * matched pair of edges cancels exactly, so a closed oriented surface sums
 * to 0, and a boundary (the sum of its edges' terms) does so by chance only.
 */
export function facesOutward(positions, indices) {
  const n = positions.length / 3;
  // Two maps: u0, w0, u1, w1 of each vertex.
  const map = new Int32Array(4 * n);
  let state = 0x9e3779b9; // xorshift32
  for (let i = 0; i < map.length; i++) {
    state ^= state << 13;
    state ^= state >>> 17;
    state ^= state << 5;
    map[i] = state;
  }
  let area0 = 0,
    area1 = 0,
    volume = 0;
  for (let t = 0; t < indices.length; t += 3) {
    const a = 4 * indices[t],
      b = 4 * indices[t + 1],
      c = 4 * indices[t + 2];
    // Twice the signed area of (a, b, c) in each map: the sum of its edges' cross products.
    area0 = (area0 + Math.imul(map[a], map[b + 1]) - Math.imul(map[b], map[a + 1])) | 0;
    area0 = (area0 + Math.imul(map[b], map[c + 1]) - Math.imul(map[c], map[b + 1])) | 0;
    area0 = (area0 + Math.imul(map[c], map[a + 1]) - Math.imul(map[a], map[c + 1])) | 0;
    area1 = (area1 + Math.imul(map[a + 2], map[b + 3]) - Math.imul(map[b + 2], map[a + 3])) | 0;
    area1 = (area1 + Math.imul(map[b + 2], map[c + 3]) - Math.imul(map[c + 2], map[b + 3])) | 0;
    area1 = (area1 + Math.imul(map[c + 2], map[a + 3]) - Math.imul(map[a + 2], map[c + 3])) | 0;
    const pa = (3 * a) / 4,
      pb = (3 * b) / 4,
      pc = (3 * c) / 4;
    const bx = positions[pb],
      by = positions[pb + 1],
      bz = positions[pb + 2],
      cx = positions[pc],
      cy = positions[pc + 1],
      cz = positions[pc + 2];
    volume += positions[pa] * (by * cz - bz * cy) + positions[pa + 1] * (bz * cx - bx * cz) + positions[pa + 2] * (bx * cy - by * cx);
  }
  return indices.length > 0 && area0 === 0 && area1 === 0 && volume > 0;
}

const sphere = new Sphere();
const corner = new Vector3();
const eye = new Vector3();

export class SurfaceLayer {
  constructor() {
    this.material = new MeshStandardMaterial({
      color: 0xd8d2c4,
      roughness: 0.75,
      metalness: 0.0,
      side: DoubleSide,
      polygonOffset: true,
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    this.singularMaterial = new MeshStandardMaterial({
      color: 0xf5b700,
      roughness: 0.6,
      side: DoubleSide,
      polygonOffset: true,
      polygonOffsetFactor: 0.5,
      polygonOffsetUnits: 0.5,
    });
    this.mesh = new Mesh(new BufferGeometry(), this.material);
    this.singular = new Mesh(new BufferGeometry(), this.singularMaterial);
    this.mesh.add(this.singular);
    this.indices = new Uint32Array(0);
    /** Whether the surface bounds solids it faces out of (facesOutward): seen from outside, its back faces are hidden. */
    this.closed = false;
  }

  /**
   * Culls the back faces for a frame through `camera` if they are hidden:
   * the surface is closed and the camera, with its near plane, is outside
   * its bounding sphere (a closed surface's first face along any ray from
   * there faces the camera). Call before drawing, and before the surface
   * cache's key (a change of side is a change of material).
   */
  cullHiddenFaces(camera) {
    let side = DoubleSide;
    const bounds = this.mesh.geometry.boundingSphere;
    if (this.closed && bounds) {
      camera.updateMatrixWorld();
      sphere.copy(bounds).applyMatrix4(this.mesh.matrixWorld);
      // The near plane's farthest corner from the eye (its rectangle lies in a ball of that radius about the eye).
      let near = 0;
      for (const [x, y] of [
        [-1, -1],
        [1, -1],
        [-1, 1],
        [1, 1],
      ])
        near = Math.max(near, corner.set(x, y, -1).applyMatrix4(camera.projectionMatrixInverse).length());
      eye.setFromMatrixPosition(camera.matrixWorld);
      if (eye.distanceTo(sphere.center) > sphere.radius + near) side = FrontSide;
    }
    if (this.material.side !== side) {
      this.material.side = side;
      this.material.needsUpdate = true;
    }
  }

  /**
   * The surface's `view` (Session.surface(): float32 positions about its
   * origin, unit normals, the bounding sphere's radius about the origin,
   * whether it is closed and faces out) and its triangles (Uint32Array). The
   * worker computed all of it: nothing here walks the mesh (facesOutward
   * only for a view without `closed`).
   */
  setMesh({ positions, normals, radius, closed }, indices) {
    this.mesh.geometry.dispose();
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(positions, 3));
    geometry.setAttribute('normal', new BufferAttribute(normals, 3));
    geometry.setIndex(new BufferAttribute(indices, 1));
    geometry.boundingSphere = new Sphere(new Vector3(), radius);
    this.mesh.geometry = geometry;
    this.indices = indices;
    // The worker's (C++, from the repair's adjacency) where given: no walk of the mesh here.
    this.closed = typeof closed === 'boolean' ? closed : facesOutward(positions, indices);
    this.setColors(null);
    this.setSingular(null);
  }

  /**
   * Per-vertex scalar field shown as a colour map, or null for plain
   * shading; `scale`: the value the colours saturate at (by default the 95th
   * percentile of |values|), returned.
   */
  setColors(values, scale = values ? robustScale(values) : 0) {
    const geometry = this.mesh.geometry;
    // Plain already: nothing changes (a changed material would draw the surface again, surface-cache.js).
    if (!values && !this.material.vertexColors && !geometry.getAttribute('color')) return scale;
    if (values) {
      geometry.setAttribute('color', new BufferAttribute(divergingColors(values, undefined, scale), 3));
      this.material.color.set(0xffffff);
    } else {
      geometry.deleteAttribute('color');
      this.material.color.set(0xd8d2c4);
    }
    this.material.vertexColors = !!values;
    this.material.needsUpdate = true;
    return scale;
  }

  /**
   * New colours for `count` vertices only (vertices[0…count)), value(v)
   * each, saturated at `scale`: only their parts of the colour buffer are
   * sent to the GPU. The colour map must be on (setColors).
   */
  updateColors(vertices, count, value, scale) {
    const colors = this.mesh.geometry.getAttribute('color');
    if (!colors || !count) return;
    const sorted = vertices.subarray(0, count).sort();
    colors.clearUpdateRanges();
    // Runs of vertices, joined across gaps of up to 64 (one upload each, at most 32 of them).
    const gap = Math.max(64, Math.ceil((sorted[count - 1] - sorted[0]) / 32));
    let start = sorted[0],
      end = sorted[0];
    for (let i = 0; i < count; i++) {
      const v = sorted[i];
      divergingColor(value(v), scale, colors.array, 3 * v);
      if (v - end > gap) {
        colors.addUpdateRange(3 * start, 3 * (end - start + 1));
        start = v;
      }
      end = v;
    }
    colors.addUpdateRange(3 * start, 3 * (end - start + 1));
    colors.needsUpdate = true;
  }

  /** Highlights the triangles whose mask value is 0 (singular), or hides the overlay. */
  setSingular(regularMask) {
    if (!regularMask && !this.singular.visible && !this.singular.geometry.index) return;
    this.singular.geometry.dispose();
    const geometry = new BufferGeometry();
    if (regularMask) {
      const picked = [];
      for (let t = 0; t < regularMask.length; t++) {
        if (!regularMask[t]) picked.push(this.indices[3 * t], this.indices[3 * t + 1], this.indices[3 * t + 2]);
      }
      geometry.setAttribute('position', this.mesh.geometry.getAttribute('position'));
      geometry.setAttribute('normal', this.mesh.geometry.getAttribute('normal'));
      geometry.setIndex(new BufferAttribute(Uint32Array.from(picked), 1));
    }
    this.singular.geometry = geometry;
    this.singular.visible = !!regularMask;
  }

  dispose() {
    this.mesh.geometry.dispose();
    this.singular.geometry.dispose();
    this.material.dispose();
    this.singularMaterial.dispose();
  }
}
