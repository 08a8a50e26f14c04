// Framing: the camera distance at which a sphere fits both the vertical and
// the horizontal field of view (a portrait canvas is limited by its width),
// within the part of the canvas that the page's panels leave uncovered; view
// presets and the up axis (Y, glTF's convention, or Z, common in CAD and scans).
import { Quaternion, Vector3 } from 'three';

/**
 * @param {{fov: number, aspect: number}} camera a PerspectiveCamera (fov vertical, in degrees)
 * @param {number} radius the bounding sphere's radius
 * @param {{width: number, height: number}} [area] the part of the canvas to fit into, as fractions of its width and height
 */
export function fitDistance(camera, radius, area = { width: 1, height: 1 }) {
  const tanVertical = Math.tan((camera.fov * Math.PI) / 360);
  const halfVertical = Math.atan(tanVertical * area.height);
  const halfHorizontal = Math.atan(tanVertical * camera.aspect * area.width);
  return radius / Math.sin(Math.min(halfVertical, halfHorizontal));
}

/**
 * The largest rectangle of a width × height canvas that none of `covers`
 * (rectangles {left, top, right, bottom} in the canvas's pixels) overlaps:
 * each cover is avoided by keeping to one of its four sides.
 * @param {number} width @param {number} height
 * @param {{left: number, top: number, right: number, bottom: number}[]} covers
 */
export function uncoveredRect(width, height, covers) {
  const inside = covers.filter((c) => c.right > 0 && c.bottom > 0 && c.left < width && c.top < height && c.right > c.left && c.bottom > c.top);
  let best = { left: 0, top: 0, right: width, bottom: height };
  let bestArea = -1;
  const sides = 4 ** inside.length;
  for (let choice = 0; choice < sides; choice++) {
    const r = { left: 0, top: 0, right: width, bottom: height };
    inside.forEach((c, i) => {
      const side = Math.floor(choice / 4 ** i) % 4;
      if (side === 0) r.right = Math.min(r.right, c.left);
      else if (side === 1) r.left = Math.max(r.left, c.right);
      else if (side === 2) r.bottom = Math.min(r.bottom, c.top);
      else r.top = Math.max(r.top, c.bottom);
    });
    const area = Math.max(0, r.right - r.left) * Math.max(0, r.bottom - r.top);
    if (area > bestArea) [best, bestArea] = [r, area];
  }
  // Nothing sensible left (a cover over everything): the whole canvas.
  return bestArea >= 0.1 * width * height ? best : { left: 0, top: 0, right: width, bottom: height };
}

const Y = new Vector3(0, 1, 0);
export const UP_AXES = { y: new Vector3(0, 1, 0), z: new Vector3(0, 0, 1) };

/** Where the camera sits, seen from the model's centre, for a Y-up model (top and bottom tilt a hair so the up vector stays defined). */
const PRESETS_Y_UP = {
  front: [0, 0, 1],
  back: [0, 0, -1],
  left: [-1, 0, 0],
  right: [1, 0, 0],
  top: [0, 1, 1e-4],
  bottom: [0, -1, 1e-4],
  iso: [1, 1, 1],
};
export const VIEW_PRESETS = Object.keys(PRESETS_Y_UP);

/** The unit direction from the model's centre to the camera for `preset` with `up` ('y' or 'z'). */
export function presetDirection(preset, up = 'y') {
  const toModel = new Quaternion().setFromUnitVectors(Y, UP_AXES[up] ?? Y);
  return new Vector3(...(PRESETS_Y_UP[preset] ?? PRESETS_Y_UP.front)).applyQuaternion(toModel).normalize();
}

/** Sets the camera's up axis and makes OrbitControls orbit around it (they read it only when made). */
export function setUpAxis(camera, controls, up) {
  camera.up.copy(UP_AXES[up] ?? Y);
  controls._quat.setFromUnitVectors(camera.up, Y);
  controls._quatInverse = controls._quat.clone().invert();
}
