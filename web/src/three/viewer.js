// The 3D view: renderer, camera, orbit controls, lights, the surface and the
// line layers. Renders on demand (after a change), not in a loop.
import { Color, DirectionalLight, HemisphereLight, PerspectiveCamera, Scene, Sphere, Vector3, WebGLRenderer } from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { fitDistance, presetDirection, setUpAxis, uncoveredRect } from './fit.js';
import { LineLayer, concaveShade, creasesAsLines } from './line-layer.js';
import { SurfaceLayer } from './surface-layer.js';
import { SurfaceCache } from './surface-cache.js';
import { LINE_COLORS } from './colors.js';

const BACKGROUND = { light: 0xf4f4f2, dark: 0x1d1f24 };
/**
 * Surfaces from this many triangles on are drawn through a SurfaceCache: a
 * frame that changes only the lines does not draw them again. Smaller ones
 * cost little to draw and not the cache's GPU memory (about as much as
 * the antialiased canvas's own: 40 bytes a pixel).
 */
export const CACHE_MIN_TRIANGLES = 200_000;

export class Viewer {
  /** @param {HTMLElement} container  @param {{onContextLost, onContextRestored}} handlers */
  constructor(container, { onContextLost, onContextRestored } = {}) {
    this.container = container;
    this.renderer = new WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    container.appendChild(this.renderer.domElement);
    this.scene = new Scene();
    this.camera = new PerspectiveCamera(35, 1, 0.01, 100);
    this.scene.add(this.camera);
    this.scene.add(new HemisphereLight(0xffffff, 0x606070, 1.6));
    const key = new DirectionalLight(0xffffff, 1.8);
    key.position.set(1, 1.5, 2);
    this.camera.add(key); // the light follows the view
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());
    this.surface = new SurfaceLayer();
    this.lines = new LineLayer();
    this.creases = new LineLayer({ ridgeColor: LINE_COLORS.crease, valleyColor: concaveShade(LINE_COLORS.crease) });
    this.scene.add(this.surface.mesh, this.lines.group, this.creases.group);
    this.origin = [0, 0, 0];
    /** The canvas's rectangles that the page covers (panels), in CSS pixels of the canvas: framing avoids them. */
    this.covers = () => [];
    this.upAxis = 'y';
    this.preset = 'front';
    this.setBackground('light');
    this.surfaceCache = new SurfaceCache();
    /** Tests lower it to cache a small surface. */
    this.cacheMinTriangles = CACHE_MIN_TRIANGLES;

    const canvas = this.renderer.domElement;
    canvas.addEventListener('webglcontextlost', (event) => {
      event.preventDefault(); // allows the context to be restored
      this.surfaceCache.invalidate();
      onContextLost?.();
    });
    canvas.addEventListener('webglcontextrestored', () => {
      onContextRestored?.();
      this.render();
    });
    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(container);
    this.resize();
  }

  /** The worker's surface (Session.surface()), drawn from its `view`: float32 positions about `view.origin`, normals, radius.
   *  `fit`: frame it (a new mesh), else keep the view (pre-smoothing changed). */
  setSurface({ indices, view }, { fit = true } = {}) {
    this.origin = Array.from(view.origin);
    this.surface.setMesh(view, indices);
    if (fit) this.fitView();
    else this.render();
  }

  /** Every faired line; `kept` (line indices) are shown. */
  setLines(lines, kept) {
    this.lines.setLines(lines, this.origin, kept);
    this.render();
  }

  /** No lines and no creases (a new surface whose lines are to come). */
  clearLines() {
    const none = {
      points: new Float64Array(0),
      offsets: new Uint32Array(1),
      types: new Uint8Array(0),
      strengths: new Float64Array(0),
      lengths: new Float64Array(0),
      closed: new Uint8Array(0),
    };
    this.lines.setLines(none, this.origin);
    this.setCreases({ ...none, convex: new Uint8Array(0), angles: new Float64Array(0) });
  }

  /** The creases (Session.creases()): all shown, convex and concave in two shades. */
  setCreases(creases) {
    this.creaseLines = creasesAsLines(creases);
    this.creases.setLines(this.creaseLines, this.origin);
    this.render();
  }

  /** A threshold change: other lines shown, no geometry rebuilt. */
  setKept(kept) {
    this.lines.setKept(kept);
    this.render();
  }

  /** The canvas's uncovered rectangle, in CSS pixels. */
  uncovered() {
    const { clientWidth: w, clientHeight: h } = this.container;
    return uncoveredRect(w, h, this.covers());
  }

  /**
   * Whether the rectangle the model was last framed in (fitView) is still
   * uncovered in a canvas of the same size: the page's boxes changed their
   * contents but did not grow over it, so framing again would only move the
   * picture (and draw the surface anew).
   */
  framingUncovered() {
    const was = this.framedIn;
    const { clientWidth: w, clientHeight: h } = this.container;
    if (!was || was.width !== w || was.height !== h) return false;
    const now = this.uncovered();
    return now.left <= was.left && now.top <= was.top && now.right >= was.right && now.bottom >= was.bottom;
  }

  /** Shifts the projection so that the orbit centre is the centre of the uncovered rectangle. */
  applyFrame() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (!w || !h) return;
    const r = this.uncovered();
    const [x, y] = [w / 2 - (r.left + r.right) / 2, h / 2 - (r.top + r.bottom) / 2];
    if (x || y) this.camera.setViewOffset(w, h, x, y, w, h);
    else this.camera.clearViewOffset();
    this.camera.updateProjectionMatrix();
    this.render();
  }

  /** Frames the model in the uncovered rectangle, seen from the current preset. */
  fitView() {
    const geometry = this.surface.mesh.geometry;
    const sphere = geometry.boundingSphere ?? new Sphere(new Vector3(), 1);
    const radius = sphere.radius || 1;
    const { clientWidth: w, clientHeight: h } = this.container;
    const r = this.uncovered();
    this.framedIn = { ...r, width: w, height: h };
    const area = w && h ? { width: (r.right - r.left) / w, height: (r.bottom - r.top) / h } : undefined;
    const distance = fitDistance(this.camera, radius, area);
    this.camera.near = distance / 100;
    this.camera.far = distance * 10;
    this.camera.position.copy(sphere.center).addScaledVector(presetDirection(this.preset, this.upAxis), distance * 1.05);
    this.controls.target.copy(sphere.center);
    this.controls.update();
    this.applyFrame();
  }

  /** A view preset: 'front', 'back', 'left', 'right', 'top', 'bottom' or 'iso' (relative to the up axis). */
  setPreset(preset) {
    this.preset = preset;
    this.fitView();
  }

  /** 'y' or 'z': the model's up direction; the view is framed again from the front. */
  setUpAxis(up) {
    this.upAxis = up;
    setUpAxis(this.camera, this.controls, up);
    this.fitView();
  }

  setBackground(mode) {
    this.scene.background = new Color(BACKGROUND[mode] ?? BACKGROUND.light);
    this.render();
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.applyFrame();
    this.lines.setResolution(w, h); // line width in CSS pixels
    this.creases.setResolution(w, h);
    this.render();
  }

  render() {
    if (this.pending) return;
    this.pending = requestAnimationFrame(() => {
      this.pending = 0;
      this.draw();
      this.renderCount = (this.renderCount ?? 0) + 1;
      const after = this.afterDraw ?? [];
      this.afterDraw = null;
      for (const callback of after) callback();
    });
  }

  /** Runs `callback` once the next frame is drawn (one is asked for). */
  afterFrame(callback) {
    (this.afterDraw ??= []).push(callback);
    this.render();
  }

  /**
   * Compiles, once, what the first frames of a large surface need beyond a
   * small one's: the surface cache's copy program, and SwiftShader's code
   * for the cache's draws, by drawing the scene through the cache, then as
   * usual, in one frame (the canvas shows the usual picture; the cache's
   * picture is freed again); and the line layers' programs as the cache
   * draws them, alone, without the scene's lights (the creases' layer is
   * empty on the sample: its first crease would compile it). Otherwise a
   * first large mesh compiles them in its surface's and its lines' frames.
   * Only while a small surface is shown (a large one drew through the cache).
   */
  warmUpCache() {
    if (this.largeSurface()) return;
    // After a frame already asked for, if any: the last draw of the frame is the usual one.
    requestAnimationFrame(() => {
      this.surface.cullHiddenFaces(this.camera);
      this.drawThroughCache();
      this.draw();
      for (const layer of [this.lines, this.creases]) this.renderer.compile(layer.group, this.camera);
    });
  }

  /** Whether the surface is drawn through the surface cache. */
  largeSurface() {
    const index = this.surface.mesh.geometry.index;
    return (index ? index.count / 3 : 0) >= this.cacheMinTriangles;
  }

  /** The scene through the surface cache, the lines and creases drawn over its picture. */
  drawThroughCache() {
    this.surfaceCache.draw(this.renderer, this.scene, this.camera, [this.lines.group, this.creases.group]);
  }

  /** One frame, now: through the surface cache when the surface is large. */
  draw() {
    this.surface.cullHiddenFaces(this.camera);
    for (const layer of [this.lines, this.creases]) layer.fitDetail(this.camera, this.renderer.domElement.height); // device pixels
    if (this.largeSurface()) this.drawThroughCache();
    else {
      this.surfaceCache.release();
      this.renderer.render(this.scene, this.camera);
    }
  }

  dispose() {
    this.resizeObserver.disconnect();
    this.controls.dispose();
    this.surface.dispose();
    this.lines.dispose();
    this.creases.dispose();
    this.surfaceCache.dispose();
    this.renderer.dispose();
  }
}
