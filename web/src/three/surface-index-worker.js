// The smoothing brush's SurfaceIndex (BVH and vertex adjacency: seconds on a
// million triangles) built off the page's main thread, so switching the brush
// on does not freeze the page. Gets the surface's float32 positions and
// indices (copies), sends the index's arrays back (transferred).
import { SurfaceIndex } from './surface-index.js';

self.onmessage = ({ data: { id, positions, indices } }) => {
  const parts = SurfaceIndex.parts(new SurfaceIndex(positions, indices));
  self.postMessage(
    { id, parts },
    Object.values(parts)
      .filter(ArrayBuffer.isView)
      .map((a) => a.buffer),
  );
};
