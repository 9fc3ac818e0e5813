/**
 * Statistical tests of the BSDFs' `sample` against their `pdf`: the
 * chi-square goodness-of-fit test of Mitsuba (Jakob's `chi2` test, also in
 * pbrt-v3): sample N directions, histogram them over a partition of the
 * sphere, compare with the expected counts N·∫cell pdf (integrated
 * numerically, Gauss–Legendre per cell), pool the cells expected below 5,
 * and reject when the p-value of the χ² statistic is below 0.01 after a
 * Šidák correction for the number of tests.
 *
 * The partition is spherical coordinates about the normal (so the horizon is
 * a cell edge and the pdf is smooth inside every cell), with bin edges
 * concentrated around the mirror direction so that even narrow GGX lobes span
 * many cells. Samples the sampler refuses (returns false) land in a "failed"
 * pseudo-cell whose expected count is N·(1 − ∫hemisphere pdf), and samples
 * below the horizon in a cell whose expected count is zero.
 *
 * Alongside: sample weights equal f·cosθi/pdf, `pdf` agrees with the pdf the
 * sampler reports, `eval` is reciprocal, and weights never create energy.
 * Everything runs on the core's PCG hash with fixed seeds.
 */
import { describe, expect, it } from 'vitest';
import { bsdfEval, bsdfPdf, bsdfSample } from '../helpers/bsdf-calls.ts';
import { ggxD, ggxG1 } from '../../src/core/bsdf/ggx.ts';
import { fresnelDielectric, schlickWeight } from '../../src/core/bsdf/fresnel.ts';
import { compileMaterials } from '../../src/core/bsdf/materials.ts';
import { BsdfSample, BsdfValue } from '../../src/core/bsdf/records.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import type { MaterialDesc, Vec3 } from '../../src/core/scene/format/types.ts';
import { chi2Survival, chi2Test, type Chi2Result } from '../helpers/chi2.ts';
import { gaussLegendre, HemisphereGrid } from '../helpers/hemisphere-grid.ts';

// ---------------------------------------------------------------------------
// Materials and directions.

const BLACK: Vec3 = [0, 0, 0];
const ROUGHNESSES = [0.05, 0.3, 0.7, 1.0];
const COLOR: Vec3 = [0.9, 0.6, 0.3];
const DESCS: MaterialDesc[] = [
  { type: 'diffuse', albedo: [0.8, 0.5, 0.2], emission: BLACK },
  { type: 'diffuse', albedo: [1, 1, 1], emission: BLACK },
  ...ROUGHNESSES.map((roughness): MaterialDesc => ({
    type: 'conductor',
    color: COLOR,
    roughness,
    emission: BLACK,
  })),
  ...ROUGHNESSES.map((roughness): MaterialDesc => ({
    type: 'conductor',
    color: [1, 1, 1],
    roughness,
    emission: BLACK,
  })),
  // A roughness whose alpha differs from 0.3's by 20%, for the power check.
  { type: 'conductor', color: COLOR, roughness: 0.33, emission: BLACK },
  { type: 'conductor', color: COLOR, roughness: 0, emission: BLACK },
  { type: 'dielectric', ior: 1.5, color: [0.9, 0.8, 0.7], roughness: 0, emission: BLACK },
];
const MATERIALS = compileMaterials(DESCS);
const DIFFUSE = 0;
const DIFFUSE_WHITE = 1;
const CONDUCTOR = (r: number): number => 2 + ROUGHNESSES.indexOf(r);
const CONDUCTOR_WHITE = (r: number): number => 2 + ROUGHNESSES.length + ROUGHNESSES.indexOf(r);
const CONDUCTOR_033 = 2 + 2 * ROUGHNESSES.length;
const MIRROR = CONDUCTOR_033 + 1;
const GLASS = MIRROR + 1;

const DEG = Math.PI / 180;
/** Azimuth of wo: off the axes, so nothing lines up by accident. */
const PHI_O = 0.7;

function direction(thetaDeg: number, phi = PHI_O): [number, number, number] {
  const t = thetaDeg * DEG;
  return [Math.sin(t) * Math.cos(phi), Math.sin(t) * Math.sin(phi), Math.cos(t)];
}

function rand(seed: number, i: number, d: number): number {
  return hashToUnit(sampleKey(seed, i, 0), d);
}

/** Uniform direction on the upper hemisphere, z ≥ zMin. */
function randomUpper(seed: number, i: number, zMin = 0): [number, number, number] {
  const z = zMin + (1 - zMin) * rand(seed, i, 0);
  const r = Math.sqrt(Math.max(0, 1 - z * z));
  const p = 2 * Math.PI * rand(seed, i, 1);
  return [r * Math.cos(p), r * Math.sin(p), z];
}

function relErr(a: number, b: number): number {
  const m = Math.max(Math.abs(a), Math.abs(b));
  return m === 0 ? 0 : Math.abs(a - b) / m;
}

// ---------------------------------------------------------------------------
// The χ² run.

const N_SAMPLES = 250_000;
const SIGNIFICANCE = 0.01;

interface Case {
  name: string;
  material: number;
  thetaO: number;
  /** Angular width of the lobe, for the partition. */
  width: number;
}

const CASES: Case[] = [
  { name: 'diffuse, wo normal', material: DIFFUSE, thetaO: 0, width: 10 },
  { name: 'diffuse, wo at 60°', material: DIFFUSE, thetaO: 60, width: 10 },
];
for (const r of ROUGHNESSES) {
  for (const thetaO of [0, 45, 85]) {
    CASES.push({
      name: `conductor roughness ${r}, wo at ${thetaO}°`,
      material: CONDUCTOR(r),
      thetaO,
      width: 2.5 * r * r,
    });
  }
}
/** Šidák-corrected level of each test, so that all together reject at 1%. */
const ALPHA = 1 - Math.pow(1 - SIGNIFICANCE, 1 / CASES.length);

interface RunResult {
  chi2: Chi2Result;
  /** ∫ pdf over the upper hemisphere. */
  mass: number;
  failures: number;
  expectedFailures: number;
  /** Worst relative error of weight vs f·cosθi/pdf and of sample pdf vs `pdf`. */
  weightErr: number;
  pdfErr: number;
}

/**
 * Samples `n` directions from material m for wo and tests them against
 * `pdf` (by default the material's own `bsdfPdf`).
 */
function runChi2(
  m: number,
  wo: [number, number, number],
  width: number,
  n: number,
  seed: number,
  pdf: (x: number, y: number, z: number) => number = (x, y, z) =>
    bsdfPdf(MATERIALS, m, wo[0], wo[1], wo[2], x, y, z),
): RunResult {
  const [wox, woy, woz] = wo;
  const thetaR = Math.acos(Math.min(1, woz));
  const phiR = Math.atan2(-woy, -wox);
  const grid = HemisphereGrid.around(thetaR, phiR, Math.max(width, 1e-4));
  const expected = grid.integrate(pdf);
  let mass = 0;
  for (let i = 0; i < grid.below; i++) mass += expected[i];
  for (let i = 0; i < grid.below; i++) expected[i] *= n;
  // What the hemisphere misses is what the sampler must refuse.
  const expectedFailures = n * Math.max(0, 1 - mass);
  expected[grid.failed] = expectedFailures;
  const observed = new Float64Array(grid.nCells);
  const s = new BsdfSample();
  const f = new BsdfValue();
  let weightErr = 0;
  let pdfErr = 0;
  for (let i = 0; i < n; i++) {
    const key = sampleKey(seed, i, 0);
    const ok = bsdfSample(
      MATERIALS,
      m,
      wox,
      woy,
      woz,
      hashToUnit(key, 0),
      hashToUnit(key, 1),
      hashToUnit(key, 2),
      s,
    );
    if (!ok) {
      observed[grid.failed]++;
      continue;
    }
    observed[grid.cellOf(s.wx, s.wy, s.wz)]++;
    if (s.isDelta || !(s.wz > 0)) continue;
    const p = bsdfPdf(MATERIALS, m, wox, woy, woz, s.wx, s.wy, s.wz);
    bsdfEval(MATERIALS, m, wox, woy, woz, s.wx, s.wy, s.wz, f);
    pdfErr = Math.max(pdfErr, relErr(s.pdf, p));
    const c = s.wz / s.pdf;
    weightErr = Math.max(
      weightErr,
      relErr(s.weightR, f.r * c),
      relErr(s.weightG, f.g * c),
      relErr(s.weightB, f.b * c),
    );
  }
  return {
    chi2: chi2Test(observed, expected),
    mass,
    failures: observed[grid.failed],
    expectedFailures,
    weightErr,
    pdfErr,
  };
}

describe('χ² machinery', () => {
  it('computes the χ² survival function', () => {
    // dof 2: exp(−x/2) exactly.
    for (const x of [0.1, 1, 5, 20, 60]) {
      expect(chi2Survival(x, 2)).toBeCloseTo(Math.exp(-x / 2), 13);
    }
    // Table values: the 1% and 5% critical points.
    expect(chi2Survival(6.634896601021214, 1)).toBeCloseTo(0.01, 10);
    expect(chi2Survival(23.209251158954356, 10)).toBeCloseTo(0.01, 10);
    expect(chi2Survival(124.34211340400407, 100)).toBeCloseTo(0.05, 10);
    expect(chi2Survival(1.1454762260617692, 5)).toBeCloseTo(0.95, 10);
    // Large dof: mean dof, median ≈ dof(1 − 2/(9 dof))³.
    const k = 800;
    expect(chi2Survival(k * (1 - 2 / (9 * k)) ** 3, k)).toBeCloseTo(0.5, 3);
    expect(chi2Survival(0, 7)).toBe(1);
  });

  it('computes Gauss–Legendre rules exact to degree 2n − 1', () => {
    const { x, w } = gaussLegendre(8);
    for (let deg = 0; deg <= 15; deg++) {
      let s = 0;
      for (let i = 0; i < 8; i++) s += w[i] * x[i] ** deg;
      expect(s).toBeCloseTo(deg % 2 === 0 ? 2 / (deg + 1) : 0, 13);
    }
  });

  it('partitions the hemisphere exactly (cosine pdf integrates to 1)', () => {
    const grid = HemisphereGrid.around(45 * DEG, 1, 0.01);
    const cells = grid.integrate((_x, _y, z) => z / Math.PI);
    expect(cells.reduce((a, b) => a + b, 0)).toBeCloseTo(1, 12);
    // Every cell is found by cellOf for a point inside it.
    const nPhi = grid.phi.length - 1;
    for (let i = 0; i + 1 < grid.theta.length; i++) {
      for (let j = 0; j < nPhi; j++) {
        const t = 0.5 * (grid.theta[i] + grid.theta[i + 1]);
        const p = grid.phiCenter + 0.5 * (grid.phi[j] + grid.phi[j + 1]);
        const c = grid.cellOf(Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t));
        expect(c).toBe(i * nPhi + j);
      }
    }
    expect(grid.cellOf(1, 0, 0)).toBe(grid.below);
    expect(grid.cellOf(0.6, 0, -0.8)).toBe(grid.below);
  });

  it('has power: rejects a sampler tested against the wrong pdf', () => {
    const wo = direction(45);
    // Cosine-weighted samples against a uniform hemisphere.
    const uniform = runChi2(DIFFUSE, wo, 10, 100_000, 11, (_x, _y, z) =>
      z > 0 ? 1 / (2 * Math.PI) : 0,
    );
    expect(uniform.chi2.pValue).toBeLessThan(1e-12);
    // GGX with α = 0.09 against the pdf of α = 0.1089.
    const pdf033 = (x: number, y: number, z: number): number =>
      bsdfPdf(MATERIALS, CONDUCTOR_033, wo[0], wo[1], wo[2], x, y, z);
    const ggx = runChi2(CONDUCTOR(0.3), wo, 0.2, 100_000, 12, pdf033);
    expect(ggx.chi2.pValue).toBeLessThan(1e-6);
    // The sampler's own pdf at the same settings passes.
    const own = runChi2(CONDUCTOR(0.3), wo, 0.2, 100_000, 12);
    expect(own.chi2.pValue).toBeGreaterThan(1e-3);
  });
});

describe('BSDF sample vs pdf: χ² goodness of fit', () => {
  CASES.forEach((c, index) => {
    it(`${c.name}`, () => {
      const wo = direction(c.thetaO);
      const r = runChi2(c.material, wo, c.width, N_SAMPLES, 1000 + index);
      expect(r.chi2.impossible).toBeNull();
      // The pdf never integrates above 1 over the hemisphere.
      expect(r.mass).toBeLessThan(1 + 1e-6);
      expect(r.chi2.dof).toBeGreaterThan(50);
      expect(
        r.chi2.pValue,
        `χ² = ${r.chi2.stat.toFixed(1)} on ${r.chi2.dof} dof, p = ${r.chi2.pValue}; ` +
          `failures ${r.failures} vs ${r.expectedFailures.toFixed(1)} expected`,
      ).toBeGreaterThan(ALPHA);
      // Weight = f·cosθi/pdf, and the pdf the sampler reports is `pdf`'s.
      expect(r.weightErr).toBeLessThan(1e-9);
      expect(r.pdfErr).toBeLessThan(1e-9);
    });
  });

  it('diffuse never fails; GGX refuses exactly the mass below the horizon', () => {
    const diffuse = runChi2(DIFFUSE, direction(30), 10, 50_000, 7);
    expect(diffuse.failures).toBe(0);
    expect(diffuse.mass).toBeCloseTo(1, 10);
    // Rough and grazing: a large fraction of the visible-normal reflections
    // go below the horizon. Its expectation is covered by the χ² above; here
    // check that it is substantial, so that the failed cell is exercised.
    const grazing = runChi2(CONDUCTOR(1), direction(85), 2.5, 50_000, 8);
    expect(grazing.expectedFailures / 50_000).toBeGreaterThan(0.05);
    expect(Math.abs(grazing.failures - grazing.expectedFailures)).toBeLessThan(
      5 * Math.sqrt(grazing.expectedFailures),
    );
  });

  it('delta lobes: the mirror and the glass pick their lobes with the right probabilities', () => {
    const s = new BsdfSample();
    const n = 100_000;
    for (const thetaO of [0, 45, 85]) {
      const [x, y, z] = direction(thetaO);
      // Mirror: every sample is the reflection, with pdf 1.
      let mirrored = 0;
      for (let i = 0; i < 1000; i++) {
        const ok = bsdfSample(MATERIALS, MIRROR, x, y, z, rand(5, i, 0), rand(5, i, 1), 0, s);
        if (ok && s.isDelta && s.pdf === 1 && s.wx === -x && s.wy === -y && s.wz === z) {
          mirrored++;
        }
      }
      expect(mirrored).toBe(1000);
      // Glass from outside and from inside: reflect with probability F.
      for (const side of [1, -1]) {
        const eta = side > 0 ? 1.5 : 1 / 1.5;
        const fr = fresnelDielectric(z, eta);
        const observed = new Float64Array(2);
        for (let i = 0; i < n; i++) {
          const key = sampleKey(60 + thetaO, i, side > 0 ? 0 : 1);
          const u = hashToUnit(key, 2);
          bsdfSample(
            MATERIALS,
            GLASS,
            x,
            y,
            side * z,
            hashToUnit(key, 0),
            hashToUnit(key, 1),
            u,
            s,
          );
          observed[s.wz * side > 0 ? 0 : 1]++;
        }
        const expected = Float64Array.of(n * fr, n * (1 - fr));
        const r = chi2Test(observed, expected);
        expect(r.impossible).toBeNull();
        expect(r.pValue).toBeGreaterThan(ALPHA);
      }
    }
  });
});

describe('BSDF eval: reciprocity and energy', () => {
  const f = new BsdfValue();
  const g = new BsdfValue();

  it('eval(wo, wi) == eval(wi, wo) for diffuse and every conductor roughness (1e-12)', () => {
    const materials = [DIFFUSE, ...ROUGHNESSES.map(CONDUCTOR), CONDUCTOR_033];
    for (const m of materials) {
      let worst = 0;
      let positive = 0;
      for (let i = 0; i < 20_000; i++) {
        // Include grazing directions (z down to 1e-6).
        const [ax, ay, az] = randomUpper(100 + m, i, i % 10 === 0 ? 0 : 1e-6);
        const [bx, by, bz] = randomUpper(200 + m, i);
        bsdfEval(MATERIALS, m, ax, ay, az, bx, by, bz, f);
        bsdfEval(MATERIALS, m, bx, by, bz, ax, ay, az, g);
        worst = Math.max(worst, relErr(f.r, g.r), relErr(f.g, g.g), relErr(f.b, g.b));
        if (f.r > 0) positive++;
        if (!(Number.isFinite(f.r) && Number.isFinite(f.g) && Number.isFinite(f.b))) worst = NaN;
      }
      expect(worst).toBeLessThan(1e-12);
      expect(positive).toBeGreaterThan(19_000);
    }
  });

  it('eval and pdf vanish below the horizon and for delta lobes', () => {
    const [ox, oy, oz] = direction(40);
    for (const m of [DIFFUSE, ...ROUGHNESSES.map(CONDUCTOR)]) {
      bsdfEval(MATERIALS, m, ox, oy, oz, 0.3, 0.2, -0.5, f);
      expect([f.r, f.g, f.b]).toEqual([0, 0, 0]);
      expect(bsdfPdf(MATERIALS, m, ox, oy, oz, 0.3, 0.2, -0.5)).toBe(0);
      bsdfEval(MATERIALS, m, ox, oy, -oz, 0.3, 0.2, 0.5, f);
      expect([f.r, f.g, f.b]).toEqual([0, 0, 0]);
      expect(bsdfPdf(MATERIALS, m, ox, oy, -oz, 0.3, 0.2, 0.5)).toBe(0);
    }
    for (const m of [MIRROR, GLASS]) {
      bsdfEval(MATERIALS, m, ox, oy, oz, -ox, -oy, oz, f);
      expect([f.r, f.g, f.b]).toEqual([0, 0, 0]);
      expect(bsdfPdf(MATERIALS, m, ox, oy, oz, -ox, -oy, oz)).toBe(0);
    }
  });

  it('conductor eval is D·G1(wo)·G1(wi)·F / (4 cosθo cosθi) with Schlick F', () => {
    const [ox, oy, oz] = direction(30);
    const [ix, iy, iz] = direction(50, PHI_O + 2.5);
    for (const r of ROUGHNESSES) {
      const alpha = r * r;
      bsdfEval(MATERIALS, CONDUCTOR(r), ox, oy, oz, ix, iy, iz, f);
      const hl = Math.hypot(ox + ix, oy + iy, oz + iz);
      const hz = (oz + iz) / hl;
      const cosOH = (ox * (ox + ix) + oy * (oy + iy) + oz * (oz + iz)) / hl;
      const common = (ggxD(hz, alpha) * ggxG1(oz, alpha) * ggxG1(iz, alpha)) / (4 * oz * iz);
      const w = schlickWeight(cosOH);
      expect(relErr(f.r, common * (COLOR[0] + (1 - COLOR[0]) * w))).toBeLessThan(1e-12);
      expect(relErr(f.g, common * (COLOR[1] + (1 - COLOR[1]) * w))).toBeLessThan(1e-12);
      expect(relErr(f.b, common * (COLOR[2] + (1 - COLOR[2]) * w))).toBeLessThan(1e-12);
    }
  });

  it('a white diffuse surface has sample weights of exactly 1', () => {
    const s = new BsdfSample();
    let notOne = 0;
    for (let i = 0; i < 50_000; i++) {
      const [x, y, z] = randomUpper(300, i, 1e-9);
      const ok = bsdfSample(
        MATERIALS,
        DIFFUSE_WHITE,
        x,
        y,
        z,
        rand(301, i, 0),
        rand(301, i, 1),
        0,
        s,
      );
      if (!ok || s.weightR !== 1 || s.weightG !== 1 || s.weightB !== 1) notOne++;
    }
    expect(notOne).toBe(0);
  });

  it('a white conductor never returns a weight above 1 (any roughness, grazing included)', () => {
    const s = new BsdfSample();
    for (const r of ROUGHNESSES) {
      let worst = 0;
      let lowest = Infinity;
      let accepted = 0;
      for (let i = 0; i < 50_000; i++) {
        // Every tenth wo within 1e-6 of the horizon.
        const [x, y, z] = randomUpper(400, i, 0);
        const zz = i % 10 === 0 ? 1e-6 * (1 + z) : z;
        const k = Math.sqrt((1 - zz * zz) / Math.max(1e-300, x * x + y * y));
        const ok = bsdfSample(
          MATERIALS,
          CONDUCTOR_WHITE(r),
          x * k,
          y * k,
          zz,
          rand(401, i, 0),
          rand(401, i, 1),
          0,
          s,
        );
        if (!ok) continue;
        accepted++;
        worst = Math.max(worst, s.weightR, s.weightG, s.weightB);
        lowest = Math.min(lowest, s.weightR, s.weightG, s.weightB);
        if (!(Number.isFinite(s.pdf) && s.pdf > 0)) lowest = NaN;
      }
      expect(accepted).toBeGreaterThan(25_000);
      expect(worst).toBeLessThanOrEqual(1 + 1e-12);
      expect(lowest).toBeGreaterThanOrEqual(0);
    }
  });
});
