// A CAD-like mesh for the crease tests: a box with sharp, convex edges only.

/**
 * A box, by default 2×1×1 with each face split into 24×24 quads (two
 * triangles each): 12 convex edges of 24 segments. `size` and `n` make
 * others (a thin slab for the brush test).
 */
export function boxObj({ size = [2, 1, 1], n = 24 } = {}) {
  const vertices = new Map();
  const lines = [];
  const vertex = (p) => {
    const key = p.map((x) => x.toFixed(6)).join(' ');
    if (!vertices.has(key)) {
      vertices.set(key, vertices.size + 1);
      lines.push(`v ${key}`);
    }
    return vertices.get(key);
  };
  const faces = [];
  for (let axis = 0; axis < 3; axis++) {
    const [u, v] = [(axis + 1) % 3, (axis + 2) % 3];
    for (const side of [0, 1]) {
      const at = (i, j) => {
        const p = [0, 0, 0];
        p[axis] = side * size[axis];
        p[u] = (i / n) * size[u];
        p[v] = (j / n) * size[v];
        return vertex(p);
      };
      for (let i = 0; i < n; i++) {
        for (let j = 0; j < n; j++) {
          const [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
          // Outward normals: the side at 0 winds the other way.
          faces.push(side ? `f ${a} ${b} ${c}\nf ${a} ${c} ${d}` : `f ${a} ${c} ${b}\nf ${a} ${d} ${c}`);
        }
      }
    }
  }
  return `${lines.join('\n')}\n${faces.join('\n')}\n`;
}
