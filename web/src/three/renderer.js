// One WebGL context for every <crestline-viewer> on the page: each view is
// rendered into the lower-left corner of a shared off-screen canvas and
// copied into the element's own 2D canvas in the same task. A page with any
// number of viewers thus never meets the browser's limit on live WebGL
// contexts (16 in Chromium), and viewers off screen cost nothing.
import { WebGLRenderer } from 'three';

let renderer = null;
const dirty = new Set();
let frame = 0;
let retry = 0;

/** The shared renderer, created on first use and again after a context loss. */
function shared() {
  if (renderer) return renderer;
  const canvas = document.createElement('canvas');
  renderer = new WebGLRenderer({ canvas, antialias: true, alpha: true, premultipliedAlpha: true });
  renderer.setPixelRatio(1);
  canvas.addEventListener('webglcontextlost', (event) => {
    event.preventDefault();
    // A canvas outside the document does not reliably get its context back
    // (Chromium never restores it): start over with a new one. Every view
    // uploads its buffers again on its next draw.
    renderer.dispose();
    renderer = null;
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
  try {
    shared();
  } catch {
    // No context now (the GPU is resetting, or too many pages use it): try again soon.
    clearTimeout(retry);
    retry = setTimeout(schedule, 1000);
    return;
  }
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
  view.surface?.cullHiddenFaces(view.camera);
  for (const layer of [view.lines, view.creases]) layer?.fitDetail(view.camera, height); // the image's pixels (an export's)
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
