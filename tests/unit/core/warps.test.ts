/**
 * Sampling warps (src/core/sampling/warps.ts): each warp lands in its domain,
 * round-trips with its inverse, its pdf integrates to one over its domain
 * (numerical quadrature in spherical or polar coordinates), and its pdf is
 * the reciprocal of the warp's Jacobian determinant (finite differences), so
 * pdf and warp agree pointwise and not just on average.
 */
import { describe, expect, it } from 'vitest';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import {
  cosineHemisphereToSquare,
  squareToCosineHemisphere,
  squareToCosineHemispherePdf,
  squareToUniformCone,
  squareToUniformConePdf,
  squareToUniformDiskConcentric,
  squareToUniformDiskConcentricPdf,
  squareToUniformSphere,
  squareToUniformSpherePdf,
  uniformConeToSquare,
  uniformDiskConcentricToSquare,
  uniformSphereToSquare,
  type Vec2Out,
  type Vec3Out,
} from '../../../src/core/sampling/warps.ts';

const SEED = 0x5eed;
const N = 100_000;

/** Deterministic uniform number in [0, 1) for sample i, dimension d. */
function rand(i: number, d: number, seed = SEED): number {
  return hashToUnit(sampleKey(seed, i, 0), d);
}

/** Shortest signed difference of two angles, in (−π, π]. */
function angleDiff(a: number, b: number): number {
  let d = a - b;
  while (d > Math.PI) d -= 2 * Math.PI;
  while (d <= -Math.PI) d += 2 * Math.PI;
  return d;
}

/** A direction warp in the form the Jacobian test needs: u → (z, φ). */
type DirectionWarp = (u0: number, u1: number, out: Vec3Out) => void;

/**
 * |det ∂(z, φ)/∂(u0, u1)| by central differences: the solid-angle measure is
 * dω = dz dφ, so this must equal 1 / pdf(ω) for a warp of density pdf.
 */
function directionJacobian(warp: DirectionWarp, u0: number, u1: number, h: number): number {
  const p = { x: 0, y: 0, z: 0 };
  const m = { x: 0, y: 0, z: 0 };
  warp(u0 + h, u1, p);
  warp(u0 - h, u1, m);
  const dz0 = (p.z - m.z) / (2 * h);
  const dphi0 = angleDiff(Math.atan2(p.y, p.x), Math.atan2(m.y, m.x)) / (2 * h);
  warp(u0, u1 + h, p);
  warp(u0, u1 - h, m);
  const dz1 = (p.z - m.z) / (2 * h);
  const dphi1 = angleDiff(Math.atan2(p.y, p.x), Math.atan2(m.y, m.x)) / (2 * h);
  return Math.abs(dz0 * dphi1 - dz1 * dphi0);
}

/**
 * ∫ f(θ, φ) sinθ dθ dφ over θ ∈ [θ0, θ1], φ ∈ [0, 2π) by the midpoint rule
 * (error O(1/n²)); f gets the Cartesian direction.
 */
function integrateSphere(
  f: (x: number, y: number, z: number) => number,
  theta0: number,
  theta1: number,
  nTheta: number,
  nPhi: number,
): number {
  const dt = (theta1 - theta0) / nTheta;
  const dp = (2 * Math.PI) / nPhi;
  let sum = 0;
  for (let i = 0; i < nTheta; i++) {
    const t = theta0 + (i + 0.5) * dt;
    const st = Math.sin(t);
    const ct = Math.cos(t);
    let row = 0;
    for (let j = 0; j < nPhi; j++) {
      const p = (j + 0.5) * dp;
      row += f(st * Math.cos(p), st * Math.sin(p), ct);
    }
    sum += row * st;
  }
  return sum * dt * dp;
}

describe('squareToUniformDiskConcentric', () => {
  it('lands in the unit disk, including at the corners and edges of the square', () => {
    const d: Vec2Out = { x: 0, y: 0 };
    const edges = [0, 1e-12, 0.25, 0.5, 0.75, 1 - 1e-12, 1];
    for (const a of edges) {
      for (const b of edges) {
        squareToUniformDiskConcentric(a, b, d);
        expect(Number.isFinite(d.x) && Number.isFinite(d.y)).toBe(true);
        expect(d.x * d.x + d.y * d.y).toBeLessThanOrEqual(1 + 1e-15);
      }
    }
    let maxR2 = 0;
    for (let i = 0; i < N; i++) {
      squareToUniformDiskConcentric(rand(i, 0), rand(i, 1), d);
      maxR2 = Math.max(maxR2, d.x * d.x + d.y * d.y);
    }
    expect(maxR2).toBeLessThanOrEqual(1 + 1e-15);
    squareToUniformDiskConcentric(0.5, 0.5, d);
    expect([d.x, d.y]).toEqual([0, 0]);
  });

  it('round-trips with its inverse both ways (1e-9)', () => {
    const d: Vec2Out = { x: 0, y: 0 };
    const u: Vec2Out = { x: 0, y: 0 };
    let worst = 0;
    for (let i = 0; i < N; i++) {
      const u0 = rand(i, 0);
      const u1 = rand(i, 1);
      // The centre of the square is the one point where the inverse is undefined.
      if (Math.abs(u0 - 0.5) < 1e-9 && Math.abs(u1 - 0.5) < 1e-9) continue;
      squareToUniformDiskConcentric(u0, u1, d);
      uniformDiskConcentricToSquare(d.x, d.y, u);
      worst = Math.max(worst, Math.abs(u.x - u0), Math.abs(u.y - u1));
    }
    expect(worst).toBeLessThan(1e-9);
    // Disk → square → disk, from points uniform in the disk (by rejection).
    worst = 0;
    let outside = 0;
    for (let i = 0; i < N; i++) {
      const x = 2 * rand(i, 2) - 1;
      const y = 2 * rand(i, 3) - 1;
      if (x * x + y * y >= 1) continue;
      uniformDiskConcentricToSquare(x, y, u);
      if (!(u.x >= 0 && u.x <= 1 && u.y >= 0 && u.y <= 1)) outside++;
      squareToUniformDiskConcentric(u.x, u.y, d);
      worst = Math.max(worst, Math.abs(d.x - x), Math.abs(d.y - y));
    }
    expect(outside).toBe(0);
    expect(worst).toBeLessThan(1e-9);
  });

  it('round-trips exactly on the wedge seams (the diagonals and the axes)', () => {
    const d: Vec2Out = { x: 0, y: 0 };
    const u: Vec2Out = { x: 0, y: 0 };
    for (let k = 1; k < 100; k++) {
      const t = k / 100;
      for (const [u0, u1] of [
        [t, t],
        [t, 1 - t],
        [t, 0.5],
        [0.5, t],
      ]) {
        if (u0 === 0.5 && u1 === 0.5) continue;
        squareToUniformDiskConcentric(u0, u1, d);
        uniformDiskConcentricToSquare(d.x, d.y, u);
        expect(Math.abs(u.x - u0)).toBeLessThan(1e-9);
        expect(Math.abs(u.y - u1)).toBeLessThan(1e-9);
      }
    }
  });

  it('has a pdf that integrates to 1 over the disk (and is zero outside it)', () => {
    // Polar midpoint rule over r ∈ [0, 1.25] with r = 1 on a cell edge.
    const nr = 1250;
    const nphi = 256;
    const dr = 1.25 / nr;
    const dphi = (2 * Math.PI) / nphi;
    let sum = 0;
    for (let i = 0; i < nr; i++) {
      const r = (i + 0.5) * dr;
      for (let j = 0; j < nphi; j++) {
        const p = (j + 0.5) * dphi;
        sum += squareToUniformDiskConcentricPdf(r * Math.cos(p), r * Math.sin(p)) * r;
      }
    }
    expect(sum * dr * dphi).toBeCloseTo(1, 9);
    expect(squareToUniformDiskConcentricPdf(0.8, 0.8)).toBe(0);
  });

  it('is area-preserving: |det J| = 1 / pdf = π away from the seams', () => {
    const p: Vec2Out = { x: 0, y: 0 };
    const m: Vec2Out = { x: 0, y: 0 };
    const h = 1e-7;
    let checked = 0;
    for (let i = 0; i < 2000; i++) {
      const u0 = rand(i, 0);
      const u1 = rand(i, 1);
      const ox = 2 * u0 - 1;
      const oy = 2 * u1 - 1;
      if (Math.abs(Math.abs(ox) - Math.abs(oy)) < 1e-4 || Math.abs(ox) + Math.abs(oy) < 1e-3) {
        continue;
      }
      squareToUniformDiskConcentric(u0 + h, u1, p);
      squareToUniformDiskConcentric(u0 - h, u1, m);
      const dx0 = (p.x - m.x) / (2 * h);
      const dy0 = (p.y - m.y) / (2 * h);
      squareToUniformDiskConcentric(u0, u1 + h, p);
      squareToUniformDiskConcentric(u0, u1 - h, m);
      const dx1 = (p.x - m.x) / (2 * h);
      const dy1 = (p.y - m.y) / (2 * h);
      const det = Math.abs(dx0 * dy1 - dx1 * dy0);
      squareToUniformDiskConcentric(u0, u1, p);
      expect(det * squareToUniformDiskConcentricPdf(p.x, p.y)).toBeCloseTo(1, 5);
      checked++;
    }
    expect(checked).toBeGreaterThan(1900);
  });
});

describe('squareToCosineHemisphere', () => {
  it('lands on the unit upper hemisphere', () => {
    const w: Vec3Out = { x: 0, y: 0, z: 0 };
    let minZ = 1;
    let worstNorm = 0;
    for (let i = 0; i < N; i++) {
      squareToCosineHemisphere(rand(i, 0), rand(i, 1), w);
      minZ = Math.min(minZ, w.z);
      worstNorm = Math.max(worstNorm, Math.abs(Math.hypot(w.x, w.y, w.z) - 1));
    }
    expect(minZ).toBeGreaterThanOrEqual(0);
    expect(worstNorm).toBeLessThan(1e-12);
    for (const [a, b] of [
      [0, 0],
      [1, 1],
      [0, 1],
      [0.5, 0.5],
      [1, 0.5],
    ]) {
      squareToCosineHemisphere(a, b, w);
      expect(w.z).toBeGreaterThanOrEqual(0);
      expect(Math.abs(Math.hypot(w.x, w.y, w.z) - 1)).toBeLessThan(1e-12);
    }
  });

  it('round-trips with its inverse (1e-9)', () => {
    const w: Vec3Out = { x: 0, y: 0, z: 0 };
    const u: Vec2Out = { x: 0, y: 0 };
    let worst = 0;
    for (let i = 0; i < N; i++) {
      const u0 = rand(i, 0);
      const u1 = rand(i, 1);
      if (Math.abs(u0 - 0.5) < 1e-9 && Math.abs(u1 - 0.5) < 1e-9) continue;
      squareToCosineHemisphere(u0, u1, w);
      cosineHemisphereToSquare(w.x, w.y, u);
      worst = Math.max(worst, Math.abs(u.x - u0), Math.abs(u.y - u1));
    }
    expect(worst).toBeLessThan(1e-9);
  });

  it('has a pdf that integrates to 1 over the sphere (zero below the horizon)', () => {
    const f = (_x: number, _y: number, z: number): number => squareToCosineHemispherePdf(z);
    expect(integrateSphere(f, 0, Math.PI, 2000, 8)).toBeCloseTo(1, 6);
    expect(integrateSphere(f, Math.PI / 2, Math.PI, 100, 8)).toBe(0);
    expect(squareToCosineHemispherePdf(-0.5)).toBe(0);
  });

  it('has pdf = 1 / |det ∂(z,φ)/∂u| (cosine-weighted)', () => {
    const w: Vec3Out = { x: 0, y: 0, z: 0 };
    let checked = 0;
    for (let i = 0; i < 2000; i++) {
      const u0 = rand(i, 0);
      const u1 = rand(i, 1);
      const ox = 2 * u0 - 1;
      const oy = 2 * u1 - 1;
      // Away from the wedge seams, the centre and the rim (where dz/du → ∞).
      if (Math.abs(Math.abs(ox) - Math.abs(oy)) < 1e-3 || Math.abs(ox) + Math.abs(oy) < 1e-2) {
        continue;
      }
      if (Math.max(Math.abs(ox), Math.abs(oy)) > 0.99) continue;
      squareToCosineHemisphere(u0, u1, w);
      const det = directionJacobian(squareToCosineHemisphere, u0, u1, 1e-7);
      expect(det * squareToCosineHemispherePdf(w.z)).toBeCloseTo(1, 5);
      checked++;
    }
    expect(checked).toBeGreaterThan(1800);
  });
});

describe('squareToUniformSphere', () => {
  it('lands on the unit sphere', () => {
    const w: Vec3Out = { x: 0, y: 0, z: 0 };
    let worstNorm = 0;
    for (let i = 0; i < N; i++) {
      squareToUniformSphere(rand(i, 0), rand(i, 1), w);
      worstNorm = Math.max(worstNorm, Math.abs(Math.hypot(w.x, w.y, w.z) - 1));
    }
    expect(worstNorm).toBeLessThan(1e-12);
    for (const [a, b] of [
      [0, 0],
      [1, 1],
      [0.5, 0],
    ]) {
      squareToUniformSphere(a, b, w);
      expect(Math.abs(Math.hypot(w.x, w.y, w.z) - 1)).toBeLessThan(1e-12);
    }
  });

  it('round-trips with its inverse (1e-9), away from the poles and the φ = 0 seam', () => {
    const w: Vec3Out = { x: 0, y: 0, z: 0 };
    const u: Vec2Out = { x: 0, y: 0 };
    let worst = 0;
    for (let i = 0; i < N; i++) {
      const u0 = rand(i, 0);
      const u1 = rand(i, 1);
      if (u0 < 1e-9 || u0 > 1 - 1e-9 || u1 < 1e-9 || u1 > 1 - 1e-9) continue;
      squareToUniformSphere(u0, u1, w);
      uniformSphereToSquare(w.x, w.y, w.z, u);
      worst = Math.max(worst, Math.abs(u.x - u0), Math.abs(u.y - u1));
    }
    expect(worst).toBeLessThan(1e-9);
  });

  it('has a pdf that integrates to 1 and equals 1 / |det ∂(z,φ)/∂u|', () => {
    expect(integrateSphere(() => squareToUniformSpherePdf(), 0, Math.PI, 2000, 8)).toBeCloseTo(
      1,
      6,
    );
    for (let i = 0; i < 500; i++) {
      const u0 = 0.001 + 0.998 * rand(i, 0);
      const u1 = 0.001 + 0.998 * rand(i, 1);
      const det = directionJacobian(squareToUniformSphere, u0, u1, 1e-7);
      expect(det * squareToUniformSpherePdf()).toBeCloseTo(1, 6);
    }
  });
});

describe('squareToUniformCone', () => {
  const CONES = [-1, -0.5, 0, 0.3, 0.9, 0.999];
  // Cones so narrow that 1 − cosθmax is near the resolution of a double at 1.
  const NARROW = [1 - 1e-6, 1 - 1e-9, 1 - 1e-12, 1 - 2 ** -50];

  it('lands in the cone, on the unit sphere, for wide and very narrow cones', () => {
    const w: Vec3Out = { x: 0, y: 0, z: 0 };
    for (const c of [...CONES, ...NARROW]) {
      let minZ = 1;
      let maxZ = -1;
      let worstNorm = 0;
      for (let i = 0; i < 20_000; i++) {
        squareToUniformCone(rand(i, 0), rand(i, 1), c, w);
        minZ = Math.min(minZ, w.z);
        maxZ = Math.max(maxZ, w.z);
        worstNorm = Math.max(worstNorm, Math.abs(Math.hypot(w.x, w.y, w.z) - 1));
      }
      expect(minZ).toBeGreaterThanOrEqual(c);
      expect(maxZ).toBeLessThanOrEqual(1);
      expect(worstNorm).toBeLessThan(1e-12);
      for (const [a, b] of [
        [0, 0],
        [1, 0.25],
      ]) {
        squareToUniformCone(a, b, c, w);
        expect(w.z).toBeGreaterThanOrEqual(c);
        expect(Math.abs(Math.hypot(w.x, w.y, w.z) - 1)).toBeLessThan(1e-12);
      }
      expect(Number.isFinite(squareToUniformConePdf(c))).toBe(true);
      expect(squareToUniformConePdf(c)).toBeGreaterThan(0);
    }
  });

  it('round-trips with its inverse (1e-9; narrow cones lose what 1 − z can resolve)', () => {
    const w: Vec3Out = { x: 0, y: 0, z: 0 };
    const u: Vec2Out = { x: 0, y: 0 };
    for (const c of [...CONES, ...NARROW]) {
      // u0 is recovered from 1 − z, whose rounding (≈ ε at z ≈ 1) is amplified
      // by 1 / (1 − cosθmax): for 1 − 1e-6 that is still below 1e-9.
      const tol0 = 1e-9 + (2 * Number.EPSILON) / (1 - c);
      let worst0 = 0;
      let worst1 = 0;
      for (let i = 0; i < 20_000; i++) {
        const u0 = rand(i, 0);
        const u1 = rand(i, 1);
        if (u0 < 1e-6 || u1 < 1e-9 || u1 > 1 - 1e-9) continue;
        squareToUniformCone(u0, u1, c, w);
        uniformConeToSquare(w.x, w.y, w.z, c, u);
        worst0 = Math.max(worst0, Math.abs(u.x - u0));
        // A narrow cone rounds cosθ to exactly 1 for the smallest u0: the
        // sample is then the axis itself, whose φ is undefined.
        if (w.x !== 0 || w.y !== 0) worst1 = Math.max(worst1, Math.abs(u.y - u1));
      }
      expect(worst0).toBeLessThan(tol0);
      expect(worst1).toBeLessThan(1e-9);
    }
  });

  it('has a pdf that integrates to 1 over the cone', () => {
    for (const c of [...CONES, ...NARROW]) {
      const pdf = squareToUniformConePdf(c);
      const integral = integrateSphere(() => pdf, 0, Math.acos(c), 1000, 4);
      expect(integral).toBeCloseTo(1, 5);
    }
  });

  it('has pdf = 1 / |det ∂(z,φ)/∂u| for cones that finite differences resolve', () => {
    for (const c of CONES) {
      for (let i = 0; i < 200; i++) {
        const u0 = 0.001 + 0.998 * rand(i, 0);
        const u1 = 0.001 + 0.998 * rand(i, 1);
        const det = directionJacobian(
          (a, b, out) => squareToUniformCone(a, b, c, out),
          u0,
          u1,
          1e-6,
        );
        expect(det * squareToUniformConePdf(c)).toBeCloseTo(1, 6);
      }
    }
  });

  it('is the whole sphere for cosθmax = −1 and the hemisphere for 0', () => {
    expect(squareToUniformConePdf(-1)).toBeCloseTo(squareToUniformSpherePdf(), 15);
    expect(squareToUniformConePdf(0)).toBeCloseTo(1 / (2 * Math.PI), 15);
    const a: Vec3Out = { x: 0, y: 0, z: 0 };
    const b: Vec3Out = { x: 0, y: 0, z: 0 };
    for (let i = 0; i < 1000; i++) {
      const u0 = rand(i, 0);
      const u1 = rand(i, 1);
      squareToUniformCone(u0, u1, -1, a);
      squareToUniformSphere(u0, u1, b);
      expect(Math.abs(a.x - b.x) + Math.abs(a.y - b.y) + Math.abs(a.z - b.z)).toBeLessThan(1e-12);
    }
  });
});
