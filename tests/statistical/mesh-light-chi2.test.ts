/**
 * Sampling an emissive mesh by area: the triangle warp's three faces (sample, pdf,
 * inverse) agree, and a χ² test of where the points land against the exact expected
 * counts, over a mesh of triangles of very different sizes, each cut into k² congruent
 * sub-triangles (equal areas) by its barycentric coordinates.
 *
 * Fixed seeds; rejection at p < 0.01 / (number of χ² tests).
 */
import { describe, expect, it } from 'vitest';
import { MeshLight, MeshLightSample, triangleArea } from '../../src/core/lights/mesh-light.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import {
  squareToUniformTriangle,
  squareToUniformTrianglePdf,
  uniformTriangleToSquare,
} from '../../src/core/sampling/warps.ts';
import { chi2Test } from '../helpers/chi2.ts';
import { icosphere } from '../helpers/mesh-gen.ts';

describe('uniform triangle warp', () => {
  it('inverts, stays inside the triangle, and has density 2 over it', () => {
    const b = { x: 0, y: 0 };
    const u = { x: 0, y: 0 };
    for (let i = 0; i < 10_000; i++) {
      const key = sampleKey(4, i, 0);
      const u0 = hashToUnit(key, 0);
      const u1 = hashToUnit(key, 1);
      squareToUniformTriangle(u0, u1, b);
      if (!(b.x >= 0 && b.y >= 0 && b.x + b.y <= 1)) expect.fail(`outside at ${u0}, ${u1}`);
      uniformTriangleToSquare(b.x, b.y, u);
      if (Math.abs(u.x - u0) > 1e-15 || Math.abs(u.y - u1) > 1e-15) {
        expect.fail(`inverse of (${u0}, ${u1}) is (${u.x}, ${u.y})`);
      }
    }
    expect(squareToUniformTrianglePdf(0.2, 0.3)).toBe(2);
    expect(squareToUniformTrianglePdf(0.7, 0.4)).toBe(0);
  });
});

/** Sub-triangle index (0 … k² − 1) of the point with barycentrics (b1, b2). */
function subCell(b1: number, b2: number, k: number): number {
  const x = b1 * k;
  const y = b2 * k;
  const i = Math.min(k - 1, Math.floor(x));
  const j = Math.min(k - 1 - i, Math.floor(y));
  const up = x - i + (y - j) < 1 || i + j === k - 1;
  // Row j has 2(k − j) − 1 cells; index them row by row.
  let index = 0;
  for (let r = 0; r < j; r++) index += 2 * (k - r) - 1;
  return index + 2 * i + (up ? 0 : 1);
}

/** Barycentrics (b1, b2) of point p in triangle t (by least squares on two edges). */
function barycentrics(
  m: MeshLight,
  t: number,
  px: number,
  py: number,
  pz: number,
): [number, number] {
  const p = m.positions;
  const [a, b, c] = [0, 1, 2].map((k) => m.indices[3 * t + k] * 3);
  const e1 = [0, 1, 2].map((k) => p[b + k] - p[a + k]);
  const e2 = [0, 1, 2].map((k) => p[c + k] - p[a + k]);
  const q = [px - p[a], py - p[a + 1], pz - p[a + 2]];
  const dot = (x: number[], y: number[]) => x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  const d11 = dot(e1, e1),
    d12 = dot(e1, e2),
    d22 = dot(e2, e2);
  const q1 = dot(q, e1),
    q2 = dot(q, e2);
  const det = d11 * d22 - d12 * d12;
  return [(d22 * q1 - d12 * q2) / det, (d11 * q2 - d12 * q1) / det];
}

const CASES: [string, Float64Array, Uint32Array][] = [
  (() => {
    // A big, a middling and a tiny triangle, not touching, areas 8 : 0.5 : 0.02.
    const positions = new Float64Array([
      0, 0, 0, 4, 0, 0, 0, 4, 0, 10, 0, 0, 11, 0, 0, 10, 0, 1, -3, 2, 1, -3, 2.2, 1, -3, 2, 1.2,
    ]);
    return [
      'three triangles of very different sizes',
      positions,
      new Uint32Array([0, 1, 2, 3, 4, 5, 6, 7, 8]),
    ];
  })() as [string, Float64Array, Uint32Array],
  (() => {
    const s = icosphere(1, 2, [1, 2, 3]);
    return ['an icosphere', s.positions, s.indices];
  })() as [string, Float64Array, Uint32Array],
];

describe('emissive mesh sampling by area: χ²', () => {
  const alpha = 0.01 / CASES.length;
  it.each(CASES)('%s', (_, positions, indices) => {
    const count = indices.length / 3;
    // The light is the whole index array here; `first` is exercised by an offset copy.
    const light = new MeshLight(positions, indices, 0, count);
    const k = 4;
    const cells = k * k;
    const n = 100_000;
    const observed = new Float64Array(count * cells);
    const s = new MeshLightSample();
    let off = 0;
    for (let i = 0; i < n; i++) {
      const key = sampleKey(21, i, 0);
      light.sample(hashToUnit(key, 0), hashToUnit(key, 1), s);
      const [b1, b2] = barycentrics(light, s.triangle, s.px, s.py, s.pz);
      if (b1 < -1e-9 || b2 < -1e-9 || b1 + b2 > 1 + 1e-9) off++;
      observed[s.triangle * cells + subCell(Math.max(0, b1), Math.max(0, b2), k)]++;
    }
    expect(off).toBe(0);
    const expected = new Float64Array(count * cells);
    for (let t = 0; t < count; t++) {
      const a = triangleArea(positions, indices, t);
      for (let c = 0; c < cells; c++) expected[t * cells + c] = (n * a) / light.area / cells;
    }
    const result = chi2Test(observed, expected);
    expect(result.impossible).toBeNull();
    expect(result.pValue, `χ² = ${result.stat.toFixed(1)} on ${result.dof} dof`).toBeGreaterThan(
      alpha,
    );
  });

  it('samples only its own triangles, gives unit normals along the winding, and inverts', () => {
    const sphere = icosphere(1);
    // Two meshes in one index array: the light is the second.
    const indices = new Uint32Array([...sphere.indices, ...sphere.indices.map((i) => i)]);
    const first = sphere.indices.length / 3;
    const light = new MeshLight(sphere.positions, indices, first, first);
    expect(light.area).toBeCloseTo(
      Array.from({ length: first }, (_, t) =>
        triangleArea(sphere.positions, sphere.indices, t),
      ).reduce((a, b) => a + b),
      12,
    );
    const s = new MeshLightSample();
    const back = { x: 0, y: 0 };
    for (let i = 0; i < 2000; i++) {
      const key = sampleKey(8, i, 0);
      const u0 = hashToUnit(key, 0);
      const u1 = hashToUnit(key, 1);
      light.sample(u0, u1, s);
      expect(s.triangle).toBeGreaterThanOrEqual(first);
      // Outward winding: the normal points away from the centre.
      expect(s.nx * s.px + s.ny * s.py + s.nz * s.pz).toBeGreaterThan(0);
      expect(Math.hypot(s.nx, s.ny, s.nz)).toBeCloseTo(1, 14);
      const [b1, b2] = barycentrics(light, s.triangle, s.px, s.py, s.pz);
      light.invert(s.triangle, 1 - b1 - b2, b1, back);
      expect(Math.abs(back.x - u0)).toBeLessThan(1e-9);
      expect(Math.abs(back.y - u1)).toBeLessThan(1e-9);
    }
    expect(light.pdfArea()).toBe(1 / light.area);
  });

  it('refuses a mesh of zero area', () => {
    const p = new Float64Array([0, 0, 0, 1, 0, 0, 2, 0, 0]);
    expect(() => new MeshLight(p, new Uint32Array([0, 1, 2]), 0, 1)).toThrow(/non-zero area/);
  });
});
