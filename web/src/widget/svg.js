// toSVG(): the lines as drawn in the current view, with the parts hidden by
// the surface removed. Visibility comes from the surface's depth buffer,
// rendered from the viewer's camera by the shared renderer and read back:
// a line point is visible when it is not behind the nearest surface at its
// pixel (with a tolerance, since the lines lie on that surface).
import { MeshDepthMaterial, NoBlending, RGBADepthPacking, Vector3, WebGLRenderTarget } from 'three';
import { RIDGE, VALLEY } from '../viewer/line-layer.js';
import { sharedRenderer } from './renderer.js';

const point = new Vector3();
const escape = (value) => String(value).replace(/[&<>"]/g, (c) => `&#${c.charCodeAt(0)};`);
// three.js packDepthToRGBA (ShaderChunk/packing): depth = Σ byte/255 · factor.
const UNPACK = [255 / 256, 255 / 256 / 256, 255 / 256 / 65536, 1 / 16777216];

/** Window depths (0 near … 1 far / empty) of the surface, row 0 at the bottom. */
function surfaceDepth(view, width, height) {
  const renderer = sharedRenderer();
  const target = new WebGLRenderTarget(width, height);
  const material = new MeshDepthMaterial({ depthPacking: RGBADepthPacking, blending: NoBlending });
  const { scene, camera } = view;
  const saved = { background: scene.background, override: scene.overrideMaterial, lines: view.lines.group.visible };
  Object.assign(scene, { background: null, overrideMaterial: material });
  view.lines.group.visible = false;
  renderer.setRenderTarget(target);
  renderer.setClearColor(0xffffff, 1);
  renderer.clear();
  renderer.render(scene, camera);
  const bytes = new Uint8Array(width * height * 4);
  renderer.readRenderTargetPixels(target, 0, 0, width, height, bytes);
  renderer.setRenderTarget(null);
  Object.assign(scene, { background: saved.background, overrideMaterial: saved.override });
  view.lines.group.visible = saved.lines;
  target.dispose();
  material.dispose();
  const depth = new Float32Array(width * height);
  for (let i = 0; i < depth.length; i++) {
    const b = 4 * i;
    depth[i] = (bytes[b] * UNPACK[0] + bytes[b + 1] * UNPACK[1] + bytes[b + 2] * UNPACK[2] + bytes[b + 3] * UNPACK[3]) / 255;
  }
  return depth;
}

/** Perspective window depth → distance in front of the camera. */
function viewDistance(depth, near, far) {
  const ndc = 2 * depth - 1;
  return (2 * near * far) / (far + near - ndc * (far - near));
}

/**
 * Visible runs of the lines of `type` in the view, as SVG path data.
 * A line is sampled about every pixel so that partly hidden segments are cut
 * where they disappear.
 */
function visiblePath(view, lines, type, depth, width, height, tolerance) {
  const { points, offsets, types, closed } = lines;
  const { camera, origin } = view;
  const { near, far } = camera;
  const parts = [];
  let run = [];
  const flush = () => {
    if (run.length > 1) parts.push(`M${run.join('L')}`);
    run = [];
  };
  const project = (i) => {
    point.set(points[3 * i] - origin[0], points[3 * i + 1] - origin[1], points[3 * i + 2] - origin[2]).project(camera);
    return [(point.x + 1) * 0.5 * width, (1 - point.y) * 0.5 * height, point.z];
  };
  const visible = ([x, y, z]) => {
    if (z < -1 || z > 1 || x < 0 || y < 0 || x >= width || y >= height) return false;
    const px = Math.floor(x);
    const py = height - 1 - Math.floor(y);
    // The farthest surface in the 3×3 neighbourhood: lines on silhouettes stay.
    let surface = 0;
    for (let dy = -1; dy <= 1; dy++) {
      for (let dx = -1; dx <= 1; dx++) {
        const sx = Math.min(width - 1, Math.max(0, px + dx));
        const sy = Math.min(height - 1, Math.max(0, py + dy));
        surface = Math.max(surface, depth[sy * width + sx]);
      }
    }
    if (surface >= 0.999999) return true;
    return viewDistance((z + 1) / 2, near, far) <= viewDistance(surface, near, far) + tolerance;
  };
  for (let l = 0; l < types.length; l++) {
    if (types[l] !== type) continue;
    const first = offsets[l];
    const last = offsets[l + 1] - 1;
    const ids = [];
    for (let i = first; i <= last; i++) ids.push(i);
    if (closed[l]) ids.push(first);
    let previous = project(ids[0]);
    for (let k = 1; k < ids.length; k++) {
      const next = project(ids[k]);
      const steps = Math.max(1, Math.ceil(Math.hypot(next[0] - previous[0], next[1] - previous[1])));
      for (let s = k === 1 ? 0 : 1; s <= steps; s++) {
        const t = s / steps;
        const p = previous.map((v, c) => v + (next[c] - v) * t);
        if (visible(p)) run.push(`${p[0].toFixed(2)} ${p[1].toFixed(2)}`);
        else flush();
      }
      previous = next;
    }
    flush();
  }
  return parts.join('');
}

/**
 * The SVG document of what the viewer shows. `style`: {ridges, valleys (shown),
 * ridgeColor, valleyColor, lineWidth (CSS px), background (CSS colour or
 * 'transparent')}; `width`×`height` in CSS pixels.
 */
export function viewToSvg(view, lines, style, width, height) {
  const depth = surfaceDepth(view, width, height);
  // Faired lines may stray from the surface by the fairing bound; allow a few
  // hundredths of the model's radius.
  const tolerance = view.radius * 0.02;
  const paths = [];
  for (const [type, shown, color] of [[RIDGE, style.ridges, style.ridgeColor], [VALLEY, style.valleys, style.valleyColor]]) {
    if (!shown) continue;
    const d = visiblePath(view, lines, type, depth, width, height, tolerance);
    const name = type === RIDGE ? 'ridges' : 'valleys';
    if (d) paths.push(`  <path id="${name}" stroke="${escape(color)}" d="${d}"/>`);
  }
  const background = style.background && style.background !== 'transparent'
    ? `  <rect width="100%" height="100%" fill="${escape(style.background)}"/>\n` : '';
  return `<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="${width}" height="${height}" viewBox="0 0 ${width} ${height}">
${background}  <g fill="none" stroke-width="${style.lineWidth}" stroke-linecap="round" stroke-linejoin="round">
${paths.join('\n')}
  </g>
</svg>
`;
}
