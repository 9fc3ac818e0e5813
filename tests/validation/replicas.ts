/**
 * Independent replicas of a render: the same scene rendered with K seeds,
 * reduced to per-seed means over image regions (the whole image, its four
 * quadrants and 8×8-pixel blocks), per channel. Seeds are independent
 * replicas for either sampler (the Sobol sampler's scrambling is keyed by
 * the seed), so the spread of the per-seed means across seeds is an
 * honest estimate of the variance of their average — for Sobol too, where
 * a per-sample variance s²/n would not be.
 */
import { renderAdaptiveFilm } from '../helpers/render.ts';
import {
  Film,
  PathTracer,
  RenderStats,
  type CompiledScene,
  type Estimator,
  type LightSamplerKind,
  type SamplerKind,
  type Scene,
} from '../../src/core/index.ts';

export interface Region {
  name: string;
  x0: number;
  y0: number;
  x1: number;
  y1: number;
}

/** The whole image, its quadrants and its 8×8 blocks (edge blocks may be smaller). */
export function imageRegions(width: number, height: number, block = 8): Region[] {
  const regions: Region[] = [{ name: 'image', x0: 0, y0: 0, x1: width, y1: height }];
  const hx = Math.ceil(width / 2);
  const hy = Math.ceil(height / 2);
  for (const [i, j] of [
    [0, 0],
    [1, 0],
    [0, 1],
    [1, 1],
  ]) {
    regions.push({
      name: `quadrant ${i},${j}`,
      x0: i * hx,
      y0: j * hy,
      x1: i === 0 ? hx : width,
      y1: j === 0 ? hy : height,
    });
  }
  for (let y = 0; y < height; y += block) {
    for (let x = 0; x < width; x += block) {
      regions.push({
        name: `block ${x / block},${y / block}`,
        x0: x,
        y0: y,
        x1: Math.min(width, x + block),
        y1: Math.min(height, y + block),
      });
    }
  }
  return regions;
}

export interface RenderConfig {
  estimator: Estimator;
  sampler: SamplerKind;
  /** The light choice of NEE (default: the light BVH). */
  lightSampler?: LightSamplerKind;
  /** Samples per pixel of each replica; with `adaptive`, the passes. */
  spp: number;
  /**
   * Adaptive sampling (src/core/film/adaptive.ts): each replica renders the uniform
   * pilot into a film, builds the sample map from it and renders the passes up to
   * `spp` at the map's rates, as the command line does; a pixel's value is its film
   * mean over the samples it took.
   */
  adaptive?: boolean;
}

export interface Replicas {
  config: RenderConfig;
  regions: Region[];
  seeds: number;
  /** means[(k · regions + r) · 3 + c]: mean radiance of seed k over region r, channel c. */
  means: Float64Array;
  /** Samples behind each region's mean over all seeds: pixels · spp · seeds. */
  samples: number[];
  /** Largest single sample value seen (any channel). */
  maxSample: number;
  stats: RenderStats;
}

/** Renders `seeds.length` replicas of `scene` at width × height with `config`. */
export function renderReplicas(
  scene: Scene,
  compiled: CompiledScene,
  config: RenderConfig,
  seeds: readonly number[],
  width: number,
  height: number,
  regions: Region[],
): Replicas {
  const K = seeds.length;
  const R = regions.length;
  const means = new Float64Array(K * R * 3);
  const pixel = new Float64Array(width * height * 3);
  const stats = new RenderStats();
  let maxSample = 0;
  /** Per region: the samples behind its means, over every seed. */
  const samples = regions.map(() => 0);
  for (let k = 0; k < K; k++) {
    const tracer = new PathTracer(compiled, {
      width,
      height,
      maxBounces: scene.settings.maxBounces,
      seed: seeds[k],
      estimator: config.estimator,
      sampler: config.sampler,
      lightSampler: config.lightSampler,
      camera: scene.camera,
    });
    pixel.fill(0);
    if (config.adaptive) {
      renderAdaptive(tracer, width, height, config.spp, stats, pixel, regions, samples);
    } else {
      maxSample = Math.max(
        maxSample,
        renderUniform(tracer, width, height, config.spp, stats, pixel),
      );
      for (let ri = 0; ri < R; ri++) {
        const reg = regions[ri];
        samples[ri] += (reg.x1 - reg.x0) * (reg.y1 - reg.y0) * config.spp;
      }
    }
    for (let ri = 0; ri < R; ri++) {
      const reg = regions[ri];
      let r = 0,
        g = 0,
        b = 0;
      for (let y = reg.y0; y < reg.y1; y++) {
        for (let x = reg.x0; x < reg.x1; x++) {
          const p = (y * width + x) * 3;
          r += pixel[p];
          g += pixel[p + 1];
          b += pixel[p + 2];
        }
      }
      const n = (reg.x1 - reg.x0) * (reg.y1 - reg.y0);
      const o = (k * R + ri) * 3;
      means[o] = r / n;
      means[o + 1] = g / n;
      means[o + 2] = b / n;
    }
  }
  return {
    config,
    regions,
    seeds: K,
    means,
    samples,
    maxSample,
    stats,
  };
}

/**
 * One replica with every pixel's samples [0, spp): each pixel's mean goes to `pixel`. A
 * non-finite sample is left out and counted as the film would (the test then fails on the
 * count). Returns the largest sample value (any channel).
 */
function renderUniform(
  tracer: PathTracer,
  width: number,
  height: number,
  spp: number,
  stats: RenderStats,
  pixel: Float64Array,
): number {
  let maxSample = 0;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      let r = 0,
        g = 0,
        b = 0;
      for (let s = 0; s < spp; s++) {
        tracer.trace(x, y, s, stats);
        const lr = tracer.lr,
          lg = tracer.lg,
          lb = tracer.lb;
        if (!(Number.isFinite(lr) && Number.isFinite(lg) && Number.isFinite(lb))) {
          stats.rejected++;
          continue;
        }
        r += lr;
        g += lg;
        b += lb;
        maxSample = Math.max(maxSample, lr, lg, lb);
      }
      const p = (y * width + x) * 3;
      pixel[p] = r / spp;
      pixel[p + 1] = g / spp;
      pixel[p + 2] = b / spp;
    }
  }
  return maxSample;
}

/**
 * One adaptive replica (RenderConfig.adaptive): the pilot, the map, the remaining
 * passes, through a film as the command line renders them. The film rejects a
 * non-finite sample (and counts it); each pixel's mean goes to `pixel`, each region's
 * sample count is added to `samples`.
 */
function renderAdaptive(
  tracer: PathTracer,
  width: number,
  height: number,
  passes: number,
  stats: RenderStats,
  pixel: Float64Array,
  regions: Region[],
  samples: number[],
): void {
  const film = renderAdaptiveFilm(tracer, new Film(width, height), passes, stats);
  pixel.set(film.mean());
  for (let ri = 0; ri < regions.length; ri++) {
    const reg = regions[ri];
    for (let y = reg.y0; y < reg.y1; y++) {
      for (let x = reg.x0; x < reg.x1; x++) samples[ri] += film.sums[(y * width + x) * 4 + 3];
    }
  }
}

/** Mean over seeds and the variance of that mean (sample variance / K) for region r, channel c. */
export function replicaMean(
  rep: Replicas,
  r: number,
  c: number,
): { mean: number; variance: number } {
  const K = rep.seeds;
  const R = rep.regions.length;
  let sum = 0;
  for (let k = 0; k < K; k++) sum += rep.means[(k * R + r) * 3 + c];
  const mean = sum / K;
  let ss = 0;
  for (let k = 0; k < K; k++) {
    const d = rep.means[(k * R + r) * 3 + c] - mean;
    ss += d * d;
  }
  return { mean, variance: ss / (K - 1) / K };
}

/** Average number of path segments per path of a short pilot render (deterministic). */
export function pilotSegments(
  scene: Scene,
  compiled: CompiledScene,
  config: Omit<RenderConfig, 'spp'>,
  width: number,
  height: number,
): number {
  const tracer = new PathTracer(compiled, {
    width,
    height,
    maxBounces: scene.settings.maxBounces,
    seed: 0x5eed,
    estimator: config.estimator,
    sampler: config.sampler,
    lightSampler: config.lightSampler,
    camera: scene.camera,
  });
  const stats = new RenderStats();
  for (let y = 0; y < height; y += 2)
    for (let x = 0; x < width; x += 2) tracer.trace(x, y, 0, stats);
  return stats.segments / stats.paths;
}
