/**
 * Pearson's χ² goodness-of-fit test as Mitsuba's and pbrt-v3's chi2 tests run it, for
 * the statistical tests of samplers against their pdfs: the χ² survival function by the
 * regularized incomplete gamma function, and pooling of cells expected below 5.
 */

// ---------------------------------------------------------------------------
// χ² distribution: regularized incomplete gamma function (Numerical Recipes
// §6.2: series for x < a + 1, Lentz's continued fraction otherwise).

/** ln Γ(x) for x > 0 (Lanczos, g = 7, n = 9; ~1e-15 relative). */
function lnGamma(x: number): number {
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
function gammaQ(a: number, x: number): number {
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
