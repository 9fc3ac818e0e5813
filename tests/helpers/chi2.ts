/**
 * The χ² goodness-of-fit machinery of the BSDF tests (Mitsuba's `chi2` test,
 * also in pbrt-v3): the χ² survival function, Pearson's statistic with
 * pooling of small cells, Gauss–Legendre rules and a partition of the upper
 * hemisphere concentrated around a lobe. See tests/statistical/bsdf-chi2.test.ts.
 */
// ---------------------------------------------------------------------------
// χ² distribution: regularized incomplete gamma function (Numerical Recipes
// §6.2: series for x < a + 1, Lentz's continued fraction otherwise).

/** ln Γ(x) for x > 0 (Lanczos, g = 7, n = 9; ~1e-15 relative). */
export function lnGamma(x: number): number {
  const c = [
    0.99999999999980993, 676.5203681218851, -1259.1392167224028, 771.32342877765313,
    -176.61502916214059, 12.507343278686905, -0.13857109526572012, 9.9843695780195716e-6,
    1.5056327351493116e-7,
  ];
  if (x < 0.5) return Math.log(Math.PI / Math.abs(Math.sin(Math.PI * x))) - lnGamma(1 - x);
  const xm = x - 1;
  let s = c[0];
  for (let i = 1; i < 9; i++) s += c[i] / (xm + i);
  const t = xm + 7.5;
  return 0.5 * Math.log(2 * Math.PI) + (xm + 0.5) * Math.log(t) - t + Math.log(s);
}

/** Regularized upper incomplete gamma Q(a, x) = Γ(a, x) / Γ(a). */
export function gammaQ(a: number, x: number): number {
  if (x <= 0) return 1;
  const lnPre = -x + a * Math.log(x) - lnGamma(a);
  if (x < a + 1) {
    // P(a, x) by its series; Q = 1 − P.
    let ap = a;
    let del = 1 / a;
    let sum = del;
    for (let n = 0; n < 10_000; n++) {
      ap += 1;
      del *= x / ap;
      sum += del;
      if (Math.abs(del) < Math.abs(sum) * 1e-16) break;
    }
    return Math.max(0, 1 - sum * Math.exp(lnPre));
  }
  const tiny = 1e-300;
  let b = x + 1 - a;
  let c = 1 / tiny;
  let d = 1 / b;
  let h = d;
  for (let i = 1; i < 10_000; i++) {
    const an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (Math.abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (Math.abs(c) < tiny) c = tiny;
    d = 1 / d;
    const delta = d * c;
    h *= delta;
    if (Math.abs(delta - 1) < 1e-16) break;
  }
  return Math.exp(lnPre) * h;
}

/** P(X ≥ x) for X ~ χ²(dof). */
export function chi2Survival(x: number, dof: number): number {
  return gammaQ(dof / 2, x / 2);
}

export interface Chi2Result {
  stat: number;
  dof: number;
  pValue: number;
  /** Set when an observation fell in a cell of zero expected count. */
  impossible: string | null;
}

/**
 * Pearson's χ² of observed against expected counts with Mitsuba's pooling:
 * cells are visited by increasing expectation and merged into one pool while
 * they (or the pool) are expected below `minExpected`.
 */
export function chi2Test(
  observed: Float64Array,
  expected: Float64Array,
  minExpected = 5,
): Chi2Result {
  const order = Array.from(expected.keys()).sort((a, b) => expected[a] - expected[b]);
  let impossible: string | null = null;
  let stat = 0;
  let cells = 0;
  let poolObs = 0;
  let poolExp = 0;
  let pooled = 0;
  for (const i of order) {
    const e = expected[i];
    const o = observed[i];
    if (e === 0 && o > 0 && impossible === null) {
      impossible = `cell ${i} has ${o} samples but expects none`;
    }
    if (e < minExpected || (pooled > 0 && poolExp < minExpected)) {
      poolObs += o;
      poolExp += e;
      pooled++;
    } else {
      stat += ((o - e) * (o - e)) / e;
      cells++;
    }
  }
  if (pooled > 0 && poolExp > 0) {
    stat += ((poolObs - poolExp) * (poolObs - poolExp)) / poolExp;
    cells++;
  }
  const dof = cells - 1;
  return { stat, dof, pValue: dof > 0 ? chi2Survival(stat, dof) : 1, impossible };
}

// ---------------------------------------------------------------------------
// Partition of the upper hemisphere and the numerical integration of a pdf.

/** n-point Gauss–Legendre nodes and weights on [−1, 1] (Newton on P_n). */
export function gaussLegendre(n: number): { x: Float64Array; w: Float64Array } {
  const x = new Float64Array(n);
  const w = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    let z = Math.cos((Math.PI * (i + 0.75)) / (n + 0.5));
    let dp = 0;
    for (let it = 0; it < 100; it++) {
      let p0 = 1;
      let p1 = z;
      for (let k = 2; k <= n; k++) {
        const p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = (n * (z * p1 - p0)) / (z * z - 1);
      const dz = p1 / dp;
      z -= dz;
      if (Math.abs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2 / ((1 - z * z) * dp * dp);
  }
  return { x, w };
}

/**
 * n + 1 bin edges on [a, b], equally spaced in the CDF of a mixture of a
 * uniform density (weight `uniform`) and a Cauchy density centred on `c` of
 * half-width `w`, truncated to [a, b]: fine cells around c, coarse far away.
 */
export function mixtureEdges(
  n: number,
  a: number,
  b: number,
  c: number,
  w: number,
  uniform: number,
): Float64Array {
  const ta = Math.atan((a - c) / w);
  const tb = Math.atan((b - c) / w);
  const cdf = (t: number): number =>
    (uniform * (t - a)) / (b - a) + ((1 - uniform) * (Math.atan((t - c) / w) - ta)) / (tb - ta);
  const edges = new Float64Array(n + 1);
  edges[0] = a;
  edges[n] = b;
  for (let k = 1; k < n; k++) {
    const target = k / n;
    let lo = a;
    let hi = b;
    for (let it = 0; it < 80; it++) {
      const mid = 0.5 * (lo + hi);
      if (cdf(mid) < target) lo = mid;
      else hi = mid;
    }
    edges[k] = 0.5 * (lo + hi);
  }
  return edges;
}

/** Index of the bin of sorted `edges` that holds v (clamped to the range). */
export function findBin(edges: Float64Array, v: number): number {
  let lo = 0;
  let hi = edges.length - 2;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (edges[mid] <= v) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/**
 * Cells over θ ∈ [0, π/2] (θ about the normal) × φ' ∈ [−π, π) with φ' = φ −
 * φCenter, plus two pseudo-cells: `below` (wi.z ≤ 0) and `failed`.
 */
export class HemisphereGrid {
  readonly nCells: number;
  readonly below: number;
  readonly failed: number;

  constructor(
    readonly theta: Float64Array,
    readonly phi: Float64Array,
    readonly phiCenter: number,
  ) {
    const n = (theta.length - 1) * (phi.length - 1);
    this.below = n;
    this.failed = n + 1;
    this.nCells = n + 2;
  }

  /** Grid concentrated around the direction (θc, φc) with angular width w. */
  static around(thetaC: number, phiC: number, w: number, nTheta = 24, nPhi = 36): HemisphereGrid {
    const theta = mixtureEdges(nTheta, 0, Math.PI / 2, thetaC, w, 0.4);
    // The lobe's width in φ grows as 1 / sinθ; near the pole φ is uniform.
    const wPhi = w / Math.max(Math.sin(thetaC), 1e-9);
    const phi =
      wPhi > 1
        ? mixtureEdges(nPhi, -Math.PI, Math.PI, 0, 1, 1)
        : mixtureEdges(nPhi, -Math.PI, Math.PI, 0, wPhi, 0.4);
    return new HemisphereGrid(theta, phi, phiC);
  }

  cellOf(x: number, y: number, z: number): number {
    if (!(z > 0)) return this.below;
    const t = Math.acos(Math.min(1, z));
    let p = Math.atan2(y, x) - this.phiCenter;
    p -= 2 * Math.PI * Math.floor((p + Math.PI) / (2 * Math.PI));
    const i = findBin(this.theta, t);
    const j = findBin(this.phi, p);
    return i * (this.phi.length - 1) + j;
  }

  /** ∫cell pdf dω for every cell (pseudo-cells left at 0), K×K Gauss–Legendre per cell. */
  integrate(pdf: (x: number, y: number, z: number) => number, k = 8): Float64Array {
    const { x: gx, w: gw } = gaussLegendre(k);
    const nPhi = this.phi.length - 1;
    const out = new Float64Array(this.nCells);
    for (let i = 0; i + 1 < this.theta.length; i++) {
      const t0 = this.theta[i];
      const ht = 0.5 * (this.theta[i + 1] - t0);
      for (let j = 0; j < nPhi; j++) {
        const p0 = this.phi[j];
        const hp = 0.5 * (this.phi[j + 1] - p0);
        let sum = 0;
        for (let a = 0; a < k; a++) {
          const t = t0 + ht * (gx[a] + 1);
          const st = Math.sin(t);
          const ct = Math.cos(t);
          let row = 0;
          for (let b = 0; b < k; b++) {
            const p = this.phiCenter + p0 + hp * (gx[b] + 1);
            row += gw[b] * pdf(st * Math.cos(p), st * Math.sin(p), ct);
          }
          sum += gw[a] * row * st;
        }
        out[i * nPhi + j] = sum * ht * hp;
      }
    }
    return out;
  }
}
