/**
 * Hard cases of the BSDFs: the smooth dielectric (exact Fresnel, Snell's law,
 * total internal reflection, the (n1/n2)² radiance rule) and the conductor at
 * its two extremes, roughness 0 (a Schlick mirror) and roughness 1.
 *
 * Dielectric frame: +z is the outward geometric normal (outside index 1,
 * inside index `ior`); wo.z < 0 means the path arrives from inside.
 */
import { describe, expect, it } from 'vitest';
import { bsdfEval, bsdfPdf, bsdfSample } from '../../helpers/bsdf-calls.ts';
import { fresnelDielectric } from '../../../src/core/bsdf/fresnel.ts';
import { compileMaterials, M_DELTA, MATERIAL_STRIDE } from '../../../src/core/bsdf/materials.ts';
import { BsdfSample, BsdfValue } from '../../../src/core/bsdf/records.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import type { MaterialDesc, Vec3 } from '../../../src/core/scene/format/types.ts';

const BLACK: Vec3 = [0, 0, 0];
const TINT: Vec3 = [0.9, 0.75, 0.5];
const IORS = [1.5, 1.33, 2.4, 0.75, 1];
const MIRROR_F0: Vec3 = [0.95, 0.64, 0.04];
const ROUGH_F0: Vec3 = [0, 0.5, 1];

const DESCS: MaterialDesc[] = [
  ...IORS.map((ior): MaterialDesc => ({
    type: 'dielectric',
    ior,
    color: TINT,
    roughness: 0,
    emission: BLACK,
  })),
  { type: 'conductor', color: MIRROR_F0, roughness: 0, emission: BLACK },
  { type: 'conductor', color: ROUGH_F0, roughness: 1, emission: BLACK },
];
const MATERIALS = compileMaterials(DESCS);
const GLASS = (ior: number): number => IORS.indexOf(ior);
const MIRROR = IORS.length;
const ROUGH = IORS.length + 1;

function rand(seed: number, i: number, d: number): number {
  return hashToUnit(sampleKey(seed, i, 0), d);
}

/** Direction with cosine `c` to +z (c < 0: below), azimuth φ. */
function dir(c: number, phi: number): [number, number, number] {
  const s = Math.sqrt(Math.max(0, 1 - c * c));
  return [s * Math.cos(phi), s * Math.sin(phi), c];
}

function relErr(a: number, b: number): number {
  const m = Math.max(Math.abs(a), Math.abs(b));
  return m === 0 ? 0 : Math.abs(a - b) / m;
}

/**
 * Unpolarised Fresnel reflectance from the angles, written independently of
 * the implementation: Rs = sin²(θi − θt) / sin²(θi + θt), Rp = tan²(θi − θt) /
 * tan²(θi + θt) (Born & Wolf), light going from index n1 into n2.
 */
function fresnelReference(cosI: number, n1: number, n2: number): number {
  const sinT = (n1 / n2) * Math.sqrt(1 - cosI * cosI);
  if (sinT >= 1) return 1;
  const ti = Math.acos(cosI);
  const tt = Math.asin(sinT);
  if (ti === 0) return ((n1 - n2) / (n1 + n2)) ** 2;
  const rs = Math.sin(ti - tt) ** 2 / Math.sin(ti + tt) ** 2;
  const rp = Math.tan(ti - tt) ** 2 / Math.tan(ti + tt) ** 2;
  return 0.5 * (rs + rp);
}

/** Samples the glass with lobe choice u and returns a copy of the record. */
function sampleGlass(ior: number, w: [number, number, number], u: number): BsdfSample {
  const s = new BsdfSample();
  if (!bsdfSample(MATERIALS, GLASS(ior), w[0], w[1], w[2], 0.5, 0.5, u, s)) {
    throw new Error(`the dielectric refused wo = ${w}`);
  }
  return s;
}

/** Just below 1: the largest u a sampler sees from a 32-bit hash. */
const U_MAX = 1 - 2 ** -32;

describe('fresnelDielectric', () => {
  it('matches the textbook Fresnel equations on both sides of the boundary', () => {
    // (Not for ior ≈ 1: there the reference's sin(θi − θt) is the inaccurate one.)
    for (const ior of [1.5, 1.33, 2.4, 0.75, 1.1]) {
      for (let i = 1; i <= 200; i++) {
        const c = i / 200;
        // From outside (n1 = 1, eta = ior) and from inside (n1 = ior, eta = 1/ior).
        expect(Math.abs(fresnelDielectric(c, ior) - fresnelReference(c, 1, ior))).toBeLessThan(
          1e-13,
        );
        expect(Math.abs(fresnelDielectric(c, 1 / ior) - fresnelReference(c, ior, 1))).toBeLessThan(
          1e-13,
        );
      }
    }
  });

  it('at normal incidence is ((n − 1)/(n + 1))², from either side', () => {
    for (const n of [1.5, 1.33, 2.4, 0.75, 1.0001, 4]) {
      const f0 = ((n - 1) / (n + 1)) ** 2;
      // Rounding 1/n costs ε/|n − 1| relative in n − 1, hence in F, from inside.
      const tol = 1e-14 + (4 * Number.EPSILON) / Math.abs(n - 1);
      expect(relErr(fresnelDielectric(1, n), f0)).toBeLessThan(tol);
      expect(relErr(fresnelDielectric(1, 1 / n), f0)).toBeLessThan(tol);
      // And what the sampler reports as the probability of reflection.
      expect(relErr(sampleGlassPdf(n, [0, 0, 1], 0), f0)).toBeLessThan(tol);
      expect(relErr(sampleGlassPdf(n, [0, 0, -1], 0), f0)).toBeLessThan(tol);
    }
  });

  it('is zero for an index-matched boundary (eta = 1), at every angle', () => {
    for (const c of [1, 0.9, 0.5, 0.3, 0.1, 1e-3, 1e-6, 1e-8, 1e-9, 1e-12, 1e-300]) {
      expect(fresnelDielectric(c, 1)).toBe(0);
    }
    for (let i = 0; i < 10_000; i++) expect(fresnelDielectric(rand(1, i, 0), 1)).toBe(0);
  });

  it('is 1 at grazing incidence and reciprocal across the boundary (F(θ1) = F(θ2))', () => {
    for (const ior of [1.5, 2.4, 0.75]) {
      expect(fresnelDielectric(0, ior)).toBe(1);
      for (let i = 1; i < 100; i++) {
        const cosI = i / 100;
        const sinT = Math.sqrt(1 - cosI * cosI) / ior;
        if (sinT >= 1) continue;
        const cosT = Math.sqrt(1 - sinT * sinT);
        expect(
          Math.abs(fresnelDielectric(cosI, ior) - fresnelDielectric(cosT, 1 / ior)),
        ).toBeLessThan(1e-13);
      }
    }
  });
});

function sampleGlassPdf(ior: number, w: [number, number, number], u: number): number {
  const s = new BsdfSample();
  const m = compileMaterials([
    { type: 'dielectric', ior, color: TINT, roughness: 0, emission: BLACK },
  ]);
  bsdfSample(m, 0, w[0], w[1], w[2], 0.5, 0.5, u, s);
  return s.pdf;
}

describe('smooth dielectric: choice of lobe', () => {
  it('reflects with probability F exactly: u < F reflects, u ≥ F refracts, pdf = F or 1 − F', () => {
    for (const ior of IORS) {
      for (const side of [1, -1]) {
        const eta = side > 0 ? ior : 1 / ior;
        for (let i = 1; i <= 50; i++) {
          const c = i / 50;
          const w = dir(side * c, 0.4 + i);
          const f = fresnelDielectric(c, eta);
          if (f > 0) {
            const r = sampleGlass(ior, w, f * (1 - 1e-12));
            expect(r.wz * side).toBeGreaterThan(0);
            expect(r.pdf).toBe(f);
            expect([r.wx, r.wy, r.wz]).toEqual([-w[0], -w[1], w[2]]);
            expect([r.weightR, r.weightG, r.weightB]).toEqual([1, 1, 1]);
            expect(r.isDelta).toBe(true);
            expect(r.etaScale).toBe(1);
          }
          if (f < 1) {
            const t = sampleGlass(ior, w, Math.max(f, 0));
            expect(t.wz * side).toBeLessThan(0);
            expect(t.pdf).toBe(1 - f);
            expect(t.isDelta).toBe(true);
          }
        }
      }
    }
  });

  it('has a sampled frequency of reflection equal to F (binomial, 5σ)', () => {
    const n = 20_000;
    const s = new BsdfSample();
    for (const ior of [1.5, 2.4, 0.75]) {
      for (const side of [1, -1]) {
        const eta = side > 0 ? ior : 1 / ior;
        for (const c of [1, 0.8, 0.5, 0.2, 0.05]) {
          const f = fresnelDielectric(c, eta);
          const w = dir(side * c, 1.3);
          let reflected = 0;
          for (let i = 0; i < n; i++) {
            bsdfSample(MATERIALS, GLASS(ior), w[0], w[1], w[2], 0, 0, rand(17 + c, i, 2), s);
            if (s.wz * side > 0) reflected++;
          }
          const sigma = Math.sqrt(n * f * (1 - f));
          expect(Math.abs(reflected - n * f)).toBeLessThanOrEqual(5 * sigma + 1);
        }
      }
    }
  });
});

describe('smooth dielectric: refraction', () => {
  it("obeys Snell's law (n1 sinθ1 = n2 sinθ2, 1e-12), in the plane of incidence, unit length", () => {
    let worstSnell = 0;
    let worstNorm = 0;
    let worstPlane = 0;
    let refracted = 0;
    for (const ior of IORS) {
      for (let i = 0; i < 20_000; i++) {
        const side = i % 2 === 0 ? 1 : -1;
        // Cosines from 1 down to 1e-6, half of them near grazing.
        const c = i % 4 < 2 ? rand(20, i, 0) : 1e-6 + 0.05 * rand(20, i, 0);
        const w = dir(side * Math.max(c, 1e-6), 2 * Math.PI * rand(20, i, 1));
        const t = sampleGlass(ior, w, U_MAX);
        const n1 = side > 0 ? 1 : ior;
        const n2 = side > 0 ? ior : 1;
        if (t.wz * side > 0) {
          // Only total internal reflection (from the denser side) may reflect at u → 1.
          expect(n1).toBeGreaterThan(n2);
          expect(n1 * Math.hypot(w[0], w[1])).toBeGreaterThanOrEqual(n2 * (1 - 1e-12));
          continue;
        }
        refracted++;
        const sin1 = Math.hypot(w[0], w[1]);
        const sin2 = Math.hypot(t.wx, t.wy);
        worstSnell = Math.max(worstSnell, Math.abs(n1 * sin1 - n2 * sin2));
        worstNorm = Math.max(worstNorm, Math.abs(Math.hypot(t.wx, t.wy, t.wz) - 1));
        // The tangential part is antiparallel to wo's: zero cross product, negative dot.
        const cross = w[0] * t.wy - w[1] * t.wx;
        const dot = w[0] * t.wx + w[1] * t.wy;
        worstPlane = Math.max(worstPlane, Math.abs(cross), dot > 0 ? dot : 0);
      }
    }
    expect(refracted).toBeGreaterThan(60_000);
    expect(worstSnell).toBeLessThan(1e-12);
    expect(worstNorm).toBeLessThan(1e-12);
    expect(worstPlane).toBeLessThan(1e-12);
  });

  it('passes straight through at normal incidence and through an index-matched boundary', () => {
    for (const ior of IORS) {
      for (const side of [1, -1]) {
        const t = sampleGlass(ior, [0, 0, side], U_MAX);
        expect(Math.abs(t.wx) + Math.abs(t.wy)).toBe(0);
        expect(t.wz).toBe(-side);
      }
    }
    for (let i = 0; i < 1000; i++) {
      const side = i % 2 === 0 ? 1 : -1;
      const w = dir(side * (0.01 + 0.99 * rand(30, i, 0)), 6 * rand(30, i, 1));
      const t = sampleGlass(1, w, rand(30, i, 2));
      expect(t.pdf).toBe(1);
      expect(Math.abs(t.wx + w[0]) + Math.abs(t.wy + w[1]) + Math.abs(t.wz + w[2])).toBeLessThan(
        1e-12,
      );
      expect([t.weightR, t.weightG, t.weightB]).toEqual(TINT);
    }
  });

  it('is reversible: refracting the refracted direction back returns wo (1e-12)', () => {
    for (const ior of IORS) {
      for (let i = 0; i < 2000; i++) {
        const side = i % 2 === 0 ? 1 : -1;
        const w = dir(side * (0.02 + 0.98 * rand(40, i, 0)), 6.28 * rand(40, i, 1));
        const t = sampleGlass(ior, w, U_MAX);
        if (t.wz * side > 0) continue; // total internal reflection
        const back = sampleGlass(ior, [t.wx, t.wy, t.wz], U_MAX);
        expect(back.wz * side).toBeGreaterThan(0);
        expect(
          Math.abs(back.wx - w[0]) + Math.abs(back.wy - w[1]) + Math.abs(back.wz - w[2]),
        ).toBeLessThan(1e-12);
        // The same Fresnel reflectance on both sides.
        expect(Math.abs(t.pdf - back.pdf)).toBeLessThan(1e-13);
      }
    }
  });

  it('carries color·(n1/n2)² in radiance, entering and leaving, so a round trip is color²', () => {
    for (const ior of IORS) {
      const w = dir(0.7, 0.3);
      const enter = sampleGlass(ior, w, U_MAX);
      const scaleIn = 1 / (ior * ior);
      expect(relErr(enter.weightR, TINT[0] * scaleIn)).toBeLessThan(1e-14);
      expect(relErr(enter.weightG, TINT[1] * scaleIn)).toBeLessThan(1e-14);
      expect(relErr(enter.weightB, TINT[2] * scaleIn)).toBeLessThan(1e-14);
      expect(relErr(enter.etaScale, ior * ior)).toBeLessThan(1e-14);
      // Leave through the same boundary along the refracted direction.
      const leave = sampleGlass(ior, [enter.wx, enter.wy, enter.wz], U_MAX);
      expect(leave.wz).toBeGreaterThan(0);
      const scaleOut = ior * ior;
      expect(relErr(leave.weightR, TINT[0] * scaleOut)).toBeLessThan(1e-14);
      expect(relErr(leave.etaScale, 1 / (ior * ior))).toBeLessThan(1e-14);
      expect(relErr(enter.weightR * leave.weightR, TINT[0] ** 2)).toBeLessThan(1e-14);
      expect(relErr(enter.weightG * leave.weightG, TINT[1] ** 2)).toBeLessThan(1e-14);
      expect(relErr(enter.weightB * leave.weightB, TINT[2] ** 2)).toBeLessThan(1e-14);
      expect(relErr(enter.etaScale * leave.etaScale, 1)).toBeLessThan(1e-14);
    }
  });

  it('has zero eval and pdf (both lobes are Dirac deltas) and is flagged delta', () => {
    const f = new BsdfValue();
    for (const ior of IORS) {
      const m = GLASS(ior);
      expect(MATERIALS[m * MATERIAL_STRIDE + M_DELTA]).toBe(1);
      bsdfEval(MATERIALS, m, 0.6, 0, 0.8, -0.6, 0, 0.8, f);
      expect([f.r, f.g, f.b]).toEqual([0, 0, 0]);
      expect(bsdfPdf(MATERIALS, m, 0.6, 0, 0.8, -0.6, 0, 0.8)).toBe(0);
    }
  });
});

describe('smooth dielectric: total internal reflection', () => {
  it('reflects with probability 1 beyond the critical angle (from inside; from outside if ior < 1)', () => {
    for (const ior of [1.5, 1.33, 2.4, 0.75]) {
      // The denser side is the inside for ior > 1 and the outside for ior < 1.
      const side = ior > 1 ? -1 : 1;
      const ratio = ior > 1 ? 1 / ior : ior;
      const cosCritical = Math.sqrt(1 - ratio * ratio);
      for (let i = 0; i < 500; i++) {
        // Strictly beyond the critical angle, down to grazing.
        const c = cosCritical * (1 - 1e-9) * rand(50, i, 0);
        const w = dir(side * c, 6.28 * rand(50, i, 1));
        expect(fresnelDielectric(c, ior > 1 ? 1 / ior : ior)).toBe(1);
        for (const u of [0, 0.5, rand(50, i, 2), U_MAX]) {
          const s = sampleGlass(ior, w, u);
          expect(s.wz * side).toBeGreaterThan(0);
          expect([s.wx, s.wy, s.wz]).toEqual([-w[0], -w[1], w[2]]);
          expect(s.pdf).toBe(1);
          expect([s.weightR, s.weightG, s.weightB]).toEqual([1, 1, 1]);
          expect(s.etaScale).toBe(1);
        }
      }
      // Just inside the critical angle refraction exists and leaves near grazing.
      const c = cosCritical * (1 + 1e-6);
      const w = dir(side * c, 0.1);
      const t = sampleGlass(ior, w, U_MAX);
      expect(t.wz * side).toBeLessThan(0);
      expect(Math.abs(t.wz)).toBeLessThan(0.01);
      expect(Math.abs(Math.hypot(t.wx, t.wy, t.wz) - 1)).toBeLessThan(1e-12);
    }
  });

  it('always can refract from the rarer side (ior > 1 from outside), even at grazing', () => {
    for (const ior of [1.5, 2.4]) {
      for (const c of [1e-3, 1e-6, 1e-9, 1e-12]) {
        const w = dir(c, 0.2);
        const f = fresnelDielectric(c, ior);
        expect(f).toBeLessThan(1);
        expect(f).toBeGreaterThan(0.99);
        const t = sampleGlass(ior, w, f);
        expect(t.wz).toBeLessThan(0);
        expect(Math.abs(Math.hypot(t.wx, t.wy, t.wz) - 1)).toBeLessThan(1e-12);
        // Refracted at (at most) the critical angle.
        expect(Math.hypot(t.wx, t.wy)).toBeLessThanOrEqual(1 / ior + 1e-12);
      }
    }
  });
});

describe('conductor, roughness 0: a Schlick mirror', () => {
  it('reflects exactly, isDelta, pdf 1, weight Schlick(F0, cosθo) per channel', () => {
    const s = new BsdfSample();
    const f = new BsdfValue();
    expect(MATERIALS[MIRROR * MATERIAL_STRIDE + M_DELTA]).toBe(1);
    for (let i = 0; i < 5000; i++) {
      const c = i % 5 === 0 ? 1e-9 * (1 + rand(60, i, 0)) : rand(60, i, 0) || 1;
      const w = dir(c, 6.28 * rand(60, i, 1));
      const ok = bsdfSample(
        MATERIALS,
        MIRROR,
        w[0],
        w[1],
        w[2],
        rand(61, i, 0),
        rand(61, i, 1),
        0,
        s,
      );
      expect(ok).toBe(true);
      expect(s.isDelta).toBe(true);
      expect(s.pdf).toBe(1);
      expect(s.etaScale).toBe(1);
      expect([s.wx, s.wy, s.wz]).toEqual([-w[0], -w[1], w[2]]);
      const weights = [s.weightR, s.weightG, s.weightB];
      MIRROR_F0.forEach((f0, k) => {
        const schlick = f0 + (1 - f0) * Math.pow(1 - c, 5);
        expect(relErr(weights[k], schlick)).toBeLessThan(1e-12);
        expect(weights[k]).toBeLessThanOrEqual(1);
      });
      // A delta lobe: eval and pdf of any direction, the mirror one included, are zero.
      bsdfEval(MATERIALS, MIRROR, w[0], w[1], w[2], -w[0], -w[1], w[2], f);
      expect(f.r + f.g + f.b).toBe(0);
      expect(bsdfPdf(MATERIALS, MIRROR, w[0], w[1], w[2], -w[0], -w[1], w[2])).toBe(0);
    }
    // At normal incidence the weight is F0 exactly.
    bsdfSample(MATERIALS, MIRROR, 0, 0, 1, 0.5, 0.5, 0, s);
    expect([s.weightR, s.weightG, s.weightB]).toEqual(MIRROR_F0);
    expect([s.wx, s.wy, s.wz]).toEqual([-0, -0, 1]);
    // From below the shading hemisphere there is nothing to reflect.
    expect(bsdfSample(MATERIALS, MIRROR, 0.6, 0, -0.8, 0.5, 0.5, 0, s)).toBe(false);
  });
});

describe('conductor, roughness 1 (α = 1)', () => {
  it('has weights finite and in [0, 1] for F0 in {0, 0.5, 1}, grazing wo included', () => {
    const s = new BsdfSample();
    let lowest = Infinity;
    let highest = -Infinity;
    let accepted = 0;
    let bad = 0;
    const us = [0, 1e-12, 0.5, U_MAX];
    for (let i = 0; i < 30_000; i++) {
      const c = i % 3 === 0 ? 10 ** (-12 * rand(70, i, 0)) : rand(70, i, 0) || 1;
      const w = dir(c, 6.28 * rand(70, i, 1));
      const u0 = i < 16 ? us[i % 4] : rand(71, i, 0);
      const u1 = i < 16 ? us[(i >> 2) % 4] : rand(71, i, 1);
      if (!bsdfSample(MATERIALS, ROUGH, w[0], w[1], w[2], u0, u1, 0, s)) continue;
      accepted++;
      for (const v of [s.weightR, s.weightG, s.weightB]) {
        if (!Number.isFinite(v)) bad++;
        lowest = Math.min(lowest, v);
        highest = Math.max(highest, v);
      }
      if (!(Number.isFinite(s.pdf) && s.pdf > 0) || s.isDelta) bad++;
      if (!(s.wz > 0) || Math.abs(Math.hypot(s.wx, s.wy, s.wz) - 1) > 1e-12) bad++;
    }
    expect(bad).toBe(0);
    expect(accepted).toBeGreaterThan(15_000);
    expect(lowest).toBeGreaterThanOrEqual(0);
    expect(highest).toBeLessThanOrEqual(1);
  });

  it('has the closed forms of α = 1: D = 1/π, pdf = 1 / (2π(1 + cosθo)) over the hemisphere', () => {
    const f = new BsdfValue();
    for (let i = 0; i < 5000; i++) {
      const wo = dir(i % 4 === 0 ? 1e-9 + 0.01 * rand(80, i, 0) : rand(80, i, 0) || 1, 1);
      const wi = dir(rand(81, i, 0) || 1, 6.28 * rand(81, i, 1));
      const p = bsdfPdf(MATERIALS, ROUGH, wo[0], wo[1], wo[2], wi[0], wi[1], wi[2]);
      expect(relErr(p, 1 / (2 * Math.PI * (1 + wo[2])))).toBeLessThan(1e-12);
      bsdfEval(MATERIALS, ROUGH, wo[0], wo[1], wo[2], wi[0], wi[1], wi[2], f);
      // f = D·G1(wo)·G1(wi)·F / (4 cosθo cosθi), G1(z) = 2z / (1 + z) at α = 1.
      const common = 1 / (Math.PI * (1 + wo[2]) * (1 + wi[2]));
      expect(f.r).toBeGreaterThanOrEqual(0);
      expect(f.r).toBeLessThanOrEqual(common * (1 + 1e-12));
      expect(relErr(f.b, common)).toBeLessThan(1e-12); // F0 = 1: F = 1
      expect(Number.isFinite(f.g)).toBe(true);
    }
  });

  it('refuses (returns false) a fraction cosθo / (1 + cosθo) of samples, those below the horizon', () => {
    const s = new BsdfSample();
    const n = 20_000;
    for (const c of [1, 0.7, 0.2, 0.01]) {
      const w = dir(c, 2);
      let refused = 0;
      for (let i = 0; i < n; i++) {
        if (!bsdfSample(MATERIALS, ROUGH, w[0], w[1], w[2], rand(90, i, 0), rand(90, i, 1), 0, s)) {
          refused++;
        }
      }
      const p = c / (1 + c);
      expect(Math.abs(refused - n * p)).toBeLessThanOrEqual(5 * Math.sqrt(n * p * (1 - p)) + 1);
    }
  });
});
