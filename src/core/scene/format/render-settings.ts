/**
 * The render's settings: everything besides the scene that changes a sample's value.
 * One type for every hop — the command line's render, the Node and browser workers'
 * jobs, the tracer, a `.film` header (docs/film-format.md) — each of which extends it
 * with what it alone needs and passes it on whole.
 */
import type { SamplerKind } from '../../sampling/sampler.ts';

/** Next-event estimation with MIS, or BSDF sampling only (integrator/trace-path.ts). */
export type Estimator = 'nee-mis' | 'bsdf';

export interface RenderSettings {
  width: number;
  height: number;
  /** Scattering events per path at most. */
  maxBounces: number;
  /** Seed of every pixel's sample sequence, an integer in [0, 2^32). */
  seed: number;
  estimator: Estimator;
  sampler: SamplerKind;
  /**
   * Adaptive sampling (film/adaptive.ts): after a uniform pilot, each pixel takes the
   * later passes at a rate set by its neighbours' pilot error. Absent or false: every
   * pixel takes every pass. It changes which samples a film holds, so it is part of a
   * film's settings and key, written only when true (a uniform render's header and key
   * are what they were before adaptive sampling existed).
   */
  adaptive?: boolean;
}

/**
 * The settings' keys in the `.film` header's order: a film's key hashes them in this
 * order, so it is part of the format. `adaptive` is written only when true.
 */
export const RENDER_SETTING_KEYS = [
  'width',
  'height',
  'maxBounces',
  'seed',
  'sampler',
  'estimator',
  'adaptive',
] as const satisfies readonly (keyof RenderSettings)[];

/** Exactly the render settings of `source` (an object that extends them), in header order. */
export function renderSettingsOf(source: RenderSettings): RenderSettings {
  return {
    width: source.width,
    height: source.height,
    maxBounces: source.maxBounces,
    seed: source.seed,
    sampler: source.sampler,
    estimator: source.estimator,
    ...(source.adaptive === true ? { adaptive: true } : {}),
  };
}
