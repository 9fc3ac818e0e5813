/**
 * Test meshes made by code: an icosphere (closed, outward winding), a cube of 12
 * triangles and an octahedron, as flat position and index arrays.
 */

export interface TestMesh {
  positions: Float64Array;
  indices: Uint32Array;
}

/** Unit icosphere: the icosahedron subdivided `levels` times, vertices on the sphere. */
export function icosphere(levels: number, radius = 1, center: number[] = [0, 0, 0]): TestMesh {
  const t = (1 + Math.sqrt(5)) / 2;
  const verts: number[][] = [
    [-1, t, 0],
    [1, t, 0],
    [-1, -t, 0],
    [1, -t, 0],
    [0, -1, t],
    [0, 1, t],
    [0, -1, -t],
    [0, 1, -t],
    [t, 0, -1],
    [t, 0, 1],
    [-t, 0, -1],
    [-t, 0, 1],
  ].map(normalize);
  let faces = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
  ];
  for (let l = 0; l < levels; l++) {
    const mid = new Map<string, number>();
    const midpoint = (a: number, b: number): number => {
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      let m = mid.get(key);
      if (m === undefined) {
        m = verts.length;
        verts.push(normalize(verts[a].map((x, i) => (x + verts[b][i]) / 2)));
        mid.set(key, m);
      }
      return m;
    };
    const next: number[][] = [];
    for (const [a, b, c] of faces) {
      const ab = midpoint(a, b);
      const bc = midpoint(b, c);
      const ca = midpoint(c, a);
      next.push([a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]);
    }
    faces = next;
  }
  const positions = new Float64Array(verts.length * 3);
  verts.forEach((v, i) => {
    for (let k = 0; k < 3; k++) positions[3 * i + k] = center[k] + radius * v[k];
  });
  return { positions, indices: Uint32Array.from(faces.flat()) };
}

function normalize(v: number[]): number[] {
  const l = Math.hypot(v[0], v[1], v[2]);
  return v.map((x) => x / l);
}

/** The cube [0, 1]³ as 12 triangles facing outward. */
export function cube(): TestMesh {
  const positions = new Float64Array([
    0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1,
  ]);
  // Each face as two triangles, counter-clockwise seen from outside.
  const quads = [
    [0, 3, 2, 1], // z = 0
    [4, 5, 6, 7], // z = 1
    [0, 1, 5, 4], // y = 0
    [3, 7, 6, 2], // y = 1
    [0, 4, 7, 3], // x = 0
    [1, 2, 6, 5], // x = 1
  ];
  const indices: number[] = [];
  for (const [a, b, c, d] of quads) indices.push(a, b, c, a, c, d);
  return { positions, indices: Uint32Array.from(indices) };
}

/** The octahedron with vertices ±x, ±y, ±z, facing outward. */
export function octahedron(): TestMesh {
  const positions = new Float64Array([1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1]);
  const indices: number[] = [];
  for (const x of [0, 1]) {
    for (const y of [2, 3]) {
      for (const z of [4, 5]) {
        // Orientation of (x, y, z) seen from outside: flip by the octant's parity.
        const flip = (x === 1 ? 1 : 0) ^ (y === 3 ? 1 : 0) ^ (z === 5 ? 1 : 0);
        if (flip) indices.push(x, z, y);
        else indices.push(x, y, z);
      }
    }
  }
  return { positions, indices: Uint32Array.from(indices) };
}

/** Applies p → p·scale + offset to every vertex (a fresh copy). */
export function scaledMesh(m: TestMesh, scale: number, offset: number[] = [0, 0, 0]): TestMesh {
  const positions = m.positions.map((x, i) => x * scale + offset[i % 3]);
  return { positions, indices: m.indices };
}
