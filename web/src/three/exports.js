// What the page and the element hand out from a view: the `lines` event's
// summary, PNG renderings at a chosen size, and the camera and style of the
// view for the core's SVG writer (the worker draws it: client exportFile('svg')).
import { Matrix4 } from 'three';
import { RIDGE, VALLEY, concaveShade } from './line-layer.js';
import { renderInto, sharedRenderer } from './renderer.js';

const translation = new Matrix4();

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
  return new Promise((resolve, reject) =>
    canvas.toBlob((blob) => (blob ? resolve(blob) : reject(new Error('crestline-viewer: the PNG could not be encoded.'))), 'image/png'),
  );
}

/**
 * Session.linesSvg's keys for what `view` shows at `width`×`height` CSS
 * pixels: its camera as a matrix from model coordinates to clip space (the
 * surface and lines are drawn centred on `view.origin`) and the display
 * `style` {ridges, valleys, creases (shown), ridgeColor, valleyColor,
 * creaseColor (convex; concave in its darker shade), lineWidth (CSS px),
 * background (CSS colour or 'transparent'), silhouette (colour, or null for
 * none)}. `view` is a WidgetView or the app's Viewer.
 * @returns {import('../worker/protocol.js').ExportView}
 */
export function svgView(view, style, width, height) {
  const { camera } = view;
  camera.updateMatrixWorld();
  view.surface.mesh.updateMatrixWorld();
  const [x, y, z] = view.origin;
  const matrix = new Matrix4()
    .multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse)
    .multiply(view.surface.mesh.matrixWorld)
    .multiply(translation.makeTranslation(-x, -y, -z));
  const out = {
    camera: { matrix: Array.from(matrix.elements), width, height },
    ridges: Boolean(style.ridges),
    valleys: Boolean(style.valleys),
    creases: Boolean(style.creases),
    ridgeColor: String(style.ridgeColor),
    valleyColor: String(style.valleyColor),
    creaseColor: String(style.creaseColor),
    concaveColor: `#${concaveShade(style.creaseColor).getHexString()}`,
    strokeWidth: style.lineWidth,
    silhouette: Boolean(style.silhouette),
    background: style.background && style.background !== 'transparent' ? String(style.background) : '',
  };
  if (style.silhouette) out.silhouetteColor = String(style.silhouette);
  return out;
}
