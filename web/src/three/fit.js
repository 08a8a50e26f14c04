// Framing: the camera distance at which a sphere fits both the vertical and
// the horizontal field of view (a portrait canvas is limited by its width).

/**
 * @param {{fov: number, aspect: number}} camera a PerspectiveCamera (fov vertical, in degrees)
 * @param {number} radius the bounding sphere's radius
 */
export function fitDistance(camera, radius) {
  const halfVertical = (camera.fov * Math.PI) / 360;
  const halfHorizontal = Math.atan(Math.tan(halfVertical) * camera.aspect);
  return radius / Math.sin(Math.min(halfVertical, halfHorizontal));
}
