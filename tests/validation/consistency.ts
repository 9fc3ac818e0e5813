/**
 * Estimator consistency on one scene: three renders of K independent
 * seeds each,
 *   A = NEE+MIS with Sobol (the default),
 *   B = BSDF-only with Sobol,
 *   C = NEE+MIS with independent samples,
 * and Welch tests of A = B and A = C on the per-seed means of every image
 * region (whole image, quadrants, 8×8 blocks) and channel. Two unbiased
 * estimators of one integral must agree; the tolerance is the spread
 * across seeds.
 *
 * Heavy tails. BSDF-only sampling finds a small bright light only by
 * hitting it: rare, huge samples. When every seed happens to miss them, B
 * reads low *and* its spread is small, so a plain t test would cry wolf.
 * Two facts bound this (see bsdfSampleBound):
 *   1. every BSDF-only sample lies in [0, V] with V known from the scene;
 *   2. a deficit Δ = mean(A) − mean(B) > 0 that comes from missed samples
 *      needs missed mass Δ made of samples of size ≤ V: at least m = ΔN/V
 *      of them were expected among B's N samples, and the chance of
 *      missing them all is ≤ e^(−m) (Poisson).
 * So B's variance gets the floor ΔV/N (the variance of that Poisson mass,
 * Bhatia–Davis: Var ≤ μV for samples in [0, V]). With it the z test
 * rejects only when m > z², where e^(−m) is below 1e-12 for the suite's z —
 * a far smaller false-alarm rate than the test's own. The floor only acts
 * when B reads low; B reading high through a lucky rare sample inflates
 * B's own spread, which the t statistic already sees.
 */
import { compileScene, type Scene } from '../../src/core/index.ts';
import { gltfSampleFactors } from './gltf-bounds.ts';
import {
  imageRegions,
  pilotSegments,
  renderReplicas,
  replicaMean,
  type RenderConfig,
  type Replicas,
} from './replicas.ts';
import { normalQuantileTwoSided, welch } from './stats.ts';

export { GLTF_WEIGHT_BOUND, sheenWeightBound } from './gltf-bounds.ts';

export interface ConsistencyOptions {
  width: number;
  height: number;
  /** Independent seeds per configuration. */
  seeds: number;
  /**
   * Work per configuration, in segment-equivalents: a path costs its
   * segments plus 2 (camera ray set-up and sampler, measured: about two
   * segments' time). A deterministic pilot render sets spp from it.
   */
  budget: number;
  /** Largest spp per seed. */
  maxSpp: number;
  /**
   * Also render NEE+MIS with lights chosen by power (D) and test it against A, whose
   * lights the light BVH chooses: both have low variance, so this pair sees a bias
   * in the BVH's choice that the BSDF-only one, noisy among many small lights, cannot.
   */
  lightSamplerPair?: boolean;
}

export interface PairTest {
  pair: 'nee-vs-bsdf' | 'sobol-vs-independent' | 'bvh-vs-power';
  region: string;
  channel: number;
  meanA: number;
  meanB: number;
  t: number;
  nu: number;
  p: number;
}

export interface SceneConsistency {
  tests: PairTest[];
  spp: Partial<Record<'A' | 'B' | 'C' | 'D', number>>;
  /** Largest BSDF-only sample and its bound V. */
  maxBsdfSample: number;
  bsdfBound: number;
  rejected: number;
  segments: number;
  /**
   * Power: the smallest relative bias of A in the whole image (brightest
   * channel) that each pair would detect at ALPHA_PER_TEST, given the
   * variances observed (normal approximation; Infinity for a black image).
   */
  detectable: Record<PairTest['pair'], number>;
}

type ConfigKey = 'A' | 'B' | 'C' | 'D';
const CONFIGS: Record<ConfigKey, Omit<RenderConfig, 'spp'>> = {
  A: { estimator: 'nee-mis', sampler: 'sobol' },
  B: { estimator: 'bsdf', sampler: 'sobol' },
  C: { estimator: 'nee-mis', sampler: 'independent' },
  D: { estimator: 'nee-mis', sampler: 'sobol', lightSampler: 'power' },
};

/**
 * An upper bound V on any one sample of the BSDF-only estimator. A path
 * adds β·Le at each of its ≤ B+1 vertices and β·Lenv once at the end. Its
 * throughput β is a product of sample weights, each ≤ 1 (Lambertian:
 * albedo; GGX with visible normals: F·G1 ≤ 1; smooth dielectric: 1 or
 * colour, chosen by Fresnel), of the (n1/n2)² of radiance at each
 * refraction — entering a solid divides by ior², leaving it multiplies, so
 * the running product stays ≤ 1 per solid a path starts outside of and
 * ≤ ior² for the one it starts in (the generator gives every glass object
 * its own material: one factor max(1, ior²) per dielectric material covers
 * both) — and of Russian
 * roulette's 1/(1−q) with q = max(0.05, 1 − max β·etaScale), which can
 * lift the largest channel by at most 1/0.95 per bounce from the third.
 * With a = the largest diffuse albedo (1 as soon as any conductor or
 * dielectric is present, GLTF_WEIGHT_BOUND with a glTF model, sheenWeightBound with a
 * sharp glTF sheen):
 * A dispersive glTF volume makes a path carry one channel weighted 3 (dispersion.ts):
 * one factor χ = 3 when any material disperses, and its ηfactor uses the largest
 * dispersed index ior + h.
 * V = (Le·Σₖ aᵏ + Lenv·max(1, a)^B) · ηfactor · χ · 0.95^−(B−2),
 * Lenv the constant environment or the brightest texel of the map times its
 * scale.
 */
export function bsdfSampleBound(scene: Scene): number {
  let le = 0;
  let a = 0;
  let eta = 1;
  let channel = 1;
  for (const m of Object.values(scene.materials)) {
    le = Math.max(le, ...m.emission);
    if (m.type === 'diffuse') a = Math.max(a, ...m.albedo);
    else a = 1;
    if (m.type === 'dielectric') eta *= Math.max(1, m.ior * m.ior);
  }
  for (const s of scene.shapes) {
    if (s.type !== 'gltf' || s.data === null) continue;
    const f = gltfSampleFactors(s.data.materials);
    le = Math.max(le, f.emission);
    a = Math.max(a, f.weight);
    eta *= f.eta;
    channel = Math.max(channel, f.channel);
  }
  const B = scene.settings.maxBounces;
  let sum = 0;
  for (let k = 0; k <= B; k++) sum += a ** k;
  const env = Math.max(...scene.environment, environmentMapMaximum(scene));
  // The environment is reached after at most B scattering events, each weighing ≤ a when a > 1.
  return (
    (le * sum + env * Math.max(1, a) ** B) * eta * channel * Math.pow(1 / 0.95, Math.max(0, B - 2))
  );
}

/** The brightest radiance an environment map sends: largest texel times scale (0 without one). */
export function environmentMapMaximum(scene: Scene): number {
  const map = scene.environmentMap ?? null;
  if (map === null) return 0;
  const rgb = map.image!.rgb;
  let max = 0;
  for (let i = 0; i < rgb.length; i++) max = Math.max(max, rgb[i] * map.scale[i % 3]);
  return max;
}

/** Powers of two keep each seed's Sobol points a whole (0,2)-net. */
function sppFor(
  budget: number,
  perPath: number,
  pixels: number,
  seeds: number,
  max: number,
): number {
  const ideal = budget / (perPath * pixels * seeds);
  let spp = 1;
  while (spp * 2 <= Math.min(ideal, max)) spp *= 2;
  return spp;
}

/**
 * Runs the three configurations on `scene` and tests both pairs. `variants`
 * replaces the scene of one configuration (the tests' own power check
 * injects a known bias that way).
 */
export function checkConsistency(
  scene: Scene,
  options: ConsistencyOptions,
  seedBase: number,
  variants: Partial<Record<ConfigKey, Scene>> = {},
): SceneConsistency {
  const compiled = compileScene(scene);
  const { width, height, seeds } = options;
  const regions = imageRegions(width, height);
  const reps = {} as Record<ConfigKey, Replicas>;
  const spp = {} as Record<ConfigKey, number>;
  let segments = 0;
  const keys: ConfigKey[] = options.lightSamplerPair ? ['A', 'B', 'C', 'D'] : ['A', 'B', 'C'];
  for (const key of keys) {
    const perPath = pilotSegments(scene, compiled, CONFIGS[key], width, height) + 2;
    spp[key] = sppFor(options.budget, perPath, width * height, seeds, options.maxSpp);
    const seedList = Array.from(
      { length: seeds },
      (_, k) => seedBase + 7919 * k + key.charCodeAt(0),
    );
    const own = variants[key];
    reps[key] = renderReplicas(
      own ?? scene,
      own ? compileScene(own) : compiled,
      { ...CONFIGS[key], spp: spp[key] },
      seedList,
      width,
      height,
      regions,
    );
    segments += reps[key].stats.segments;
  }
  const bound = bsdfSampleBound(scene);
  const tests: PairTest[] = [];
  const detectable = {
    'nee-vs-bsdf': Infinity,
    'sobol-vs-independent': Infinity,
    'bvh-vs-power': Infinity,
  };
  const pairs: ['nee-vs-bsdf' | 'sobol-vs-independent' | 'bvh-vs-power', ConfigKey][] = [
    ['nee-vs-bsdf', 'B'],
    ['sobol-vs-independent', 'C'],
  ];
  if (options.lightSamplerPair) pairs.push(['bvh-vs-power', 'D']);
  for (const [pair, other] of pairs) {
    for (let r = 0; r < regions.length; r++) {
      for (let c = 0; c < 3; c++) {
        const a = replicaMean(reps.A, r, c);
        const b = replicaMean(reps[other], r, c);
        let vb = b.variance;
        let dfb = seeds - 1;
        if (other === 'B') {
          const floor = (Math.max(0, a.mean - b.mean) * bound) / reps.B.samples[r];
          if (floor > vb) {
            vb = floor;
            dfb = Infinity;
          }
        }
        // Rounding: sums of up to ~1e6 doubles agree to ~1e-12 relative at worst.
        const precision = 1e-12 * Math.max(Math.abs(a.mean), Math.abs(b.mean));
        const w = welch(a.mean, a.variance + precision * precision, seeds - 1, b.mean, vb, dfb);
        if (r === 0 && a.mean > 0) {
          // Δ = z·sqrt(vA + vB + Δ·V/N) (the floor grows with the deficit), solved for Δ.
          const z = Z_PER_TEST;
          const k = other === 'B' ? (z * z * bound) / reps.B.samples[r] : 0;
          const delta = (k + Math.sqrt(k * k + 4 * z * z * (a.variance + b.variance))) / 2;
          detectable[pair] = Math.min(detectable[pair], delta / a.mean);
        }
        tests.push({
          pair,
          region: regions[r].name,
          channel: c,
          meanA: a.mean,
          meanB: b.mean,
          ...w,
        });
      }
    }
  }
  return {
    tests,
    spp,
    maxBsdfSample: reps.B.maxSample,
    bsdfBound: bound,
    rejected: reps.A.stats.rejected + reps.B.stats.rejected + reps.C.stats.rejected,
    segments,
    detectable,
  };
}

/** The suite's settings (consistency-suite.ts explains the false-alarm rate). */
export const SCENE_COUNT = 120;
/** Mesh-family scenes (generateScene(seed, { family: 'mesh' })), seeds MESH_FIRST_SEED…. */
export const MESH_SCENE_COUNT = 40;
export const MESH_FIRST_SEED = 3001;
/** glTF-family scenes (generateScene(seed, { family: 'gltf' })), seeds GLTF_FIRST_SEED…. */
export const GLTF_SCENE_COUNT = 32;
export const GLTF_FIRST_SEED = 5001;
/**
 * Punctual-light scenes (generateScene(seed, { family: 'punctual' })), seeds
 * PUNCTUAL_FIRST_SEED…, checked by punctual.ts (Sobol = independent, point = sphere):
 * TESTS_PER_SCENE tests each, like the other families.
 */
export const PUNCTUAL_SCENE_COUNT = 10;
export const PUNCTUAL_FIRST_SEED = 7001;
/** Many-light scenes (generateScene(seed, { family: 'many' }), archetypes-many.ts), seeds MANY_FIRST_SEED…. */
export const MANY_SCENE_COUNT = 10;
export const MANY_FIRST_SEED = 9001;
export const ALPHA_SUITE = 1e-3;
export const OPTIONS: ConsistencyOptions = {
  width: 32,
  height: 24,
  seeds: 32,
  budget: 2_700_000,
  maxSpp: 32,
};
/**
 * The mesh family at half the work: a segment through the BVH of a few hundred
 * triangles costs about twice one through a handful of spheres and quads.
 */
export const MESH_OPTIONS: ConsistencyOptions = { ...OPTIONS, budget: 1_350_000 };
export const TESTS_PER_SCENE = 2 * imageRegions(OPTIONS.width, OPTIONS.height).length * 3;
/** The many-light family adds a third pair (bvh-vs-power) and renders four configurations. */
export const MANY_OPTIONS: ConsistencyOptions = { ...OPTIONS, lightSamplerPair: true };
export const MANY_TESTS_PER_SCENE = (TESTS_PER_SCENE * 3) / 2;
/** Bonferroni over every test of the five families: the whole suite fails by chance with p ≤ ALPHA_SUITE. */
export const ALPHA_PER_TEST =
  ALPHA_SUITE /
  ((SCENE_COUNT + MESH_SCENE_COUNT + GLTF_SCENE_COUNT + PUNCTUAL_SCENE_COUNT) * TESTS_PER_SCENE +
    MANY_SCENE_COUNT * MANY_TESTS_PER_SCENE);
const Z_PER_TEST = normalQuantileTwoSided(ALPHA_PER_TEST);
