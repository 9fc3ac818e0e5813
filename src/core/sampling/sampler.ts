/**
 * Where the random numbers of one (pixel, sample) come from. Every number
 * is a pure function of (seed, pixel, sample, dimension), so any worker can
 * compute any sample in any order and the image is bit-identical whatever
 * the thread count or stripe layout.
 *
 * Dimensions are assigned by role, not by a running counter, so that a
 * path that skips a step (no light sampling on glass, say) does not shift
 * the numbers of later bounces:
 *   0–1 film position, 2–3 lens position,
 *   per bounce b, from DIM_BOUNCE + b·DIM_PER_BOUNCE: light choice, light
 *   point (2), BSDF direction (2), BSDF lobe, Russian roulette, alpha.
 */
import { INV_2_32, hashToUnit, sampleKeyBits } from '../rng/pcg.ts';
import {
  SOBOL_DIMENSIONS,
  SOBOL_GROUP_OF,
  SOBOL_NO_LENS,
  SOBOL_PIXEL_KEYS,
  pixelKeyBits,
  sobolFillKeyed,
  sobolPixelKeys,
} from './sobol.ts';

export const DIM_FILM = 0;
export const DIM_LENS = 2;
export const DIM_BOUNCE = 4;
export const DIM_PER_BOUNCE = 8;
export const DIM_LIGHT_CHOICE = 0;
export const DIM_LIGHT_POINT = 1;
export const DIM_BSDF = 3;
export const DIM_BSDF_LOBE = 5;
export const DIM_ROULETTE = 6;
/**
 * Whether a path passes through a surface with alpha (glTF MASK/BLEND): the first
 * such surface after bounce b uses this dimension of the bounce; further ones in the
 * same segment use DIM_ALPHA_EXTRA + b·DIM_ALPHA_STRIDE + k (hashed numbers).
 */
export const DIM_ALPHA = 7;
export const DIM_ALPHA_EXTRA = 1 << 24;
export const DIM_ALPHA_STRIDE = 4096;

export type SamplerKind = 'independent' | 'sobol';
export const SAMPLER_KINDS: readonly SamplerKind[] = ['independent', 'sobol'];
/**
 * The default, chosen by `npm run bench` (BENCHMARKS.md): Owen-scrambled
 * Sobol gives lower error than independent samples at equal spp on every
 * canonical scene and at equal time overall.
 */
export const DEFAULT_SAMPLER: SamplerKind = 'sobol';

/**
 * The sampler of a tracer. 'independent' draws every dimension from the
 * PCG hash; 'sobol' draws the leading dimensions (camera, lens, first
 * bounce) from a low-discrepancy sequence randomised per pixel (see
 * sobol.ts) and the rest from the PCG hash. One class with a kind tag keeps
 * the call sites in the tracer monomorphic.
 */
export class Sampler {
  readonly seed: number;
  readonly kind: SamplerKind;
  private readonly lowDiscrepancy: boolean;
  private key = 0;
  /** Low-discrepancy numbers of the current (pixel, sample), filled once in startPixelSample. */
  private readonly ld = new Float64Array(SOBOL_DIMENSIONS);
  /** The Sobol keys of pixel `keysPixel` (they depend on the pixel only). */
  private readonly pixelKeys = new Int32Array(SOBOL_PIXEL_KEYS);
  private keysPixel = -1;

  constructor(seed: number, kind: SamplerKind = DEFAULT_SAMPLER) {
    this.seed = seed >>> 0;
    this.kind = kind;
    this.lowDiscrepancy = kind === 'sobol';
  }

  /**
   * Starts sample `sampleIndex` of pixel `pixelIndex`. `lens` false skips
   * the lens dimensions (a pinhole camera never reads them); every other
   * number is the same either way.
   */
  startPixelSample(pixelIndex: number, sampleIndex: number, lens = true): void {
    this.key = sampleKeyBits(this.seed, pixelIndex, sampleIndex);
    // The low-discrepancy groups are computed here, once per path: fill()
    // then reads them, and hashes the dimensions no group covers.
    if (this.lowDiscrepancy) {
      // Consecutive samples of one pixel (PathTracer.renderRow) share its keys.
      if (pixelIndex !== this.keysPixel) {
        sobolPixelKeys(pixelKeyBits(this.seed, pixelIndex), this.pixelKeys);
        this.keysPixel = pixelIndex;
      }
      sobolFillKeyed(this.pixelKeys, sampleIndex, this.ld, lens ? 0 : SOBOL_NO_LENS);
    }
  }

  /**
   * Writes dimensions [dimension, dimension + count) into out[0…count).
   * The tracer calls this rather than get1D: numbers written to a typed
   * array stay unboxed, where a returned double that is not inlined would
   * be allocated on the heap.
   */
  fill(dimension: number, count: number, out: Float64Array): void {
    this.fillRange(dimension, 0, count, out);
  }

  /**
   * Like fill, for dimensions dimension + k with k in [from, to), each into
   * out[k]; the rest of out is left as it was. A bounce draws only the
   * numbers it reads (no light numbers on a mirror, no light choice with one
   * light): every number is the same function of its dimension, so skipping
   * one changes no other.
   */
  fillRange(dimension: number, from: number, to: number, out: Float64Array): void {
    const key = this.key;
    for (let k = from; k < to; k++) {
      const d = dimension + k;
      if (this.lowDiscrepancy && d < SOBOL_DIMENSIONS && SOBOL_GROUP_OF[d] >= 0) {
        out[k] = this.ld[d];
      } else {
        // hashToUnit with the PCG hash inlined by hand, in int32 arithmetic.
        const input = (key + Math.imul(d, 0x9e3779b9)) | 0;
        const state = (Math.imul(input, 747796405) + 2891336453) | 0;
        const word = Math.imul((state >>> ((state >>> 28) + 4)) ^ state, 277803737);
        out[k] = (((word >>> 22) ^ word) >>> 0) * INV_2_32;
      }
    }
  }

  get1D(dimension: number): number {
    if (this.lowDiscrepancy && dimension < SOBOL_DIMENSIONS && SOBOL_GROUP_OF[dimension] >= 0) {
      return this.ld[dimension];
    }
    return hashToUnit(this.key >>> 0, dimension);
  }
}
