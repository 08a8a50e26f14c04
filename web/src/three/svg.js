// toSVG(): the lines as drawn in the current view, with the parts hidden by
// the surface removed. Visibility comes from the surface's depth buffer,
// rendered from the viewer's camera by the shared renderer and read back:
// a line point is visible when it is not behind the nearest surface at its
// pixel (with a tolerance, since the lines lie on that surface).
import { Color, MeshDepthMaterial, NoBlending, RGBADepthPacking, Vector3, WebGLRenderTarget } from 'three';
import { CONCAVE, CONVEX, RIDGE, VALLEY, concaveShade } from './line-layer.js';
import { sharedRenderer } from './renderer.js';

const point = new Vector3();
const EMPTY = 0.999999; // the cleared depth: no surface at this pixel
const escape = (value) => String(value).replace(/[&<>"]/g, (c) => `&#${c.charCodeAt(0)};`);
// three.js packDepthToRGBA (ShaderChunk/packing): depth = Σ byte/255 · factor.
const UNPACK = [255 / 256, 255 / 256 / 256, 255 / 256 / 65536, 1 / 16777216];

/** Window depths (0 near … 1 far / empty) of the surface, row 0 at the bottom. */
function surfaceDepth(view, width, height, renderer) {
  const target = new WebGLRenderTarget(width, height);
  const material = new MeshDepthMaterial({ depthPacking: RGBADepthPacking, blending: NoBlending });
  const { scene, camera } = view;
  const saved = { background: scene.background, override: scene.overrideMaterial, lines: view.lines.group.visible, creases: view.creases?.group.visible, clear: renderer.getClearColor(new Color()), alpha: renderer.getClearAlpha() };
  Object.assign(scene, { background: null, overrideMaterial: material });
  view.lines.group.visible = false;
  if (view.creases) view.creases.group.visible = false;
  renderer.setRenderTarget(target);
  renderer.setClearColor(0xffffff, 1);
  renderer.clear();
  renderer.render(scene, camera);
  const bytes = new Uint8Array(width * height * 4);
  renderer.readRenderTargetPixels(target, 0, 0, width, height, bytes);
  renderer.setRenderTarget(null);
  renderer.setClearColor(saved.clear, saved.alpha);
  Object.assign(scene, { background: saved.background, overrideMaterial: saved.override });
  view.lines.group.visible = saved.lines;
  if (view.creases) view.creases.group.visible = saved.creases;
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

/** Screen projection and the visibility test of one view. */
function visibilityTest(view, depth, width, height, tolerance) {
  const { camera } = view;
  const { near, far } = camera;
  /** Local (centred) coordinates → [x, y (CSS px, y down), NDC z]. */
  const project = (x, y, z) => {
    point.set(x, y, z).project(camera);
    return [(point.x + 1) * 0.5 * width, (1 - point.y) * 0.5 * height, point.z];
  };
  const visible = ([x, y, z]) => {
    if (z < -1 || z > 1 || x < 0 || y < 0 || x >= width || y >= height) return false;
    const px = Math.floor(x);
    const py = height - 1 - Math.floor(y);
    // The 3×3 neighbourhood, like a line a few pixels wide: empty pixels
    // (silhouettes) let it through; its depth range stands in for the
    // polygon offset the on-screen surface gets on steep slopes.
    let nearest = Infinity;
    let farthest = 0;
    for (let dy = -1; dy <= 1; dy++) {
      for (let dx = -1; dx <= 1; dx++) {
        const sx = Math.min(width - 1, Math.max(0, px + dx));
        const sy = Math.min(height - 1, Math.max(0, py + dy));
        const d = depth[sy * width + sx];
        if (d >= EMPTY) return true;
        const distance = viewDistance(d, near, far);
        nearest = Math.min(nearest, distance);
        farthest = Math.max(farthest, distance);
      }
    }
    return viewDistance((z + 1) / 2, near, far) <= farthest + (farthest - nearest) + tolerance;
  };
  return { project, visible };
}

/**
 * SVG path data of the visible runs of `chains` (arrays of projected
 * points). Each segment is sampled about every pixel so that partly hidden
 * ones are cut where they disappear.
 */
function visiblePath(chains, visible) {
  const parts = [];
  let run = [];
  const flush = () => {
    if (run.length > 1) parts.push(`M${run.join('L')}`);
    run = [];
  };
  for (const chain of chains) {
    for (let k = 1; k < chain.length; k++) {
      const [from, to] = [chain[k - 1], chain[k]];
      const steps = Math.max(1, Math.ceil(Math.hypot(to[0] - from[0], to[1] - from[1])));
      for (let s = k === 1 ? 0 : 1; s <= steps; s++) {
        const p = from.map((v, c) => v + ((to[c] - v) * s) / steps);
        if (visible(p)) run.push(`${p[0].toFixed(2)} ${p[1].toFixed(2)}`);
        else flush();
      }
    }
    flush();
  }
  return parts.join('');
}

/** The worker's lines of one type as chains of projected points (closed lines repeat their start). */
function lineChains(lines, type, origin, project) {
  const { points, offsets, types, closed } = lines;
  const chains = [];
  for (let l = 0; l < types.length; l++) {
    if (types[l] !== type) continue;
    const chain = [];
    for (let i = offsets[l]; i < offsets[l + 1]; i++) chain.push(project(points[3 * i] - origin[0], points[3 * i + 1] - origin[1], points[3 * i + 2] - origin[2]));
    if (closed[l]) chain.push(chain[0]);
    chains.push(chain);
  }
  return chains;
}

/**
 * Outline edges of the surface seen from `eye` (local coordinates): edges
 * between a triangle facing the eye and one facing away, and boundary
 * edges, chained where they meet.
 */
function silhouetteChains(geometry, eye, project) {
  const p = geometry.getAttribute('position').array;
  const index = geometry.getIndex().array;
  const facing = new Int8Array(index.length / 3);
  const a = new Vector3(), b = new Vector3(), c = new Vector3();
  for (let t = 0; t < facing.length; t++) {
    a.fromArray(p, 3 * index[3 * t]);
    b.fromArray(p, 3 * index[3 * t + 1]).sub(a);
    c.fromArray(p, 3 * index[3 * t + 2]).sub(a);
    facing[t] = b.cross(c).dot(a.sub(eye).negate()) > 0 ? 1 : -1;
  }
  // Edge (min, max) → facing of its first triangle, or 0 once it is an inner edge.
  const edges = new Map();
  const vertexCount = p.length / 3;
  for (let t = 0; t < facing.length; t++) {
    for (let k = 0; k < 3; k++) {
      const [u, v] = [index[3 * t + k], index[3 * t + ((k + 1) % 3)]];
      const key = Math.min(u, v) * vertexCount + Math.max(u, v);
      const seen = edges.get(key);
      edges.set(key, seen === undefined ? facing[t] : seen !== facing[t] ? 2 : 0);
    }
  }
  const outline = new Map(); // vertex → outline neighbours
  for (const [key, state] of edges) {
    if (state === 0) continue; // both triangles face the same way
    const [u, v] = [Math.floor(key / vertexCount), key % vertexCount];
    for (const [x, y] of [[u, v], [v, u]]) outline.set(x, [...(outline.get(x) ?? []), y]);
  }
  const used = new Set();
  const chains = [];
  const take = (u, v) => used.add(Math.min(u, v) * vertexCount + Math.max(u, v));
  const free = (u, v) => !used.has(Math.min(u, v) * vertexCount + Math.max(u, v));
  for (const [start, neighbours] of outline) {
    for (const next of neighbours) {
      if (!free(start, next)) continue;
      take(start, next);
      const chain = [start, next];
      for (let at = next, step; (step = outline.get(at).find((w) => free(at, w))) !== undefined; at = step) {
        take(at, step);
        chain.push(step);
      }
      chains.push(chain.map((v) => project(p[3 * v], p[3 * v + 1], p[3 * v + 2])));
    }
  }
  return chains;
}

/**
 * The SVG document of what the viewer shows. `style`: {ridges, valleys, creases (shown),
 * ridgeColor, valleyColor, creaseColor (convex; concave in its darker shade), lineWidth (CSS px), background (CSS colour or
 * 'transparent'), silhouette (colour, or null for none)}; `width`×`height`
 * in CSS pixels. `view` is a WidgetView or anything with its scene, camera,
 * surface and lines layers and origin (the app's Viewer) — its creases are
 * `view.creaseLines` (creasesAsLines, set by setCreases) — and `renderer` any
 * WebGLRenderer (by default the widgets' shared one).
 */
export function viewToSvg(view, lines, style, width, height, renderer = sharedRenderer()) {
  const depth = surfaceDepth(view, width, height, renderer);
  const radius = view.radius ?? view.surface.mesh.geometry.boundingSphere?.radius ?? 1;
  // Faired lines may stray from the surface by the fairing bound: allow a
  // hundredth of the model's radius.
  const { project, visible } = visibilityTest(view, depth, width, height, radius * 0.01);
  const paths = [];
  const add = (name, color, widthFactor, chains) => {
    const d = visiblePath(chains, visible);
    const stroke = widthFactor === 1 ? '' : ` stroke-width="${style.lineWidth * widthFactor}"`;
    if (d) paths.push(`  <path id="${name}" stroke="${escape(color)}"${stroke} d="${d}"/>`);
  };
  if (style.silhouette) add('silhouette', style.silhouette, 0.6, silhouetteChains(view.surface.mesh.geometry, view.camera.position, project));
  if (style.ridges) add('ridges', style.ridgeColor, 1, lineChains(lines, RIDGE, view.origin, project));
  if (style.valleys) add('valleys', style.valleyColor, 1, lineChains(lines, VALLEY, view.origin, project));
  if (style.creases && view.creaseLines) {
    add('creases-convex', style.creaseColor, 1, lineChains(view.creaseLines, CONVEX, view.origin, project));
    add('creases-concave', `#${concaveShade(style.creaseColor).getHexString()}`, 1, lineChains(view.creaseLines, CONCAVE, view.origin, project));
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
