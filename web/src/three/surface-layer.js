// The shaded surface. Polygon offset pushes it back in depth so the feature
// lines lying exactly on it win the depth test without showing through it.
import { BufferAttribute, BufferGeometry, DoubleSide, Mesh, MeshStandardMaterial } from 'three';
import { divergingColors, robustScale } from './colormap.js';

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
  }

  /** positions: Float32Array (already centred), indices: Uint32Array. */
  setMesh(positions, indices) {
    this.mesh.geometry.dispose();
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(positions, 3));
    geometry.setIndex(new BufferAttribute(indices, 1));
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    this.mesh.geometry = geometry;
    this.indices = indices;
    this.setColors(null);
    this.setSingular(null);
  }

  /** Per-vertex scalar field shown as a colour map, or null for plain shading; returns the value the colours saturate at. */
  setColors(values) {
    const geometry = this.mesh.geometry;
    const scale = values ? robustScale(values) : 0;
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

  /** Highlights the triangles whose mask value is 0 (singular), or hides the overlay. */
  setSingular(regularMask) {
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
