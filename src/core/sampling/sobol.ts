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
import { INV_2_32, hashToUnit, pcgHashBits, sampleKey } from '../rng/pcg.ts';

/**
 * Dimensions [0, SOBOL_DIMENSIONS) come from this module: the camera (film
 * 0–1, lens 2–3) and the first bounce (4–11, see sampler.ts). Deeper
 * bounces carry little of the variance after the first has been
 * stratified, and the PCG hash is cheaper.
 */
export const SOBOL_DIMENSIONS = 12;

/**
 * How the leading dimensions are grouped, following the layout of
 * sampler.ts: film (0,1), lens (2,3), then the first bounce from
 * DIM_BOUNCE = 4: light point (5,6) and BSDF direction (7,8). Each group is
 * a 2D Sobol pair ([first dimension, size]; size 1 would be van der Corput,
 * which the fill also supports). The first bounce's light choice (4), lobe
 * choice (9), roulette (10, never drawn: roulette starts at the third
 * bounce) and dimension 11 stay on the hash: the canonical scenes have one
 * emitter and few two-lobe surfaces, so stratifying those 1D choices bought
 * less error than its cost in time (bench/run.mjs, equal-time study).
 */
export const SOBOL_GROUPS: readonly (readonly [number, number])[] = [
  [0, 2],
  [2, 2],
  [5, 2],
  [7, 2],
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
  // Bit reversal is linear over XOR, so the reversed table is built the same
  // way from reversed directions.
  if (reversed) for (let i = 0; i < 32; i++) dirs[i] = reverseBits32(dirs[i]);
  // Entry v of byte b is the XOR of the directions of v's set bits: entry
  // h + v (v < h = 2^bit) is entry v XOR direction `bit`, one XOR per entry
  // (this runs at start-up, in every worker, before V8 optimises anything).
  const table = new Uint32Array(4 * 256);
  for (let b = 0; b < 4; b++) {
    const t = b * 256;
    for (let bit = 0; bit < 8; bit++) {
      const d = dirs[b * 8 + bit];
      const h = 1 << bit;
      for (let v = 0; v < h; v++) table[t + h + v] = table[t + v] ^ d;
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
  return pixelKeyBits(seed, pixel) >>> 0;
}

/** pixelKey as a signed 32-bit integer (see pcgHashBits). */
export function pixelKeyBits(seed: number, pixel: number): number {
  return pcgHashBits((seed + pcgHashBits(pixel | 0)) | 0);
}

/** SOBOL_GROUPS as flat typed arrays for the fill loop. */
const GROUP_FIRST = Int32Array.from(SOBOL_GROUPS, (g) => g[0]);
const GROUP_SIZE = Int32Array.from(SOBOL_GROUPS, (g) => g[1]);
const GROUP_COUNT = SOBOL_GROUPS.length;

/** Per dimension < SOBOL_DIMENSIONS: its group, or −1 for a hashed one. */
export const SOBOL_GROUP_OF = new Int8Array(SOBOL_DIMENSIONS).fill(-1);
SOBOL_GROUPS.forEach(([first, size], g) => SOBOL_GROUP_OF.fill(g, first, first + size));

/** sobolFill's `skip` mask for the lens group (dimensions 2–3). */
export const SOBOL_NO_LENS = 1 << SOBOL_GROUP_OF[2];

/** Length of the key array of one pixel (sobolPixelKeys): three keys per group. */
export const SOBOL_PIXEL_KEYS = 3 * GROUP_COUNT;

/**
 * The hash keys of one pixel, for every group g (key = pixelKey(seed,
 * pixel), either form): gk = pcgHash(key + (g + 1)·φ), the key of the
 * index shuffle (the odd multiplier spreads small g), and the keys of the
 * two coordinates' scrambles, pcgHash(gk ^ A) and pcgHash(gk ^ B), as
 * keys[3g], keys[3g + 1], keys[3g + 2] (int32). They depend on the pixel
 * only: a sampler drawing several samples of one pixel computes them once.
 */
export function sobolPixelKeys(key: number, keys: Int32Array): void {
  for (let g = 0; g < GROUP_COUNT; g++) {
    let h = (key + Math.imul(g + 1, 0x9e3779b9)) | 0;
    h = (Math.imul(h, 747796405) + 2891336453) | 0;
    h = Math.imul((h >>> ((h >>> 28) + 4)) ^ h, 277803737);
    const gk = (h >>> 22) ^ h;
    keys[3 * g] = gk;
    keys[3 * g + 1] = pcgHashBits(gk ^ 0x68e31da4);
    keys[3 * g + 2] = pcgHashBits(gk ^ 0xb5297a4d);
  }
}

/** Scratch keys of sobolFill. */
const FILL_KEYS = new Int32Array(SOBOL_PIXEL_KEYS);

/**
 * Fills the dimensions of every group of out[0 .. SOBOL_DIMENSIONS) with the
 * low-discrepancy numbers of one (pixel, sample), but the groups whose bit
 * is set in `skip`; `key` is pixelKey(seed, pixel) (either form: only its
 * bits count). Dimensions in no group are left alone: the sampler hashes
 * them, as sobolSample does.
 */
export function sobolFill(key: number, sample: number, out: Float64Array, skip = 0): void {
  sobolPixelKeys(key, FILL_KEYS);
  sobolFillKeyed(FILL_KEYS, sample, out, skip);
}

/**
 * sobolFill with the pixel's keys already computed (sobolPixelKeys).
 * For group g with keys gk, k0, k1:
 *   index = owenScramble(sample, gk)                      (the shuffle)
 *   out[first]     = owenScramble(vdc(index), k0)
 *   out[first + 1] = owenScramble(sobol1(index), k1)
 * Written to do few bit reversals: with rs the reversed sample, the index is
 * rev(LK_gk(rs)); the van der Corput point of index i is rev(i), so its
 * scramble rev(LK(rev(rev(i)))) is rev(LK(i)); rev(sobol1(i)) comes from a
 * reversed table, so its scramble is rev(LK(table(i))). Everything is
 * inlined by hand: this runs once per path and the profiler showed the
 * helper calls (not inlined by V8 at this size) costing as much as the
 * arithmetic.
 */
export function sobolFillKeyed(
  keys: Int32Array,
  sample: number,
  out: Float64Array,
  skip = 0,
): void {
  const t = SOBOL1_REV_TABLE;
  let rs = sample >>> 0;
  rs = ((rs >>> 1) & 0x55555555) | ((rs & 0x55555555) << 1);
  rs = ((rs >>> 2) & 0x33333333) | ((rs & 0x33333333) << 2);
  rs = ((rs >>> 4) & 0x0f0f0f0f) | ((rs & 0x0f0f0f0f) << 4);
  rs = ((rs >>> 8) & 0x00ff00ff) | ((rs & 0x00ff00ff) << 8);
  rs = (rs >>> 16) | (rs << 16);
  for (let g = 0; g < GROUP_COUNT; g++) {
    if ((skip >> g) & 1) continue;
    const gk = keys[3 * g];
    // Shuffled index, still bit-reversed: LK_gk(rs) (see lkPermute).
    let x = rs ^ Math.imul(rs, 0x3d20adea);
    x = (x + gk) | 0;
    x = Math.imul(x, (gk >>> 16) | 1);
    x ^= Math.imul(x, 0x05526c56);
    x ^= Math.imul(x, 0x53a22864);
    // index = rev(x)
    x = ((x >>> 1) & 0x55555555) | ((x & 0x55555555) << 1);
    x = ((x >>> 2) & 0x33333333) | ((x & 0x33333333) << 2);
    x = ((x >>> 4) & 0x0f0f0f0f) | ((x & 0x0f0f0f0f) << 4);
    x = ((x >>> 8) & 0x00ff00ff) | ((x & 0x00ff00ff) << 8);
    const index = ((x >>> 16) | (x << 16)) >>> 0;
    const first = GROUP_FIRST[g];
    scrambleInto(index, keys[3 * g + 1], out, first);
    if (GROUP_SIZE[g] === 2) {
      const v1 =
        t[index & 255] ^
        t[256 + ((index >>> 8) & 255)] ^
        t[512 + ((index >>> 16) & 255)] ^
        t[768 + (index >>> 24)];
      scrambleInto(v1, keys[3 * g + 2], out, first + 1);
    }
  }
}

/**
 * out[at] = rev(LK_k(y)) · 2^-32: the Owen-scrambled coordinate whose
 * bit-reversed digits are y, in [0, 1). Written to the array rather than
 * returned: a returned double is boxed when the call is not inlined.
 */
function scrambleInto(y: number, k: number, out: Float64Array, at: number): void {
  y ^= Math.imul(y, 0x3d20adea);
  y = (y + k) | 0;
  y = Math.imul(y, (k >>> 16) | 1);
  y ^= Math.imul(y, 0x05526c56);
  y ^= Math.imul(y, 0x53a22864);
  y = ((y >>> 1) & 0x55555555) | ((y & 0x55555555) << 1);
  y = ((y >>> 2) & 0x33333333) | ((y & 0x33333333) << 2);
  y = ((y >>> 4) & 0x0f0f0f0f) | ((y & 0x0f0f0f0f) << 4);
  y = ((y >>> 8) & 0x00ff00ff) | ((y & 0x00ff00ff) << 8);
  out[at] = (((y >>> 16) | (y << 16)) >>> 0) * INV_2_32;
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
  const seedU = seed >>> 0;
  // Dimensions in no group use the same sample key as the hash sampler.
  if (SOBOL_GROUP_OF[dimension] < 0) return hashToUnit(sampleKey(seedU, pixel, sample), dimension);
  const out = new Float64Array(SOBOL_DIMENSIONS);
  sobolFill(pixelKey(seedU, pixel), sample, out);
  return out[dimension];
}
