// The issue-15 mesh that fan triangulation gets wrong, shared by the node
// reader test (io.test.mjs) and the browser app test.

/**
 * A cosine ridge field tiled by concave L-shaped octagons: each 2×3 block of
 * grid cells is two L-trominoes, each an OBJ face of 8 corners (the grid
 * points on its boundary, two of them straight). Fan triangulation gets
 * these wrong (overlapping and degenerate triangles); ear clipping does not.
 */
export function concaveOctagonObj(blocksX = 30, blocksY = 30) {
  const nx = 2 * blocksX;
  const ny = 3 * blocksY;
  const lines = [];
  for (let j = 0; j <= ny; j++) {
    for (let i = 0; i <= nx; i++) {
      const x = (4 * i) / nx;
      const y = (4 * j) / nx;
      lines.push(`v ${x} ${y} ${0.1 * Math.cos(2 * Math.PI * x)}`);
    }
  }
  const v = (i, j) => j * (nx + 1) + i + 1;
  for (let by = 0; by < blocksY; by++) {
    for (let bx = 0; bx < blocksX; bx++) {
      const [i, j] = [2 * bx, 3 * by];
      const L1 = [
        [0, 0],
        [1, 0],
        [2, 0],
        [2, 1],
        [1, 1],
        [1, 2],
        [0, 2],
        [0, 1],
      ];
      const L2 = [
        [1, 1],
        [2, 1],
        [2, 2],
        [2, 3],
        [1, 3],
        [0, 3],
        [0, 2],
        [1, 2],
      ];
      for (const L of [L1, L2]) lines.push(`f ${L.map(([a, b]) => v(i + a, j + b)).join(' ')}`);
    }
  }
  return `${lines.join('\n')}\n`;
}
