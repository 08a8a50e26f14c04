// The built-in sample mesh: the Stanford bunny of the npm package `bunny`
// (public domain), as a triangle soup.
import bunny from 'bunny';

export function sampleMesh() {
  const positions = Float64Array.from(bunny.positions.flat());
  const indices = Uint32Array.from(bunny.cells.flat());
  return { name: 'bunny (built-in sample)', positions, indices };
}
