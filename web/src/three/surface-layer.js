// The shaded surface. Polygon offset pushes it back in depth so the feature
// lines lying exactly on it win the depth test without showing through it.
// Both sides are drawn (an open scan shows its inside through its holes),
// but the back faces of a closed surface seen from outside are hidden behind
// its front faces: then they are culled, a third of the surface's cost in
// WebGL on the CPU (SwiftShader), with the same pixels.
import { BufferAttribute, BufferGeometry, DoubleSide, FrontSide, Mesh, MeshStandardMaterial, Sphere, Vector3 } from 'three';
import { divergingColor, divergingColors, robustScale } from './colormap.js';

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
    /** Whether the surface bounds solids it faces out of (the worker's is_closed_outward): seen from outside, its back faces are hidden. */
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
   * worker computed all of it (`closed` is C++'s is_closed_outward, from the
   * repair's adjacency): nothing here walks the mesh. A view without `closed`
   * counts as open (both sides drawn, the safe look).
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
    this.closed = closed === true;
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
