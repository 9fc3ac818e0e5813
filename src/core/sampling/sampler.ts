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
 *   point (2), BSDF direction (2), BSDF lobe, Russian roulette.
 */
import { hashToUnit, sampleKey } from '../rng/pcg.ts';

export const DIM_FILM = 0;
export const DIM_LENS = 2;
export const DIM_BOUNCE = 4;
export const DIM_PER_BOUNCE = 8;
export const DIM_LIGHT_CHOICE = 0;
export const DIM_LIGHT_POINT = 1;
export const DIM_BSDF = 3;
export const DIM_BSDF_LOBE = 5;
export const DIM_ROULETTE = 6;

export type SamplerKind = 'independent';

/** Independent uniform samples from the PCG hash. */
export class IndependentSampler {
  readonly seed: number;
  private key = 0;

  constructor(seed: number) {
    this.seed = seed >>> 0;
  }

  startPixelSample(pixelIndex: number, sampleIndex: number): void {
    this.key = sampleKey(this.seed, pixelIndex, sampleIndex);
  }

  get1D(dimension: number): number {
    return hashToUnit(this.key, dimension);
  }
}
