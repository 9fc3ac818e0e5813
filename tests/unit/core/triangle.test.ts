/**
 * The watertight ray–triangle test: exact answers on easy cases, and on hard ones
 * (points exactly on shared edges and vertices, grazing rays, huge and tiny meshes,
 * far origins) no crack and no double hit: a ray through a closed convex mesh crosses
 * it exactly twice, a ray through a plane of triangles exactly once.
 */
import { describe, expect, it } from 'vitest';
import { TriangleEdges, triangleEdges } from '../../../src/core/geometry/triangle-edges.ts';
import { triangleNormal } from '../../../src/core/lights/mesh-light.ts';
import {
  TriangleHit,
  TriangleRay,
  hitTriangle,
  intersectTriangleBary,
  setTriangleRay,
} from '../../../src/core/geometry/triangle.ts';
import { exactDiffOfProducts } from '../../../src/core/geometry/exact.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import { cube, icosphere, octahedron, scaledMesh, type TestMesh } from '../../helpers/mesh-gen.ts';

const r = new TriangleRay();
/** A ray record: the far bound lives at index 6 (accel/trace.ts R_T). */
const best = new Float64Array(8);

/** Distance by the fast test (hitTriangle), Infinity for a miss. */
function intersectTriangle(
  positions: Float64Array,
  indices: Uint32Array,
  tri: number,
  ray: TriangleRay,
  tMax: number,
): number {
  best[6] = tMax;
  return hitTriangle(positions, indices, tri, ray, best) ? best[6] : Infinity;
}

function shoot(
  m: TestMesh,
  o: number[],
  d: number[],
  tMax = Infinity,
): { count: number; ts: number[] } {
  setTriangleRay(o[0], o[1], o[2], d[0], d[1], d[2], r);
  const ts: number[] = [];
  let nan = 0;
  for (let i = 0; i < m.indices.length / 3; i++) {
    const t = intersectTriangle(m.positions, m.indices, i, r, tMax);
    if (Number.isNaN(t)) nan++;
    if (t < Infinity) ts.push(t);
  }
  if (nan > 0) expect.fail(`${nan} NaN distances`);
  return { count: ts.length, ts: ts.sort((a, b) => a - b) };
}

const single: TestMesh = {
  positions: new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0]),
  indices: new Uint32Array([0, 1, 2]),
};

describe('exact sign of a·b − c·d', () => {
  it('is exact where the rounded difference is wrong or zero', () => {
    // (1 + 2^-30)(1 - 2^-30) − 1 = −2^-60, lost entirely by rounding.
    const a = 1 + 2 ** -30;
    const b = 1 - 2 ** -30;
    expect(a * b - 1 * 1).toBe(0);
    expect(exactDiffOfProducts(a, b, 1, 1)).toBe(-(2 ** -60));
    expect(exactDiffOfProducts(3, 7, 7, 3)).toBe(0);
    expect(Math.sign(exactDiffOfProducts(0.1, 0.3, 0.3, 0.1))).toBe(0);
    expect(exactDiffOfProducts(1e100, 1e-100, 1e-100, 1e100)).toBe(0);
  });
});

describe('ray–triangle basics', () => {
  it('hits with the right distance and barycentrics', () => {
    setTriangleRay(0.25, 0.5, -2, 0, 0, 1, r);
    const hit = new TriangleHit();
    const t = intersectTriangleBary(single.positions, single.indices, 0, r, Infinity, hit);
    expect(t).toBe(2);
    expect(hit.b0).toBeCloseTo(0.25, 15);
    expect(hit.b1).toBeCloseTo(0.25, 15);
    expect(hit.b2).toBeCloseTo(0.5, 15);
    // From behind, with a non-unit direction: same point, t in units of |d|.
    setTriangleRay(0.25, 0.5, 3, 0, 0, -2, r);
    expect(intersectTriangle(single.positions, single.indices, 0, r, Infinity)).toBe(1.5);
  });

  it('misses outside, behind the origin, beyond tMax, edge-on and from its own plane', () => {
    expect(shoot(single, [1, 1, -1], [0, 0, 1]).count).toBe(0);
    expect(shoot(single, [0.2, 0.2, 1], [0, 0, 1]).count).toBe(0);
    expect(shoot(single, [0.2, 0.2, -1], [0, 0, 1], 1).count).toBe(0);
    expect(shoot(single, [0.2, 0.2, -1], [0, 0, 1], 1 + 1e-15).count).toBe(1);
    expect(shoot(single, [-1, 0.2, 0], [1, 0, 0]).count).toBe(0); // in the plane
    expect(shoot(single, [0.2, 0.2, 0], [0, 0, 1]).count).toBe(0); // origin on it: t = 0
  });

  it('agrees with a plane intersection on random rays to 1e-13', () => {
    const m = icosphere(1);
    const hit = new TriangleHit();
    let hits = 0;
    for (let i = 0; i < 2000; i++) {
      const key = sampleKey(3, i, 0);
      const o = [0, 1, 2].map((k) => 6 * hashToUnit(key, k) - 3);
      const d = [0, 1, 2].map((k) => hashToUnit(key, 3 + k) - 0.5);
      setTriangleRay(o[0], o[1], o[2], d[0], d[1], d[2], r);
      for (let tri = 0; tri < m.indices.length / 3; tri++) {
        const t = intersectTriangleBary(m.positions, m.indices, tri, r, Infinity, hit);
        if (t === Infinity) continue;
        hits++;
        const p = m.positions;
        const [a, b, c] = [0, 1, 2].map((k) => m.indices[3 * tri + k] * 3);
        for (let k = 0; k < 3; k++) {
          const fromBary = hit.b0 * p[a + k] + hit.b1 * p[b + k] + hit.b2 * p[c + k];
          expect(Math.abs(o[k] + t * d[k] - fromBary)).toBeLessThan(1e-13);
        }
        expect(Math.min(hit.b0, hit.b1, hit.b2)).toBeGreaterThanOrEqual(0);
        expect(hit.b0 + hit.b1 + hit.b2).toBeCloseTo(1, 14);
      }
    }
    expect(hits).toBeGreaterThan(200);
  });
});

describe('watertight: exactly one hit where a ray crosses the surface', () => {
  it('through the shared edges and vertices of an octahedron and a cube, on the axes', () => {
    const oct = octahedron();
    // Vertex (0, 0, 1) is shared by 4 faces, (0, 0, −1) too: 2 crossings, not 8.
    expect(shoot(oct, [0, 0, -5], [0, 0, 1]).count).toBe(2);
    expect(shoot(oct, [0, 0, 5], [0, 0, -1]).count).toBe(2);
    // Entering and leaving through edges y = 0.
    expect(shoot(oct, [-5, 0, 0.5], [1, 0, 0]).count).toBe(2);
    expect(shoot(oct, [0.25, -5, 0.25], [0, 1, 0]).count).toBe(2);
    const box = cube();
    // Along the diagonal through the corners (0,0,0) and (1,1,1), each shared by 6 triangles.
    expect(shoot(box, [-1, -1, -1], [1, 1, 1]).count).toBe(2);
    expect(shoot(box, [2, 2, 2], [-1, -1, -1]).count).toBe(2);
    // Through the middle of faces along their diagonal edges, and through face centres.
    for (const [x, y] of [
      [0.5, 0.5],
      [0.25, 0.25],
      [0.75, 0.75],
      [0.3, 0.6],
    ]) {
      expect(shoot(box, [x, y, -1], [0, 0, 1]).count).toBe(2);
      expect(shoot(box, [x, -1, y], [0, 1, 0]).count).toBe(2);
      expect(shoot(box, [-1, x, y], [1, 0, 0]).count).toBe(2);
    }
  });

  it('through the vertices and edge points of an icosphere from random directions, at every scale', () => {
    const base = icosphere(2);
    for (const [scale, offset] of [
      [1, 0],
      [1e-30, 0],
      [1e30, 0],
      [1e-6, 1e3],
      [1, 1e7],
      [1e80, 0],
      [1e-80, 0],
      // Beyond ~2^±340 the distance's cubic over- or underflows: the careful path rescales.
      [1e120, 0],
      [1e150, 1e151],
      [1e300, 0],
      [1e-120, 0],
      [1e-200, 0],
      [1e-300, 1e-299],
    ] as const) {
      const m = scaledMesh(base, scale, [offset, -offset, offset / 3]);
      const p = m.positions;
      let tested = 0;
      for (let i = 0; i < 600; i++) {
        const key = sampleKey(11, i, 0);
        const tri = Math.floor(hashToUnit(key, 0) * (m.indices.length / 3));
        const [a, b] = [0, 1].map((k) => m.indices[3 * tri + k] * 3);
        // A vertex (exactly) or a point on an edge (rounded onto or beside it).
        const s = i % 2 === 0 ? 0 : hashToUnit(key, 1);
        const target = [0, 1, 2].map((k) => p[a + k] + s * (p[b + k] - p[a + k]));
        const c = [offset, -offset, offset / 3];
        const out = [0, 1, 2].map((k) => target[k] - c[k]);
        // Come from outside, within 60° of the outward direction: the line passes
        // through the interior, so it crosses the surface exactly twice.
        const jitter = [0, 1, 2].map((k) => (hashToUnit(key, 2 + k) - 0.5) * scale);
        const dir = [0, 1, 2].map((k) => -(out[k] + 0.5 * jitter[k]));
        const origin = [0, 1, 2].map((k) => target[k] - 3 * dir[k]);
        const { count } = shoot(m, origin, dir);
        if (count !== 2) expect.fail(`scale ${scale}, offset ${offset}, ray ${i}: ${count} hits`);
        tested++;
      }
      expect(tested).toBe(600);
    }
  });

  it('through a plane of 2·64² triangles: one hit per ray aimed at its vertices and edges', () => {
    const n = 64;
    const pos: number[] = [];
    for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) pos.push(i / n, j / n, 0);
    const idx: number[] = [];
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        const v = j * (n + 1) + i;
        // Alternate the diagonal so vertices have 4 and 8 triangles around them.
        if ((i + j) % 2 === 0) idx.push(v, v + 1, v + n + 2, v, v + n + 2, v + n + 1);
        else idx.push(v, v + 1, v + n + 1, v + 1, v + n + 2, v + n + 1);
      }
    }
    const plane = { positions: new Float64Array(pos), indices: new Uint32Array(idx) };
    for (let i = 0; i < 400; i++) {
      const key = sampleKey(5, i, 0);
      const gx = 1 + Math.floor(hashToUnit(key, 0) * (n - 2));
      const gy = 1 + Math.floor(hashToUnit(key, 1) * (n - 2));
      const kind = i % 4;
      // Vertex, horizontal edge, vertical edge, diagonal.
      const f = hashToUnit(key, 2);
      const x = (gx + (kind === 1 || kind === 3 ? f : 0)) / n;
      const y = (gy + (kind === 2 || kind === 3 ? f : 0)) / n;
      const d = [hashToUnit(key, 3) - 0.5, hashToUnit(key, 4) - 0.5, 1];
      const o = [x - 2 * d[0], y - 2 * d[1], -2];
      expect(shoot(plane, o, d).count, `ray ${i} kind ${kind}`).toBe(1);
      // Straight down onto exact grid points (exact zeros in the edge functions).
      expect(shoot(plane, [gx / n, gy / n, 1], [0, 0, -1]).count).toBe(1);
      expect(shoot(plane, [(gx + 0.5) / n, gy / n, 1], [0, 0, -1]).count).toBe(1);
    }
  });
});

describe('the fast and the careful test', () => {
  it('give the same answers, near edges too', () => {
    const m = icosphere(2);
    let hits = 0;
    for (let i = 0; i < 3000; i++) {
      const key = sampleKey(17, i, 0);
      const tri = Math.floor(hashToUnit(key, 0) * (m.indices.length / 3));
      const [a, b, c] = [0, 1, 2].map((k) => m.indices[3 * tri + k] * 3);
      // Aim at points inside, on the edges and just outside, from random origins.
      const s = 1.2 * hashToUnit(key, 1) - 0.1;
      const t = i % 3 === 0 ? 0 : hashToUnit(key, 2) * (1 - s);
      const p = [0, 1, 2].map(
        (k) =>
          m.positions[a + k] +
          s * (m.positions[b + k] - m.positions[a + k]) +
          t * (m.positions[c + k] - m.positions[a + k]),
      );
      const o = [0, 1, 2].map((k) => 4 * hashToUnit(key, 3 + k) - 2);
      setTriangleRay(o[0], o[1], o[2], p[0] - o[0], p[1] - o[1], p[2] - o[2], r);
      for (const tMax of [Infinity, 1, 0.5]) {
        const fast = intersectTriangle(m.positions, m.indices, tri, r, tMax);
        const careful = intersectTriangleBary(m.positions, m.indices, tri, r, tMax, null);
        if (fast !== careful)
          expect.fail(`ray ${i}, tMax ${tMax}: fast ${fast}, careful ${careful}`);
        if (fast < Infinity) hits++;
      }
    }
    expect(hits).toBeGreaterThan(2000);
  });
});

describe('exact edge functions', () => {
  it('gives the hit to the triangle that holds the point exactly, where rounding says "on the edge"', () => {
    // In the plane z = 0, seen along +z from the origin: B ≈ (−1, −1) and C ≈ (1, 1)
    // with 1 − a·b = 2^-60 exactly, which rounds to 0. So the ray passes 2^-61 beside the
    // shared edge BC, on the side of D = (1, −1): only triangle (D, C, B) holds it. The
    // mirror images swap the roles, so a tie rule alone would get one of them wrong.
    const a = 1 + 2 ** -30;
    const b = 1 - 2 ** -30;
    for (const [mx, my] of [
      [1, 1],
      [-1, 1],
      [1, -1],
      [-1, -1],
    ]) {
      const pts = [
        [-1, 1], // A
        [-1, -b], // B
        [a, 1], // C
        [1, -1], // D
      ].map(([x, y]) => [x * mx, y * my, 0]);
      const m = {
        positions: new Float64Array(pts.flat()),
        indices: new Uint32Array([0, 1, 2, 3, 2, 1]),
      };
      setTriangleRay(0, 0, -1, 0, 0, 1, r);
      const t1 = intersectTriangle(m.positions, m.indices, 0, r, Infinity);
      const t2 = intersectTriangle(m.positions, m.indices, 1, r, Infinity);
      expect([t1, t2], `mirror ${mx}, ${my}`).toEqual([Infinity, 1]);
    }
  });
});

describe('hard rays', () => {
  it('gives a finite distance or a miss for grazing rays, never NaN', () => {
    for (const e of [1e-8, 1e-12, 1e-15, 1e-200, 0]) {
      const { ts } = shoot(single, [-1, 0.25, e], [1, 0, -e]);
      for (const t of ts) expect(t).toBeGreaterThan(0);
    }
  });

  it('hits a huge and a tiny triangle at the right distance', () => {
    const huge = scaledMesh(single, 1e30);
    expect(shoot(huge, [1e29, 1e29, -5], [0, 0, 1]).ts).toEqual([5]);
    const tiny = scaledMesh(single, 1e-30);
    const [t] = shoot(tiny, [2.5e-31, 2.5e-31, -1e-30], [0, 0, 1]).ts;
    expect(Math.abs(t / 1e-30 - 1)).toBeLessThan(1e-15);
    // A tiny triangle far from the origin, seen from far away.
    const far = scaledMesh(single, 1e-3, [1e6, 1e6, 1e6]);
    const { ts } = shoot(far, [1e6 + 2.5e-4, 1e6 + 2.5e-4, 0], [0, 0, 1]);
    expect(ts).toHaveLength(1);
    expect(Math.abs(ts[0] - 1e6)).toBeLessThan(1e-9);
  });
});

describe('triangleNormal', () => {
  // triangleNormal (lights/mesh-light.ts) writes out triangleEdges' arithmetic for V8's
  // inlining; it must give what the shared routine's scaled edges give, bit for bit, at
  // every magnitude.
  it('equals normalize(cross) of triangleEdges scaled by 1/m, at magnitudes 2^-1000 … 2^1000', () => {
    const edges = new TriangleEdges();
    const out = { nx: 0, ny: 0, nz: 0 };
    let state = 12345;
    const rand = () => ((state = (Math.imul(state, 1664525) + 1013904223) >>> 0) / 2 ** 32) * 2 - 1;
    let checked = 0;
    for (let k = -1000; k <= 1000; k += 25) {
      for (let n = 0; n < 20; n++) {
        const s = 2 ** k;
        const p = Float64Array.from({ length: 9 }, () => rand() * s);
        triangleNormal(p, 0, 3, 6, out);
        triangleEdges(p, 0, 3, 6, edges);
        const inv = edges.m > 0 ? 1 / edges.m : 1;
        const [ax, ay, az] = [edges.e1x * inv, edges.e1y * inv, edges.e1z * inv];
        const [bx, by, bz] = [edges.e2x * inv, edges.e2y * inv, edges.e2z * inv];
        const cx = ay * bz - az * by;
        const cy = az * bx - ax * bz;
        const cz = ax * by - ay * bx;
        const len = Math.sqrt(cx * cx + cy * cy + cz * cz);
        expect([out.nx, out.ny, out.nz]).toEqual([cx / len, cy / len, cz / len]);
        expect(Math.hypot(out.nx, out.ny, out.nz)).toBeCloseTo(1, 12);
        checked++;
      }
    }
    expect(checked).toBe(81 * 20);
  });
});
