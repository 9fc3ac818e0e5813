/**
 * Exact, order-independent sums of samples, so that a render split by
 * samples across threads, processes or machines, merged in any order,
 * gives the same bits as one long run (see docs/film-format.md).
 *
 * Floating-point addition is not associative, so no floating sum — Kahan
 * compensated or not — can promise the same bits for every way of cutting
 * the samples of a pixel into ranges. Integer addition can. Each sample
 * value v (a double) is rounded once to a fixed-point integer
 *
 *   q = round(v · 2^40)            (units of 2^-40 ≈ 9.1e-13)
 *
 * and the integers are summed exactly. The sum lives in two doubles, both
 * holding integers exactly:
 *
 *   total = hi · 2^52 + lo,   0 ≤ lo < 2^52,   |hi| < 2^53
 *
 * — a 105-bit integer, unique for each total (canonical), so any order of
 * additions and any grouping (parts, checkpoints, threads) leaves the same
 * (hi, lo). This is the pre-rounding idea of reproducible summation
 * (Demmel & Nguyen, "Fast Reproducible Floating-Point Summation", ARITH
 * 2013) with a fixed, global grid instead of a data-dependent one.
 *
 * Range. A sample with |v| > SAMPLE_LIMIT = 2^40 (≈ 1.1e12) is rejected
 * like a NaN (counted, never added); with at most MAX_COUNT = 2^24 samples
 * per pixel |total| stays below 2^104 units, inside the representation.
 * Resolution: 2^-41 absolute per sample, i.e. a relative error of 5e-9 for
 * a sample of 1e-4 — far below the Float32 display sums' 6e-8.
 *
 * Why every step is exact (q an integer-valued double, |q| ≤ 2^81):
 * q · 2^-52 is a power-of-two scaling, floor of it is qh; q − qh·2^52 lies
 * in [0, 2^52) and is a multiple of ulp(q) (which divides 2^52), so it is
 * representable; lo + that < 2^53. All are integers below 2^53 or exact
 * multiples of a power of two, so no operation rounds.
 */

/** Fixed-point fraction bits: one unit is 2^-SCALE_BITS. */
export const SCALE_BITS = 40;
export const SCALE = 2 ** SCALE_BITS;
export const INV_SCALE = 2 ** -SCALE_BITS;
/** The low limb holds [0, LIMB). */
export const LIMB = 2 ** 52;
export const INV_LIMB = 2 ** -52;
/** Largest |sample| added; beyond it a sample is rejected. */
export const SAMPLE_LIMIT = 2 ** 40;
/** Most samples a pixel may hold (also where a Float32 count stops being exact). */
export const MAX_COUNT = 2 ** 24;
/** Largest |hi| a pixel with `count` samples can reach (SAMPLE_LIMIT · count in units / LIMB). */
export const HI_PER_SAMPLE = (SAMPLE_LIMIT * SCALE) / LIMB;

/**
 * Adds v (|v| ≤ SAMPLE_LIMIT, not NaN: the caller checks) to the exact
 * sum (hi[i], lo[i]) and returns the new sum as a double.
 *
 * Rounding is to nearest, ties to even, done with the 2^52 trick: for
 * 0 ≤ x < 2^52, x + 2^52 lies where doubles are the integers, so the
 * addition itself rounds x (IEEE 754 round-to-nearest-even) and
 * subtracting 2^52 back is exact. That is the common case (0 ≤ v < 4096)
 * and needs no Math.round or Math.floor; the rest takes the general path.
 */
export function addFixed(hi: Float64Array, lo: Float64Array, i: number, v: number): number {
  const x = v * SCALE;
  let l: number;
  let h = hi[i];
  if (x >= 0 && x < LIMB) {
    l = lo[i] + (x + LIMB - LIMB);
  } else {
    // |x| ≥ 2^52 is already an integer; a negative x is rounded as −round(−x).
    const q = x > -LIMB && x < 0 ? -(-x + LIMB - LIMB) : x;
    const qh = Math.floor(q * INV_LIMB);
    l = lo[i] + (q - qh * LIMB);
    h += qh;
  }
  if (l >= LIMB) {
    l -= LIMB;
    h += 1;
  }
  lo[i] = l;
  hi[i] = h;
  return (h * LIMB + l) * INV_SCALE;
}

/** Adds the exact sum (h, l) to (hi[i], lo[i]). */
export function addExact(
  hi: Float64Array,
  lo: Float64Array,
  i: number,
  h: number,
  l: number,
): void {
  let sl = lo[i] + l;
  let sh = hi[i] + h;
  if (sl >= LIMB) {
    sl -= LIMB;
    sh += 1;
  }
  lo[i] = sl;
  hi[i] = sh;
}

/**
 * The exact sum (hi[i], lo[i]) as a double (rounded once, to nearest).
 * This one formula is used wherever a sum is read, so a value derived
 * from the same exact sum is always the same bits.
 */
export function exactValue(hi: Float64Array, lo: Float64Array, i: number): number {
  return (hi[i] * LIMB + lo[i]) * INV_SCALE;
}

/**
 * Whether (h, l) is a canonical exact sum that `count` samples can reach:
 * both integers, 0 ≤ l < 2^52, |h| within the count's bound. Rejects NaN.
 * (A −0 passes; callers store h + 0 and l + 0, which is +0.)
 */
export function isValidExact(h: number, l: number, count: number): boolean {
  return (
    Number.isInteger(l) &&
    l >= 0 &&
    l < LIMB &&
    Number.isInteger(h) &&
    Math.abs(h) <= HI_PER_SAMPLE * count
  );
}
