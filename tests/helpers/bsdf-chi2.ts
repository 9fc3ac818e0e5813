/**
 * The harness of the glTF BSDF statistical tests (gltf-bsdf-chi2.test.ts and the
 * tests modelled on it), for any lobe with the record-based calls of gltf-pbr.ts:
 *
 * - `bsdfChi2`: Pearson's χ² of `sample` against `pdf` (Mitsuba's chi2 test, also in
 *   pbrt-v3) on a hemisphere grid concentrated around the mirror direction, or on the
 *   whole sphere; delta samples and refusals share one pseudo-cell expected at
 *   N·(1 − ∫pdf). Alongside, every non-delta sample's weight must be f·|cosθi|/pdf
 *   and its reported density `pdf`'s. The cells are hemisphere-grid.ts's, the
 *   statistic (pooling cells expected below 5) chi2.ts's.
 * - `furnace`: the mean sample weight per channel and its standard error (energy:
 *   × etaScale), for white-furnace tests.
 * - `evalBothWays`: f(wo, wi) against f(wi, wo), for reciprocity tests.
 *
 * Samples are drawn on the core's PCG hash from fixed seeds: sample i of a run
 * reads hashToUnit(sampleKey(seed, i, stream), 0…2).
 */
import { expect } from 'vitest';
import { gltfEval, gltfPdf, gltfSample } from '../../src/core/bsdf/gltf-pbr.ts';
import { BsdfQuery, BsdfSample, BsdfValue } from '../../src/core/bsdf/records.ts';
import type { ShadingParams } from '../../src/core/bsdf/shading.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import { chi2Test, type Chi2Result } from './chi2.ts';
import { HemisphereGrid } from './hemisphere-grid.ts';

export type Vec3 = [number, number, number];

/** A lobe's `sample`, `pdf` and `eval`, as gltf-pbr.ts and gltf-layers.ts export them. */
export interface Lobe {
  sample(sp: ShadingParams, q: BsdfQuery, out: BsdfSample): boolean;
  pdf(sp: ShadingParams, q: BsdfQuery): number;
  eval(sp: ShadingParams, q: BsdfQuery, out: BsdfValue): void;
}

/** The glTF BSDF of gltf-pbr.ts. */
export const gltfLobe: Lobe = { sample: gltfSample, pdf: gltfPdf, eval: gltfEval };

export const DEG = Math.PI / 180;

/** The unit direction at θ (degrees) from the normal and azimuth φ. */
export function direction(thetaDeg: number, phi = 0.7): Vec3 {
  const t = thetaDeg * DEG;
  return [Math.sin(t) * Math.cos(phi), Math.sin(t) * Math.sin(phi), Math.cos(t)];
}

export function relErr(a: number, b: number): number {
  const m = Math.max(Math.abs(a), Math.abs(b));
  return m === 0 ? 0 : Math.abs(a - b) / m;
}

/** Angular width of the grid around a lobe of roughness α; α = 0 (delta only): near-uniform. */
export function lobeWidth(alpha: number): number {
  return alpha === 0 ? 10 : Math.max(2.5 * alpha, 1e-3);
}

const q = new BsdfQuery();

function setDirections(wo: Vec3, wi: Vec3): void {
  [q.wox, q.woy, q.woz] = wo;
  [q.wix, q.wiy, q.wiz] = wi;
}

/** Sets q's wo, and its random numbers to hashToUnit(key, 0…2): a sample's query. */
export function setSampleQuery(
  q: BsdfQuery,
  wox: number,
  woy: number,
  woz: number,
  key: number,
): void {
  q.wox = wox;
  q.woy = woy;
  q.woz = woz;
  q.u0 = hashToUnit(key, 0);
  q.u1 = hashToUnit(key, 1);
  q.u2 = hashToUnit(key, 2);
}

export interface Chi2Options {
  lobe: Lobe;
  /** The material sampled. */
  sp: ShadingParams;
  /** The material whose pdf gives the expected counts, when not sp's (for the power checks). */
  pdfSp?: ShadingParams;
  /** wo in the upper hemisphere; `inside` mirrors it below (z < 0). */
  wo: Vec3;
  inside?: boolean;
  /** The grid's angular width around the mirror direction (`lobeWidth`). */
  width: number;
  n: number;
  seed: number;
  stream?: number;
  /** Gauss–Legendre points per cell side (HemisphereGrid.integrate); 8 unless told. */
  quadrature?: number;
  /**
   * Bin the far side too (a second, uniform grid) for lobes that transmit; otherwise
   * the far side is one cell expected empty, and a sample there makes `impossible`.
   */
  sphere?: boolean;
}

export interface Chi2Run extends Chi2Result {
  /** ∫pdf over the cells binned (≤ 1). */
  mass: number;
  /** Worst relative error of a weight against f·|cosθi|/pdf, and of a density against `pdf`. */
  weightErr: number;
  pdfErr: number;
  /** Observed and expected counts of the pseudo-cell of delta samples and refusals. */
  rest: [number, number];
}

/**
 * The grids live in the frame where wo is above (z mirrored from inside): near is
 * wo's side, concentrated around the mirror direction; far, with `sphere`, the other.
 * Cells: near's (its `below` cell last, expected empty, without `sphere`), then far's,
 * then the pseudo-cell of delta samples and refusals.
 */
export function bsdfChi2(o: Chi2Options): Chi2Run {
  const { lobe, sp, n } = o;
  const pdfSp = o.pdfSp ?? sp;
  const s = o.inside ? -1 : 1;
  const [wox, woy, oz] = o.wo;
  const woz = s * oz;
  const pdfAt = (x: number, y: number, z: number): number => {
    setDirections([wox, woy, woz], [x, y, z]);
    return lobe.pdf(pdfSp, q);
  };
  const near = HemisphereGrid.around(oz < 1 ? Math.acos(oz) : 0, Math.atan2(-woy, -wox), o.width);
  const en = near.integrate((x, y, z) => pdfAt(x, y, s * z), o.quadrature);
  let expected: Float64Array;
  let failed: number;
  let cellOf: (x: number, y: number, z: number) => number;
  let mass = 0;
  if (o.sphere) {
    const far = HemisphereGrid.around(0, 0, 10, 12, 24);
    const ef = far.integrate((x, y, z) => pdfAt(x, y, -s * z), o.quadrature);
    const cells = near.below + far.below + 1;
    failed = cells - 1;
    expected = new Float64Array(cells);
    for (let i = 0; i < near.below; i++) {
      expected[i] = en[i] * n;
      mass += en[i];
    }
    for (let i = 0; i < far.below; i++) {
      expected[near.below + i] = ef[i] * n;
      mass += ef[i];
    }
    // A sample in the plane (z = 0) falls in far's `below`: the pseudo-cell.
    cellOf = (x, y, z) => (z > 0 ? near.cellOf(x, y, z) : near.below + far.cellOf(x, y, -z));
  } else {
    failed = near.failed;
    expected = en;
    for (let i = 0; i < near.below; i++) mass += expected[i];
    for (let i = 0; i < near.below; i++) expected[i] *= n;
    cellOf = (x, y, z) => near.cellOf(x, y, z);
  }
  expected[failed] = n * Math.max(0, 1 - mass);

  const observed = new Float64Array(expected.length);
  const out = new BsdfSample();
  const f = new BsdfValue();
  let weightErr = 0;
  let pdfErr = 0;
  for (let i = 0; i < n; i++) {
    setSampleQuery(q, wox, woy, woz, sampleKey(o.seed, i, o.stream ?? 0));
    if (!lobe.sample(sp, q, out) || out.isDelta) {
      observed[failed]++;
      continue;
    }
    const z = s * out.wz;
    observed[cellOf(out.wx, out.wy, z)]++;
    // On a hemisphere, a sample on the far side already fails the test (`impossible`).
    if (!o.sphere && !(z > 0)) continue;
    q.wix = out.wx;
    q.wiy = out.wy;
    q.wiz = out.wz;
    lobe.eval(sp, q, f);
    pdfErr = Math.max(pdfErr, relErr(out.pdf, f.pdf), relErr(f.pdf, lobe.pdf(sp, q)));
    const k = Math.abs(out.wz) / out.pdf;
    weightErr = Math.max(
      weightErr,
      relErr(out.weightR, f.r * k),
      relErr(out.weightG, f.g * k),
      relErr(out.weightB, f.b * k),
    );
  }
  const r = chi2Test(observed, expected);
  return { ...r, mass, weightErr, pdfErr, rest: [observed[failed], expected[failed]] };
}

/**
 * The checks of every χ² case: nothing where the pdf is zero, ∫pdf ≤ 1, enough
 * cells, p above the (corrected) level `alpha`, weights and densities to 1e-9.
 */
export function expectChi2Fit(r: Chi2Run, alpha: number): void {
  expect(r.impossible).toBeNull();
  expect(r.mass).toBeLessThan(1 + 1e-6);
  expect(r.dof).toBeGreaterThan(50);
  expect(
    r.pValue,
    `χ² = ${r.stat.toFixed(1)} on ${r.dof} dof; rest ${r.rest[0]} vs ${r.rest[1].toFixed(1)}`,
  ).toBeGreaterThan(alpha);
  expect(r.weightErr).toBeLessThan(1e-9);
  expect(r.pdfErr).toBeLessThan(1e-9);
}

export interface Furnace {
  /** Per channel: the mean weight × etaScale (refusals count 0) and its standard error. */
  mean: Vec3;
  se: Vec3;
  /** Samples with a channel not finite and ≥ 0. */
  bad: number;
  /** Samples whose channels differ (of a white material: should be none). */
  notGrey: number;
}

/**
 * The white furnace's estimate of the energy a lobe keeps for wo: its mean sample
 * weight, with radiance mode's (n1/n2)² on refraction undone (× etaScale).
 */
export function furnace(
  lobe: Lobe,
  sp: ShadingParams,
  wo: Vec3,
  n: number,
  seed: number,
  stream: number,
): Furnace {
  const out = new BsdfSample();
  const sum = [0, 0, 0];
  const sum2 = [0, 0, 0];
  let bad = 0;
  let notGrey = 0;
  for (let i = 0; i < n; i++) {
    setSampleQuery(q, wo[0], wo[1], wo[2], sampleKey(seed, i, stream));
    if (!lobe.sample(sp, q, out)) continue;
    const w = [out.weightR * out.etaScale, out.weightG * out.etaScale, out.weightB * out.etaScale];
    if (!w.every((v) => Number.isFinite(v) && v >= 0)) bad++;
    if (out.weightG !== out.weightR || out.weightB !== out.weightR) notGrey++;
    for (let c = 0; c < 3; c++) {
      sum[c] += w[c];
      sum2[c] += w[c] * w[c];
    }
  }
  const mean = sum.map((v) => v / n) as Vec3;
  const se = mean.map((m, c) => Math.sqrt(Math.max(0, sum2[c] / n - m * m) / n)) as Vec3;
  return { mean, se, bad, notGrey };
}

/** Evaluates f(wo, wi) into a and f(wi, wo) into b; returns their worst relative difference. */
export function evalBothWays(
  lobe: Lobe,
  sp: ShadingParams,
  wo: Vec3,
  wi: Vec3,
  a: BsdfValue,
  b: BsdfValue,
): number {
  setDirections(wo, wi);
  lobe.eval(sp, q, a);
  setDirections(wi, wo);
  lobe.eval(sp, q, b);
  return Math.max(relErr(a.r, b.r), relErr(a.g, b.g), relErr(a.b, b.b));
}
