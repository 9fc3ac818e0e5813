/**
 * PCG hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020):
 * a stateless 32-bit permutation built from one step of a PCG LCG and its
 * RXS-M-XS output function. Being a pure function of its input, it lets any
 * worker compute any (pixel, sample, dimension) in any order, which is what
 * keeps renders bit-identical across thread counts and stripe layouts.
 */
export function pcgHash(input: number): number {
  return pcgHashBits(input) >>> 0;
}

/**
 * The same permutation with its result as a signed 32-bit integer (the same
 * bits). Hot code hashes with this form: a result above 2^31 does not fit
 * V8's small integers, so an unsigned one returned from a call that is not
 * inlined is boxed on the heap (the profiler found a sixth of the Cornell
 * render's allocations there).
 */
export function pcgHashBits(input: number): number {
  const state = (Math.imul(input, 747796405) + 2891336453) | 0;
  const word = Math.imul((state >>> ((state >>> 28) + 4)) ^ state, 277803737);
  return (word >>> 22) ^ word;
}

/** 2^-32: maps a 32-bit integer into [0, 1). */
export const INV_2_32 = 1 / 4294967296;

/**
 * Key of one (seed, pixel, sample) triple. Nesting the hash (rather than
 * adding the inputs) keeps e.g. (pixel 1, sample 0) and (pixel 0, sample 1)
 * unrelated.
 */
export function sampleKey(seed: number, pixelIndex: number, sampleIndex: number): number {
  return sampleKeyBits(seed, pixelIndex, sampleIndex) >>> 0;
}

/** sampleKey as a signed 32-bit integer (see pcgHashBits). */
export function sampleKeyBits(seed: number, pixelIndex: number, sampleIndex: number): number {
  return pcgHashBits((seed + pcgHashBits((pixelIndex + pcgHashBits(sampleIndex | 0)) | 0)) | 0);
}

/** Uniform number in [0, 1) for one dimension of the sample keyed by `key`. */
export function hashToUnit(key: number, dimension: number): number {
  return pcgHash((key + Math.imul(dimension, 0x9e3779b9)) >>> 0) * INV_2_32;
}
