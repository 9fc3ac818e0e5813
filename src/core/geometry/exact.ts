/**
 * The exact sign of a·b − c·d for doubles, for the ray–triangle test's edge functions
 * when rounding could have flipped them (Shewchuk, "Adaptive Precision Floating-Point
 * Arithmetic and Fast Robust Geometric Predicates", 1997: the error-free transforms
 * Two-Product by Dekker's splitting, and Two-Two-Diff). JavaScript has no fused
 * multiply–add, so the products are split in halves of 26 bits. Exact while no product
 * overflows or underflows (|a|, |b|, |c|, |d| roughly within 1e-145 … 1e145).
 */

const SPLITTER = 134217729; // 2^27 + 1

/** Error bound of fl(a·b − c·d) relative to |a·b| + |c·d| (Shewchuk's ccwerrboundA). */
export const DIFF_OF_PRODUCTS_ERROR = (3 + 16 * 2 ** -53) * 2 ** -53;

/** The rounding error of p = fl(a·b): a·b = p + err exactly. */
function productError(a: number, b: number, p: number): number {
  let c = SPLITTER * a;
  const ahi = c - (c - a);
  const alo = a - ahi;
  c = SPLITTER * b;
  const bhi = c - (c - b);
  const blo = b - bhi;
  return alo * blo - (p - ahi * bhi - alo * bhi - ahi * blo);
}

/**
 * a·b − c·d with the correct sign (and exactly 0 when it is 0): the largest component
 * of the exact result as a non-overlapping expansion, which has the sign of the whole.
 */
export function exactDiffOfProducts(a: number, b: number, c: number, d: number): number {
  const p1 = a * b;
  const e1 = productError(a, b, p1);
  const p2 = c * d;
  const e2 = productError(c, d, p2);
  // Two-Two-Diff (p1 + e1) − (p2 + e2) = x3 + x2 + x1 + x0, non-overlapping.
  // Two-One-Diff(p1, e1, e2) → (j, k, x0).
  let s = e1 - e2;
  let bv = s - e1;
  const x0 = e1 - (s - bv) + (-e2 - bv);
  let j = p1 + s;
  bv = j - p1;
  const k = p1 - (j - bv) + (s - bv);
  // Two-One-Diff(j, k, p2) → (x3, x2, x1).
  s = k - p2;
  bv = s - k;
  const x1 = k - (s - bv) + (-p2 - bv);
  const x3 = j + s;
  bv = x3 - j;
  const x2 = j - (x3 - bv) + (s - bv);
  if (x3 !== 0) return x3;
  if (x2 !== 0) return x2;
  if (x1 !== 0) return x1;
  return x0;
}

/** x · 2^n, exact but for underflow, for any n in [-2046, 2046] (two steps: 2^n alone may not exist). */
export function mulPow2(x: number, n: number): number {
  const half = Math.trunc(n / 2);
  return x * 2 ** half * 2 ** (n - half);
}
