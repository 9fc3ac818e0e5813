/** A small closed mesh (an octahedron) that the PLY and OBJ generators write out. */
import type { Rng } from './rng.ts';

export interface MeshData {
  positions: number[][];
  normals: number[][];
  /** Polygons: triangles, and quads where the generator merged two. */
  faces: number[][];
}

export function octahedron(rng: Rng): MeshData {
  const s = rng.float(0.5, 1.2);
  const positions = [
    [s, 0, 0],
    [-s, 0, 0],
    [0, s, 0],
    [0, -s, 0],
    [0, 0, s],
    [0, 0, -s],
  ].map((p) => p.map((c) => c + rng.float(-0.05, 0.05)));
  const normals = positions.map((p) => {
    const l = Math.hypot(p[0], p[1], p[2]);
    return p.map((c) => c / l);
  });
  const faces = [
    [0, 2, 4],
    [4, 2, 1],
    [1, 2, 5],
    [5, 2, 0],
    [4, 3, 0],
    [1, 3, 4],
    [5, 3, 1],
    [0, 3, 5],
  ];
  return { positions, normals, faces };
}
