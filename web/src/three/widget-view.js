// One <crestline-viewer>'s scene: camera, lights, the surface and line layers,
// orbit controls on the element's own 2D canvas. Drawing goes
// through the shared renderer (renderer.js).
import { Color, DirectionalLight, HemisphereLight, PerspectiveCamera, Quaternion, Scene, Spherical } from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { UP_AXES, fitDistance, setUpAxis } from './fit.js';
import { LineLayer, creasesAsLines } from './line-layer.js';
import { SurfaceLayer } from './surface-layer.js';
import { forget, requestDraw } from './renderer.js';

const KEY_STEP = Math.PI / 18; // 10° per arrow key

export class WidgetView {
  /** @param {HTMLCanvasElement} canvas the element's 2D canvas (also the controls' target) */
  constructor(canvas) {
    this.canvas = canvas;
    this.visible = false;
    this.scene = new Scene();
    this.camera = new PerspectiveCamera(35, 2, 0.01, 100);
    this.scene.add(this.camera);
    this.scene.add(new HemisphereLight(0xffffff, 0x606070, 1.6));
    const key = new DirectionalLight(0xffffff, 1.8);
    key.position.set(1, 1.5, 2);
    this.camera.add(key);
    this.surface = new SurfaceLayer();
    this.lines = new LineLayer();
    this.creases = new LineLayer(); // convex and concave creases (creasesAsLines)
    this.scene.add(this.surface.mesh, this.lines.group, this.creases.group);
    this.origin = [0, 0, 0];
    this.radius = 1;
    this.orbit = { theta: 0, phi: (75 * Math.PI) / 180, radius: 1 };
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener('change', () => this.draw());
    this.controls.addEventListener('start', () => (this.interacting = true));
    this.controls.addEventListener('end', () => (this.interacting = false));
    this.autoRotate = false;
  }

  /** The worker's surface (Session.surface()), drawn from its `view`: float32 positions about `view.origin`, normals, radius. */
  setSurface({ indices, view }) {
    this.origin = Array.from(view.origin);
    this.surface.setMesh(view, indices);
    this.radius = view.radius || 1;
    this.applyOrbit();
  }

  /** Every faired line; `kept` (line indices) are shown. */
  setLines(lines, kept) {
    this.lines.setLines(lines, this.origin, kept);
    this.draw();
  }

  /** The creases (Session.creases()), all shown. */
  setCreases(creases) {
    this.creaseLines = creasesAsLines(creases);
    this.creases.setLines(this.creaseLines, this.origin);
    this.draw();
  }

  /** A threshold change: other lines shown, no geometry rebuilt. */
  setKept(kept) {
    this.lines.setKept(kept);
    this.draw();
  }

  /**
   * {theta, phi} in radians around the model's centre, radius as a factor of
   * the framing distance; `up` ('y' or 'z'): the model's up axis, which the
   * polar angle is measured from.
   */
  setOrbit(orbit, up = 'y') {
    this.orbit = orbit;
    this.up = up;
    setUpAxis(this.camera, this.controls, up);
    this.applyOrbit();
  }

  applyOrbit() {
    const fit = fitDistance(this.camera, this.radius);
    const distance = fit * this.orbit.radius * 1.05;
    this.camera.near = fit / 100;
    this.camera.far = fit * 20;
    this.camera.updateProjectionMatrix();
    this.controls.target.set(0, 0, 0);
    // Spherical coordinates about Y, turned so that Y becomes the model's up axis.
    const toModel = new Quaternion().setFromUnitVectors(UP_AXES.y, UP_AXES[this.up ?? 'y']);
    this.camera.position.setFromSpherical(new Spherical(distance, this.orbit.phi, this.orbit.theta)).applyQuaternion(toModel);
    this.controls.minDistance = fit * 0.2;
    this.controls.maxDistance = fit * 10;
    this.controls.update();
    this.draw();
  }

  setBackground(color) {
    this.scene.background = color && color !== 'transparent' ? new Color(color) : null;
    this.draw();
  }

  /** CSS size → canvas pixels, camera aspect and line resolution. */
  resize(width, height, pixelRatio) {
    if (!width || !height) return;
    this.canvas.width = Math.round(width * pixelRatio);
    this.canvas.height = Math.round(height * pixelRatio);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.lines.setResolution(width, height);
    this.creases.setResolution(width, height);
    this.draw();
  }

  setInteractive(enabled) {
    this.controls.enabled = enabled;
  }

  /** Arrow keys orbit, +/- zoom; returns true when the key was used. */
  handleKey(key) {
    const c = this.controls;
    const actions = {
      ArrowLeft: () => c.rotateLeft(KEY_STEP),
      ArrowRight: () => c.rotateLeft(-KEY_STEP),
      ArrowUp: () => c.rotateUp(KEY_STEP),
      ArrowDown: () => c.rotateUp(-KEY_STEP),
      '+': () => c.dollyIn(1.1),
      '=': () => c.dollyIn(1.1),
      '-': () => c.dollyOut(1.1),
    };
    if (!actions[key] || !c.enabled) return false;
    actions[key]();
    c.update();
    return true;
  }

  setAutoRotate(enabled) {
    this.autoRotate = enabled;
    this.controls.autoRotate = enabled;
    this.draw();
  }

  draw() {
    requestDraw(this);
  }

  /** Called by the renderer before each frame: advances auto-rotation. */
  beforeDraw() {
    if (this.autoRotate && !this.interacting) this.controls.update();
  }

  afterDraw() {
    if (this.autoRotate) this.draw(); // next frame
  }

  dispose() {
    forget(this);
    this.controls.dispose();
    this.surface.dispose();
    this.lines.dispose();
    this.creases.dispose();
  }
}
