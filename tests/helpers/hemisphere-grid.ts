/**
 * A partition of the upper hemisphere concentrated around a lobe, and the
 * Gauss–Legendre rules that integrate a pdf over its cells: the binning of
 * the BSDF χ² tests (Mitsuba's `chi2` test, also in pbrt-v3). The χ²
 * statistic itself is in chi2.ts.
 */

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
