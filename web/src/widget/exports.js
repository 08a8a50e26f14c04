// What the element hands out besides SVG: the `lines` event's summary and
// PNG renderings at a chosen size.
import { RIDGE, VALLEY } from '../viewer/line-layer.js';
import { renderInto, sharedRenderer } from './renderer.js';

/** {counts, lengths, stats} of a result: per type, the number and total length of the lines. */
export function linesSummary(lines, stats) {
  const counts = { ridges: 0, valleys: 0 };
  const lengths = { ridges: 0, valleys: 0 };
  for (let l = 0; l < lines.types.length; l++) {
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
