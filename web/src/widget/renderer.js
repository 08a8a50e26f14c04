// One WebGL context for every <crestline-viewer> on the page: each view is
// rendered into the lower-left corner of a shared off-screen canvas and
// copied into the element's own 2D canvas in the same task. A page with any
// number of viewers thus never meets the browser's limit on live WebGL
// contexts (16 in Chromium), and viewers off screen cost nothing.
import { WebGLRenderer } from 'three';

let renderer = null;
const dirty = new Set();
let frame = 0;
let lost = false;

function shared() {
  if (renderer) return renderer;
  const canvas = document.createElement('canvas');
  renderer = new WebGLRenderer({ canvas, antialias: true, alpha: true, premultipliedAlpha: true });
  renderer.setPixelRatio(1);
  canvas.addEventListener('webglcontextlost', (event) => {
    event.preventDefault(); // the browser may restore it
    lost = true;
  });
  canvas.addEventListener('webglcontextrestored', () => {
    lost = false;
    for (const view of views) dirty.add(view);
    schedule();
  });
  return renderer;
}

const views = new Set();

/** Views ask for a frame; all dirty views are drawn in one animation frame. */
export function requestDraw(view) {
  views.add(view);
  dirty.add(view);
  schedule();
}

export function forget(view) {
  views.delete(view);
  dirty.delete(view);
}

function schedule() {
  if (!frame && dirty.size) frame = requestAnimationFrame(drawDirty);
}

function drawDirty(time) {
  frame = 0;
  if (lost) return;
  const now = [...dirty];
  dirty.clear();
  for (const view of now) if (view.visible) drawView(view, time);
  schedule(); // views that asked again while drawing (auto-rotate)
}

/** Renders `view` (see view.js) at `width`×`height` device pixels into a 2D context. */
export function renderInto(view, context, width, height) {
  const gl = shared();
  const canvas = gl.domElement;
  if (canvas.width < width || canvas.height < height) gl.setSize(Math.max(canvas.width, width), Math.max(canvas.height, height), false);
  gl.setViewport(0, 0, width, height);
  gl.setScissor(0, 0, width, height);
  gl.setScissorTest(true);
  gl.setClearColor(0x000000, 0);
  gl.render(view.scene, view.camera);
  gl.setScissorTest(false);
  context.clearRect(0, 0, width, height);
  // The viewport is at the bottom of the GL canvas, i.e. its last rows.
  context.drawImage(canvas, 0, canvas.height - height, width, height, 0, 0, width, height);
}

function drawView(view, time) {
  view.beforeDraw?.(time);
  const { canvas } = view;
  renderInto(view, canvas.getContext('2d'), canvas.width, canvas.height);
  view.afterDraw?.();
}

/** The shared renderer (for depth read-back by the SVG export). */
export function sharedRenderer() {
  return shared();
}

/** True when the browser has taken the context away (and not yet given it back). */
export function contextLost() {
  return lost;
}
