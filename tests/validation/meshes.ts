/**
 * Triangle meshes made by code for the generator's mesh family, each in its own
 * unit frame (centred on the origin, about 2 across, y up), with smooth per-vertex
 * normals where the surface has them:
 * - closed: icosphere, box (12 triangles, corner normals averaged: far from its
 *   faces), torus (genus 1);
 * - open: a hemispherical bowl, a tube without caps, a bumpy height field, a disc
 *   fan, a sheet of two triangles and a single triangle.
 * Closed meshes face outward (counter-clockwise seen from outside); open ones face
 * +y, or outward for the tube. Plain arrays: these become JSON or mesh files.
 */
import type { Rng } from './rng.ts';
import { cross, dot, length, normalize, sub, type Vec3 } from './vec.ts';

export interface LocalMesh {
  /** What it is, for the scene's bookkeeping. */
  kind: MeshKind;
  closed: boolean;
  positions: number[];
  indices: number[];
  /** Smooth per-vertex normals (unit), the same length as positions. */
  normals: number[];
}

export type MeshKind =
  'icosphere' | 'box' | 'torus' | 'bowl' | 'tube' | 'height-field' | 'disc' | 'sheet' | 'triangle';

export function icosphere(levels: number): LocalMesh {
  const t = (1 + Math.sqrt(5)) / 2;
  const verts: Vec3[] = (
    [
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
    ] as Vec3[]
  ).map(normalize);
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
        const p = verts[a].map((x, i) => (x + verts[b][i]) / 2) as Vec3;
        verts.push(normalize(p));
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
  return {
    kind: 'icosphere',
    closed: true,
    positions: verts.flat(),
    indices: faces.flat(),
    normals: verts.flat(),
  };
}

/** The cube [−1, 1]³, 8 shared corners (so its smooth normals point along the diagonals). */
export function box(): LocalMesh {
  const positions: number[] = [];
  for (let i = 0; i < 8; i++) positions.push(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  const quads = [
    [0, 2, 3, 1], // z = −1
    [4, 5, 7, 6], // z = +1
    [0, 1, 5, 4], // y = −1
    [2, 6, 7, 3], // y = +1
    [0, 4, 6, 2], // x = −1
    [1, 3, 7, 5], // x = +1
  ];
  const indices: number[] = [];
  for (const [a, b, c, d] of quads) indices.push(a, b, c, a, c, d);
  const s = 1 / Math.sqrt(3);
  return {
    kind: 'box',
    closed: true,
    positions,
    indices,
    normals: positions.map((x) => x * s),
  };
}

/** A torus about the y axis: ring radius 1, tube radius r < 1, n × m quads. */
export function torus(r: number, n: number, m: number): LocalMesh {
  const positions: number[] = [];
  const normals: number[] = [];
  for (let i = 0; i < n; i++) {
    const phi = (2 * Math.PI * i) / n;
    for (let j = 0; j < m; j++) {
      const theta = (2 * Math.PI * j) / m;
      const nx = Math.cos(theta) * Math.cos(phi);
      const ny = Math.sin(theta);
      const nz = Math.cos(theta) * Math.sin(phi);
      positions.push(Math.cos(phi) + r * nx, r * ny, Math.sin(phi) + r * nz);
      normals.push(nx, ny, nz);
    }
  }
  const indices: number[] = [];
  const at = (i: number, j: number) => (i % n) * m + (j % m);
  for (let i = 0; i < n; i++) {
    for (let j = 0; j < m; j++) {
      const a = at(i, j);
      const b = at(i + 1, j);
      const c = at(i + 1, j + 1);
      const d = at(i, j + 1);
      indices.push(a, d, c, a, c, b);
    }
  }
  return orientOutward({ kind: 'torus', closed: true, positions, indices, normals });
}

/** The lower half of the unit sphere, open at y = 0: a bowl. Faces inward (up, into the bowl). */
export function bowl(n: number, m: number): LocalMesh {
  const positions: number[] = [0, -1, 0];
  const normals: number[] = [0, 1, 0];
  for (let j = 1; j <= m; j++) {
    const theta = (Math.PI / 2) * (1 - j / m); // from the bottom (π/2 below) up to the rim
    for (let i = 0; i < n; i++) {
      const phi = (2 * Math.PI * i) / n;
      const x = Math.cos(theta) * Math.cos(phi);
      const y = -Math.sin(theta);
      const z = Math.cos(theta) * Math.sin(phi);
      positions.push(x, y, z);
      normals.push(-x, -y, -z);
    }
  }
  const indices: number[] = [];
  const ring = (j: number, i: number) => 1 + (j - 1) * n + (i % n);
  for (let i = 0; i < n; i++) indices.push(0, ring(1, i), ring(1, i + 1));
  for (let j = 1; j < m; j++) {
    for (let i = 0; i < n; i++) {
      indices.push(ring(j, i), ring(j + 1, i), ring(j + 1, i + 1));
      indices.push(ring(j, i), ring(j + 1, i + 1), ring(j, i + 1));
    }
  }
  return orientAlong({ kind: 'bowl', closed: false, positions, indices, normals });
}

/** A tube of radius 1 from y = −1 to 1 without caps, facing outward. */
export function tube(n: number): LocalMesh {
  const positions: number[] = [];
  const normals: number[] = [];
  for (let i = 0; i < n; i++) {
    const phi = (2 * Math.PI * i) / n;
    for (const y of [-1, 1]) {
      positions.push(Math.cos(phi), y, Math.sin(phi));
      normals.push(Math.cos(phi), 0, Math.sin(phi));
    }
  }
  const indices: number[] = [];
  for (let i = 0; i < n; i++) {
    const a = 2 * i;
    const b = 2 * ((i + 1) % n);
    indices.push(a, a + 1, b + 1, a, b + 1, b);
  }
  return orientAlong({ kind: 'tube', closed: false, positions, indices, normals });
}

/** A k × k grid over [−1, 1]² in xz with random smooth bumps (height ≤ 0.4), facing +y. */
export function heightField(rng: Rng, k: number): LocalMesh {
  const bumps = Array.from({ length: 3 }, () => ({
    x: rng.uniform(-1, 1),
    z: rng.uniform(-1, 1),
    h: rng.uniform(-0.3, 0.3),
    w: rng.uniform(0.3, 0.8),
  }));
  const height = (x: number, z: number) => {
    let y = 0,
      dx = 0,
      dz = 0;
    for (const b of bumps) {
      const e = b.h * Math.exp(-((x - b.x) ** 2 + (z - b.z) ** 2) / (b.w * b.w));
      y += e;
      dx += (e * -2 * (x - b.x)) / (b.w * b.w);
      dz += (e * -2 * (z - b.z)) / (b.w * b.w);
    }
    return { y, dx, dz };
  };
  const positions: number[] = [];
  const normals: number[] = [];
  for (let j = 0; j <= k; j++) {
    for (let i = 0; i <= k; i++) {
      const x = -1 + (2 * i) / k;
      const z = -1 + (2 * j) / k;
      const h = height(x, z);
      positions.push(x, h.y, z);
      normals.push(...normalize([-h.dx, 1, -h.dz]));
    }
  }
  const indices: number[] = [];
  const at = (i: number, j: number) => j * (k + 1) + i;
  for (let j = 0; j < k; j++) {
    for (let i = 0; i < k; i++) {
      indices.push(
        at(i, j),
        at(i, j + 1),
        at(i + 1, j + 1),
        at(i, j),
        at(i + 1, j + 1),
        at(i + 1, j),
      );
    }
  }
  return orientAlong({ kind: 'height-field', closed: false, positions, indices, normals });
}

/** A unit disc in the xz plane as a fan of n triangles, facing +y. */
export function disc(n: number): LocalMesh {
  const positions = [0, 0, 0];
  const normals = [0, 1, 0];
  for (let i = 0; i < n; i++) {
    const phi = (2 * Math.PI * i) / n;
    positions.push(Math.cos(phi), 0, Math.sin(phi));
    normals.push(0, 1, 0);
  }
  const indices: number[] = [];
  for (let i = 0; i < n; i++) indices.push(0, 1 + ((i + 1) % n), 1 + i);
  return orientAlong({ kind: 'disc', closed: false, positions, indices, normals });
}

/**
 * The square [−1, 1]² in xz as two triangles, facing +y, without shared vertices
 * (consecutive triples: no `indices`); its normals are tilted by up to `tilt`
 * radians, each vertex its own way, so the shading frame differs from the face.
 */
export function sheet(rng: Rng, tilt: number): LocalMesh {
  const corners: Vec3[] = [
    [-1, 0, -1],
    [-1, 0, 1],
    [1, 0, 1],
    [-1, 0, -1],
    [1, 0, 1],
    [1, 0, -1],
  ];
  const normals = corners.flatMap(() => tilted(rng, tilt));
  return {
    kind: 'sheet',
    closed: false,
    positions: corners.flat(),
    indices: [0, 1, 2, 3, 4, 5],
    normals,
  };
}

/** One triangle in the xz plane, facing +y, with tilted normals. */
export function triangle(rng: Rng, tilt: number): LocalMesh {
  const a = rng.uniform(0, 2 * Math.PI);
  const corners: Vec3[] = [0, 1, 2].map((k) => {
    const phi = a - (2 * Math.PI * k) / 3 + rng.uniform(-0.4, 0.4);
    return [Math.cos(phi), 0, Math.sin(phi)];
  });
  return {
    kind: 'triangle',
    closed: false,
    positions: corners.flat(),
    indices: [0, 1, 2],
    normals: corners.flatMap(() => tilted(rng, tilt)),
  };
}

/** +y tilted by up to `tilt` radians in a random azimuth. */
function tilted(rng: Rng, tilt: number): number[] {
  const t = rng.uniform(0, tilt);
  const phi = rng.uniform(0, 2 * Math.PI);
  return [Math.sin(t) * Math.cos(phi), Math.cos(t), Math.sin(t) * Math.sin(phi)];
}

function triangleNormal(m: LocalMesh, t: number): Vec3 {
  const p = (k: number): Vec3 => {
    const i = 3 * m.indices[3 * t + k];
    return [m.positions[i], m.positions[i + 1], m.positions[i + 2]];
  };
  const p0 = p(0);
  return cross(sub(p(1), p0), sub(p(2), p0));
}

/** Reverses every triangle (swaps its last two corners): the geometric normal flips. */
export function reverseWinding(m: LocalMesh): LocalMesh {
  const indices = m.indices.slice();
  for (let t = 0; t < indices.length; t += 3) {
    [indices[t + 1], indices[t + 2]] = [indices[t + 2], indices[t + 1]];
  }
  return { ...m, indices };
}

/** Winds every triangle so that its face normal agrees with the vertex normals. */
function orientAlong(m: LocalMesh): LocalMesh {
  const indices = m.indices.slice();
  for (let t = 0; t < indices.length / 3; t++) {
    const i = 3 * indices[3 * t];
    const n: Vec3 = [m.normals[i], m.normals[i + 1], m.normals[i + 2]];
    if (dot(triangleNormal(m, t), n) < 0) {
      [indices[3 * t + 1], indices[3 * t + 2]] = [indices[3 * t + 2], indices[3 * t + 1]];
    }
  }
  return { ...m, indices };
}

/** A closed mesh: faces point away from its centroid (true of the convex-ish shapes here). */
function orientOutward(m: LocalMesh): LocalMesh {
  return orientAlong(m);
}

/** Area of the mesh (sum of its triangles). */
export function meshArea(m: { positions: number[]; indices: number[] }): number {
  let a = 0;
  for (let t = 0; t < m.indices.length / 3; t++) {
    a += length(triangleNormal(m as LocalMesh, t)) / 2;
  }
  return a;
}
