// The panel's Export folder: files of what the app shows, downloaded as
// <mesh>-lines.<ext>: PNG rendered from the app's Viewer (../three, shared
// with the element), the others by the core's writers in the worker (OBJ,
// JSON, GLB, and SVG of the Viewer's camera).
import { renderPng, svgView } from '../three/exports.js';

/** "feline.obj" → "feline", "bunny (built-in sample)" → "bunny". */
export function baseName(name) {
  const base = String(name ?? '')
    .replace(/\s*\(.*\)\s*$/, '')
    .replace(/\.[a-z0-9]+$/i, '')
    .trim();
  return base.replace(/[^\w.-]+/g, '_') || 'mesh';
}

function download(blob, fileName) {
  const url = URL.createObjectURL(blob);
  const link = Object.assign(document.createElement('a'), { href: url, download: fileName });
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

/**
 * The exports of the app. `viewer`: the app's Viewer; `current()` returns
 * {name, lines} of the result shown (or throws why there is none); `client`:
 * what makes the core writers' files (exportText, exportFile);
 * `params`: the panel's values (display style, png scale, svg silhouette).
 */
export function createExports({ viewer, current, client, params }) {
  const style = () => ({
    ridges: params.showRidges,
    valleys: params.showValleys,
    creases: params.showCreases,
    ridgeColor: params.ridgeColor,
    valleyColor: params.valleyColor,
    creaseColor: params.creaseColor,
    lineWidth: params.lineWidth,
    background: `#${viewer.scene.background.getHexString()}`,
  });
  const cssSize = () => {
    const { width, height } = viewer.renderer.domElement.getBoundingClientRect();
    return { width: Math.max(1, Math.round(width)), height: Math.max(1, Math.round(height)) };
  };
  const shown = () => {
    const result = current();
    if (!result?.lines) throw new Error('Nothing to export yet: wait for the lines.');
    return result;
  };
  const makers = {
    async svg() {
      const { width, height } = cssSize();
      const svgStyle = { ...style(), silhouette: params.exportSilhouette ? '#3a3a3a' : null };
      return new Blob([await client.exportFile('svg', svgView(viewer, svgStyle, width, height))], { type: 'image/svg+xml' });
    },
    async png() {
      const { width, height } = cssSize();
      const scale = Number(params.pngScale) || 1;
      return renderPng(viewer, { cssWidth: width, cssHeight: height, width: width * scale, height: height * scale });
    },
    async obj() {
      return new Blob([await client.exportText('obj')], { type: 'text/plain' });
    },
    async json() {
      return new Blob([await client.exportText('json')], { type: 'application/json' });
    },
    async glb() {
      const { ridges, valleys, creases } = style();
      return new Blob([await client.exportFile('glb', { ridges, valleys, creases })], { type: 'model/gltf-binary' });
    },
  };
  return {
    /** Makes and downloads one export ('svg', 'png', 'obj', 'json', 'glb'); returns {blob, fileName}. */
    async save(format) {
      const result = shown();
      const blob = await makers[format](result);
      const fileName = `${baseName(result.name)}-lines.${format}`;
      download(blob, fileName);
      return { blob, fileName };
    },
  };
}
