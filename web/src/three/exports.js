// What the element hands out besides SVG: the `lines` event's summary, PNG
// renderings at a chosen size, and GLB with the surface and the lines.
import { BufferAttribute, BufferGeometry, Group, LineBasicMaterial, LineSegments, Mesh } from 'three';
import { RIDGE, VALLEY, segmentPositions } from './line-layer.js';
import { renderInto, sharedRenderer } from './renderer.js';

/** {counts, lengths, stats} of a result: per type, the number and total length of the kept lines. */
export function linesSummary(lines, kept, stats) {
  const counts = { ridges: 0, valleys: 0 };
  const lengths = { ridges: 0, valleys: 0 };
  for (const l of kept) {
    const key = lines.types[l] === RIDGE ? 'ridges' : lines.types[l] === VALLEY ? 'valleys' : null;
    if (!key) continue;
    counts[key] += 1;
    lengths[key] += lines.lengths[l];
  }
  return { counts, lengths, stats };
}

/**
 * PNG Blob of the view at `width`×`height` pixels (default: the element's
 * CSS size × devicePixelRatio). Lines keep their width relative to the
 * element, so a larger image looks like a sharper screenshot.
 */
export async function renderPng(view, { cssWidth, cssHeight, width, height }) {
  const ratio = Math.min(globalThis.devicePixelRatio || 1, 2);
  width = Math.round(width ?? (height ? (height * cssWidth) / cssHeight : cssWidth * ratio));
  height = Math.round(height ?? (width * cssHeight) / cssWidth);
  const limit = Math.min(8192, sharedRenderer().capabilities.maxTextureSize);
  if (!(width >= 1 && height >= 1 && width <= limit && height <= limit))
    throw new RangeError(`crestline-viewer: a PNG must be between 1 and ${limit} pixels wide and high.`);
  const canvas = document.createElement('canvas');
  canvas.width = width;
  canvas.height = height;
  const { camera } = view;
  const aspect = camera.aspect;
  camera.aspect = width / height;
  camera.updateProjectionMatrix();
  const scale = width / cssWidth;
  view.lines.setResolution(width / scale, height / scale);
  try {
    renderInto(view, canvas.getContext('2d'), width, height);
  } finally {
    camera.aspect = aspect;
    camera.updateProjectionMatrix();
    view.lines.setResolution(cssWidth, cssHeight);
  }
  return new Promise((resolve, reject) => canvas.toBlob((blob) => (blob ? resolve(blob) : reject(new Error('crestline-viewer: the PNG could not be encoded.'))), 'image/png'));
}

/**
 * GLB (ArrayBuffer) of the surface the lines lie on and the lines shown, as
 * line primitives named "ridges" and "valleys", in the model's coordinates.
 * The exporter is loaded on first use.
 */
export async function exportGlb(view, lines, style) {
  const { GLTFExporter } = await import('three/examples/jsm/exporters/GLTFExporter.js');
  const root = new Group();
  root.name = 'crestline';
  root.position.fromArray(view.origin);
  const surface = new Mesh(view.surface.mesh.geometry, view.surface.material);
  surface.name = 'surface';
  root.add(surface);
  const made = [];
  for (const [type, name, shown, color] of [[RIDGE, 'ridges', style.ridges, style.ridgeColor], [VALLEY, 'valleys', style.valleys, style.valleyColor]]) {
    const positions = segmentPositions(lines, type, view.origin);
    if (!shown || !positions.length) continue;
    const geometry = new BufferGeometry().setAttribute('position', new BufferAttribute(positions, 3));
    const material = new LineBasicMaterial({ color });
    const object = new LineSegments(geometry, material);
    object.name = name;
    root.add(object);
    made.push(geometry, material);
  }
  try {
    return await new GLTFExporter().parseAsync(root, { binary: true });
  } finally {
    for (const resource of made) resource.dispose();
  }
}
