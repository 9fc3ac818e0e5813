/**
 * Owen-scrambled Sobol samples for the leading dimensions of a path, after
 * Burley, "Practical Hash-based Owen Scrambling" (JCGT 9(4), 2020).
 *
 * For each pixel and each *group* of dimensions (a 2D pair such as the film
 * position, or a single dimension such as the light choice):
 *   1. the sample index is shuffled by a nested uniform (Owen) scramble keyed
 *      by a PCG hash of (seed, pixel, group). Owen-scrambling an index keeps
 *      every aligned block of 2^k indices inside one aligned block, so the
 *      first 2^k samples of a pixel are still a whole (0,k,2)-net — the
 *      shuffle only decorrelates the groups from each other (Burley §4,
 *      "padding" in the sense of Kollig & Keller 2002);
 *   2. the shuffled index selects a point of the 2D Sobol (0,2)-sequence
 *      (dimension 0 = van der Corput, dimension 1 = the Pascal-matrix
 *      dimension), or of van der Corput alone for a 1D group;
 *   3. each coordinate is Owen-scrambled with its own hash key, which keeps
 *      the net property (Owen 1995) and makes the estimator unbiased.
 * Only the first two Sobol dimensions are ever used: they form a
 * (0,2)-sequence, so every power-of-two prefix is stratified in every
 * elementary interval, which higher Sobol dimensions do not guarantee.
 *
 * Everything is a pure function of (seed, pixel, sample, dimension), like
 * the PCG hash sampler, so the image does not depend on thread count or
 * stripe layout.
 */
import { INV_2_32, hashToUnit, pcgHash, sampleKey } from '../rng/pcg.ts';

/**
 * Dimensions [0, SOBOL_DIMENSIONS) come from this module: the camera (film
 * 0–1, lens 2–3) and the first bounce (4–11, see sampler.ts). Deeper
 * bounces carry little of the variance after the first has been
 * stratified, and the PCG hash is cheaper.
 */
export const SOBOL_DIMENSIONS = 12;
export const SOBOL_IMPLEMENTED = true;

/**
 * How the leading dimensions are grouped, following the layout of
 * sampler.ts: film (0,1), lens (2,3), then first bounce from DIM_BOUNCE = 4:
 * light choice (4), light point (5,6), BSDF direction (7,8), BSDF lobe (9).
 * A group of size 2 is a 2D Sobol pair; size 1 is van der Corput. Each
 * entry: [first dimension, size]. Dimension 10 (Russian roulette of the
 * first bounce: roulette starts at the third) and 11 (unused) stay on the
 * hash, as does everything from the second bounce on.
 */
export const SOBOL_GROUPS: readonly (readonly [number, number])[] = [
  [0, 2],
  [2, 2],
  [4, 1],
  [5, 2],
  [7, 2],
  [9, 1],
];

/** Reverses the 32 bits of x (returns an unsigned 32-bit integer). */
export function reverseBits32(x: number): number {
  x = ((x >>> 1) & 0x55555555) | ((x & 0x55555555) << 1);
  x = ((x >>> 2) & 0x33333333) | ((x & 0x33333333) << 2);
  x = ((x >>> 4) & 0x0f0f0f0f) | ((x & 0x0f0f0f0f) << 4);
  x = ((x >>> 8) & 0x00ff00ff) | ((x & 0x00ff00ff) << 8);
  return ((x >>> 16) | (x << 16)) >>> 0;
}

/**
 * Nested uniform scramble of a 32-bit fixed-point number (bit 31 = first
 * binary digit). Burley's construction: reverse the bits, apply a
 * Laine–Karras-style permutation (each output bit depends only on the same
 * and lower input bits), reverse back — so the flip of each digit depends
 * only on the digits before it, which is Owen's scramble. The permutation
 * constants are Vegdahl's improved hash ("Building a Better LK Hash", 2021),
 * which fixes the weak high bits of Burley's original constants.
 */
export function owenScramble(x: number, seed: number): number {
  return reverseBits32(lkPermute(reverseBits32(x), seed));
}

/**
 * The permutation in the bit-reversed domain (see owenScramble): output bit
 * i depends only on input bits 0..i.
 */
function lkPermute(x: number, seed: number): number {
  x ^= Math.imul(x, 0x3d20adea);
  x = (x + seed) | 0;
  x = Math.imul(x, (seed >>> 16) | 1);
  x ^= Math.imul(x, 0x05526c56);
  x ^= Math.imul(x, 0x53a22864);
  return x;
}

/**
 * Second Sobol dimension (primitive polynomial x + 1; its generator is the
 * Pascal matrix mod 2): direction v_0 = 2^31, v_i = v_{i−1} ^ (v_{i−1} >> 1).
 * Tabulated per byte of the index so one point costs four lookups.
 */
function sobol1Table(reversed: boolean): Uint32Array {
  const dirs = new Uint32Array(32);
  dirs[0] = 0x80000000;
  for (let i = 1; i < 32; i++) dirs[i] = dirs[i - 1] ^ (dirs[i - 1] >>> 1);
  const table = new Uint32Array(4 * 256);
  for (let b = 0; b < 4; b++) {
    for (let v = 0; v < 256; v++) {
      let x = 0;
      for (let bit = 0; bit < 8; bit++) if (v & (1 << bit)) x ^= dirs[b * 8 + bit];
      // Bit reversal is linear over XOR, so the reversed point is the XOR
      // of reversed directions.
      table[b * 256 + v] = reversed ? reverseBits32(x) : x >>> 0;
    }
  }
  return table;
}
const SOBOL1_TABLE = sobol1Table(false);
/** The same, each entry bit-reversed: yields reverseBits32(sobol1(i)). */
const SOBOL1_REV_TABLE = sobol1Table(true);

/** Sobol dimension 1 of index i, as a 32-bit fixed-point number. */
export function sobol1(i: number): number {
  const t = SOBOL1_TABLE;
  return (
    (t[i & 255] ^
      t[256 + ((i >>> 8) & 255)] ^
      t[512 + ((i >>> 16) & 255)] ^
      t[768 + (i >>> 24)]) >>>
    0
  );
}

/** Key of one (seed, pixel) pair; the group keys derive from it. */
export function pixelKey(seed: number, pixel: number): number {
  return pcgHash((seed + pcgHash(pixel >>> 0)) >>> 0);
}

/**
 * Fills out[0 .. SOBOL_DIMENSIONS) with the low-discrepancy numbers of one
 * (pixel, sample); `key` is pixelKey(seed, pixel), and `sampleKeyValue` is
 * the PCG sample key, used for the dimensions no group covers.
 *
 * Written to do few bit reversals (they dominate the cost): with rs the
 * reversed sample index, the shuffled index is rev(LK_g(rs)); the van der
 * Corput point of index i is rev(i), so its Owen scramble
 * rev(LK(rev(rev(i)))) is rev(LK(i)); and rev(sobol1(i)) comes from a
 * reversed table, so its scramble is rev(LK(table(i))).
 */
export function sobolFill(
  key: number,
  sample: number,
  sampleKeyValue: number,
  out: Float64Array,
): void {
  const rs = reverseBits32(sample >>> 0);
  fillPair(out, 0, key, 1, rs);
  fillPair(out, 2, key, 2, rs);
  fillSingle(out, 4, key, 3, rs);
  fillPair(out, 5, key, 4, rs);
  fillPair(out, 7, key, 5, rs);
  fillSingle(out, 9, key, 6, rs);
  out[10] = hashToUnit(sampleKeyValue, 10);
  out[11] = hashToUnit(sampleKeyValue, 11);
}

/** Shuffled Sobol index of group g: Owen scramble keyed per (seed, pixel, group). */
function groupKeyOf(key: number, g: number): number {
  // The odd multiplier only spreads the small group numbers before hashing.
  return pcgHash((key + Math.imul(g, 0x9e3779b9)) >>> 0);
}

function fillPair(out: Float64Array, first: number, key: number, g: number, rs: number): void {
  const gk = groupKeyOf(key, g);
  const index = reverseBits32(lkPermute(rs, gk));
  out[first] = reverseBits32(lkPermute(index, pcgHash(gk ^ 0x68e31da4))) * INV_2_32;
  const t = SOBOL1_REV_TABLE;
  const v1 =
    t[index & 255] ^
    t[256 + ((index >>> 8) & 255)] ^
    t[512 + ((index >>> 16) & 255)] ^
    t[768 + (index >>> 24)];
  out[first + 1] = reverseBits32(lkPermute(v1, pcgHash(gk ^ 0xb5297a4d))) * INV_2_32;
}

function fillSingle(out: Float64Array, first: number, key: number, g: number, rs: number): void {
  const gk = groupKeyOf(key, g);
  const index = reverseBits32(lkPermute(rs, gk));
  out[first] = reverseBits32(lkPermute(index, pcgHash(gk ^ 0x68e31da4))) * INV_2_32;
}

/**
 * The number of dimension `dimension` < SOBOL_DIMENSIONS of sample `sample`
 * of pixel `pixel`: the reference form, used by tests; the sampler calls
 * sobolFill once per (pixel, sample) instead.
 */
export function sobolSample(
  seed: number,
  pixel: number,
  sample: number,
  dimension: number,
): number {
  if (dimension < 0 || dimension >= SOBOL_DIMENSIONS || !Number.isInteger(dimension)) {
    throw new RangeError(`sobol dimension ${dimension} outside [0, ${SOBOL_DIMENSIONS})`);
  }
  const out = new Float64Array(SOBOL_DIMENSIONS);
  const seedU = seed >>> 0;
  // The fallback dimension uses the same sample key as the hash sampler.
  sobolFill(pixelKey(seedU, pixel), sample, sampleKey(seedU, pixel, sample), out);
  return out[dimension];
}
