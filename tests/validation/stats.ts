/**
 * Distributions for the validation tests, written out so that the tests
 * state exactly what they compute:
 * - Student's t two-sided tail through the regularised incomplete beta
 *   function (continued fraction by the modified Lentz method; Numerical
 *   Recipes 3e §6.4, Abramowitz & Stegun 26.5.8 and 26.7.1);
 * - the Welch–Satterthwaite test for two means with unequal variances
 *   (Welch 1947);
 * - the standard normal tail and its inverse (bisection on erfc; the tests
 *   need a handful of quantiles, not speed).
 */

/** ln Γ(x) for x > 0 (Lanczos, g = 7, n = 9; ~15 digits). */
export function logGamma(x: number): number {
  const c = [
    0.99999999999980993, 676.5203681218851, -1259.1392167224028, 771.32342877765313,
    -176.61502916214059, 12.507343278686905, -0.13857109526572012, 9.9843695780195716e-6,
    1.5056327351493116e-7,
  ];
  if (x < 0.5) return Math.log(Math.PI / Math.sin(Math.PI * x)) - logGamma(1 - x);
  x -= 1;
  let a = c[0];
  const t = x + 7.5;
  for (let i = 1; i < 9; i++) a += c[i] / (x + i);
  return 0.5 * Math.log(2 * Math.PI) + (x + 0.5) * Math.log(t) - t + Math.log(a);
}

/** Continued fraction of the incomplete beta function (modified Lentz). */
function betaContinuedFraction(a: number, b: number, x: number): number {
  const tiny = 1e-300;
  let c = 1;
  let d = 1 - ((a + b) * x) / (a + 1);
  if (Math.abs(d) < tiny) d = tiny;
  d = 1 / d;
  let h = d;
  for (let m = 1; m <= 10000; m++) {
    const m2 = 2 * m;
    let aa = (m * (b - m) * x) / ((a + m2 - 1) * (a + m2));
    d = 1 + aa * d;
    if (Math.abs(d) < tiny) d = tiny;
    c = 1 + aa / c;
    if (Math.abs(c) < tiny) c = tiny;
    d = 1 / d;
    h *= d * c;
    aa = (-(a + m) * (a + b + m) * x) / ((a + m2) * (a + m2 + 1));
    d = 1 + aa * d;
    if (Math.abs(d) < tiny) d = tiny;
    c = 1 + aa / c;
    if (Math.abs(c) < tiny) c = tiny;
    d = 1 / d;
    const del = d * c;
    h *= del;
    if (Math.abs(del - 1) < 1e-15) break;
  }
  return h;
}

/** Regularised incomplete beta I_x(a, b). */
export function incompleteBeta(a: number, b: number, x: number): number {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  const front = Math.exp(
    logGamma(a + b) - logGamma(a) - logGamma(b) + a * Math.log(x) + b * Math.log(1 - x),
  );
  // The continued fraction converges fast for x < (a + 1) / (a + b + 2); use symmetry otherwise.
  if (x < (a + 1) / (a + b + 2)) return (front * betaContinuedFraction(a, b, x)) / a;
  return 1 - (front * betaContinuedFraction(b, a, 1 - x)) / b;
}

/** P(|T| ≥ |t|) for Student's t with ν degrees of freedom (ν may be fractional). */
export function studentTwoSided(t: number, nu: number): number {
  if (!Number.isFinite(t)) return 0;
  return incompleteBeta(nu / 2, 0.5, nu / (nu + t * t));
}

/** erfc(x) for x ≥ 0 (Numerical Recipes' Chebyshev fit, relative error < 1.2e-7). */
export function erfc(x: number): number {
  const z = Math.abs(x);
  const t = 1 / (1 + 0.5 * z);
  const r =
    t *
    Math.exp(
      -z * z -
        1.26551223 +
        t *
          (1.00002368 +
            t *
              (0.37409196 +
                t *
                  (0.09678418 +
                    t *
                      (-0.18628806 +
                        t *
                          (0.27886807 +
                            t *
                              (-1.13520398 +
                                t * (1.48851587 + t * (-0.82215223 + t * 0.17087277)))))))),
    );
  return x >= 0 ? r : 2 - r;
}

/** P(|Z| ≥ z) for a standard normal Z. */
export function normalTwoSided(z: number): number {
  return erfc(Math.abs(z) / Math.SQRT2);
}

/** The z with P(|Z| ≥ z) = p (bisection; p in (1e-300, 1)). */
export function normalQuantileTwoSided(p: number): number {
  let lo = 0;
  let hi = 40;
  for (let i = 0; i < 200; i++) {
    const mid = (lo + hi) / 2;
    if (normalTwoSided(mid) > p) lo = mid;
    else hi = mid;
  }
  return (lo + hi) / 2;
}

export interface WelchResult {
  t: number;
  /** Welch–Satterthwaite degrees of freedom. */
  nu: number;
  /** Two-sided p-value. */
  p: number;
}

/**
 * Welch's test of equal means from two estimates with variances of the
 * mean `va`, `vb` on `dfa`, `dfb` degrees of freedom. A variance known
 * exactly (a floor, or zero) is passed with dof Infinity.
 */
export function welch(
  ma: number,
  va: number,
  dfa: number,
  mb: number,
  vb: number,
  dfb: number,
): WelchResult {
  const v = va + vb;
  const diff = ma - mb;
  if (v === 0) return { t: diff === 0 ? 0 : Infinity, nu: Infinity, p: diff === 0 ? 1 : 0 };
  const t = diff / Math.sqrt(v);
  const denom = (dfa === Infinity ? 0 : (va * va) / dfa) + (dfb === Infinity ? 0 : (vb * vb) / dfb);
  const nu = denom === 0 ? Infinity : (v * v) / denom;
  const p = nu === Infinity || nu > 1e6 ? normalTwoSided(t) : studentTwoSided(t, nu);
  return { t, nu, p };
}
