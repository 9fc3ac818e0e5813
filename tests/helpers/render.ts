/**
 * Test helpers: load the canonical scenes and references, and render with
 * per-pixel sample statistics (mean and variance of the mean, per channel)
 * so tolerances come from the render's own noise.
 */
import { expect } from 'vitest';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { nodeSceneFiles } from '../../src/cli/scene-files.ts';
import {
  ADAPTIVE_PILOT,
  buildSampleMap,
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  decodePfm,
  loadScene as loadSceneAndFiles,
  parseScene,
  type Estimator,
  type PfmImage,
  type SamplerKind,
  type Scene,
} from '../../src/core/index.ts';

export const ROOT = fileURLToPath(new URL('../../', import.meta.url));

export function loadScene(name: string): Scene {
  return parseScene(readFileSync(`${ROOT}scenes/${name}.json`, 'utf8'));
}

export function loadReference(name: string): PfmImage {
  return decodePfm(readFileSync(`${ROOT}tests/references/${name}.pfm`));
}

export interface SampledImage {
  width: number;
  height: number;
  /** Per pixel and channel: mean of the samples. */
  mean: Float64Array;
  /** Per pixel and channel: estimated variance of that mean (s² / n). */
  varianceOfMean: Float64Array;
  stats: RenderStats;
}

export interface RenderOptions {
  width?: number;
  height?: number;
  spp: number;
  seed?: number;
  maxBounces?: number;
  estimator?: Estimator;
  /** Force or forbid the BVH (default: by the compiler's threshold). */
  bvh?: boolean;
  /**
   * The sampler (default the tracer's). Sample variances estimate the error of the
   * mean exactly only for independent samples; Sobol's mean is better than s²/n says.
   */
  sampler?: SamplerKind;
}

/** Renders with the core tracer, keeping per-pixel sums and sums of squares in doubles. */
export function renderSampled(scene: Scene, options: RenderOptions): SampledImage {
  const width = options.width ?? scene.settings.width;
  const height = options.height ?? scene.settings.height;
  const tracer = new PathTracer(compileScene(scene, { bvh: options.bvh }), {
    width,
    height,
    maxBounces: options.maxBounces ?? scene.settings.maxBounces,
    seed: options.seed ?? 1,
    estimator: options.estimator,
    sampler: options.sampler,
    camera: scene.camera,
  });
  const n = options.spp;
  const mean = new Float64Array(width * height * 3);
  const varianceOfMean = new Float64Array(width * height * 3);
  const stats = new RenderStats();
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      let sr = 0,
        sg = 0,
        sb = 0,
        qr = 0,
        qg = 0,
        qb = 0;
      for (let s = 0; s < n; s++) {
        tracer.trace(x, y, s, stats);
        sr += tracer.lr;
        sg += tracer.lg;
        sb += tracer.lb;
        qr += tracer.lr * tracer.lr;
        qg += tracer.lg * tracer.lg;
        qb += tracer.lb * tracer.lb;
      }
      const p = (y * width + x) * 3;
      const sums = [sr, sg, sb];
      const squares = [qr, qg, qb];
      for (let c = 0; c < 3; c++) {
        const m = sums[c] / n;
        mean[p + c] = m;
        varianceOfMean[p + c] = Math.max(0, squares[c] / n - m * m) / (n - 1);
      }
    }
  }
  return { width, height, mean, varianceOfMean, stats };
}

/**
 * Passes [0, passes) into `film` (a whole image, the tracer's size) as `pathwise render --adaptive on`
 * renders them, in one thread: the uniform pilot, the map built from it
 * (core/film/adaptive.ts), then the passes after it at the map's rates. The tests' one
 * reference for adaptive films.
 */
export function renderAdaptiveFilm(
  tracer: PathTracer,
  film: Film,
  passes: number,
  stats = new RenderStats(),
): Film {
  const { width, rows: height } = film;
  tracer.renderRows(film, 0, height, 0, Math.min(passes, ADAPTIVE_PILOT), stats);
  if (passes > ADAPTIVE_PILOT) {
    tracer.sampleMap = buildSampleMap(film, new Uint8Array(width * height));
    tracer.renderRows(film, 0, height, ADAPTIVE_PILOT, passes, stats);
  }
  return film;
}

/** Per-channel image mean and the standard error of that mean. */
export function imageMean(img: SampledImage): { mean: number[]; stderr: number[] } {
  const px = img.width * img.height;
  const mean = [0, 0, 0];
  const variance = [0, 0, 0];
  for (let p = 0; p < px; p++) {
    for (let c = 0; c < 3; c++) {
      mean[c] += img.mean[p * 3 + c];
      variance[c] += img.varianceOfMean[p * 3 + c];
    }
  }
  return {
    mean: mean.map((m) => m / px),
    stderr: variance.map((v) => Math.sqrt(v) / px),
  };
}

export function referenceMean(ref: PfmImage): number[] {
  const m = [0, 0, 0];
  for (let p = 0; p < ref.width * ref.height; p++)
    for (let c = 0; c < 3; c++) m[c] += ref.rgb[p * 3 + c];
  return m.map((v) => v / (ref.width * ref.height));
}

/**
 * Block test: averages over `block`×`block` pixel blocks of the render and
 * the reference, z-scores from the render's own variance (the reference,
 * at 65,536 spp, contributes `refVarianceScale` × ours), and returns the
 * χ² statistic Σz² with its degrees of freedom and the largest |z|.
 */
export function blockChiSquare(
  img: SampledImage,
  ref: PfmImage,
  block: number,
  refVarianceScale: number,
): { chi2: number; dof: number; maxAbsZ: number } {
  let chi2 = 0;
  let dof = 0;
  let maxAbsZ = 0;
  for (let by = 0; by < img.height; by += block) {
    for (let bx = 0; bx < img.width; bx += block) {
      for (let c = 0; c < 3; c++) {
        let ours = 0,
          theirs = 0,
          variance = 0;
        for (let y = by; y < Math.min(img.height, by + block); y++) {
          for (let x = bx; x < Math.min(img.width, bx + block); x++) {
            const i = (y * img.width + x) * 3 + c;
            ours += img.mean[i];
            theirs += ref.rgb[i];
            variance += img.varianceOfMean[i];
          }
        }
        // The reference is float32 data accumulated in float32 by Mitsuba
        // (its constant environment of 0.05 reads 0.0500001274, 2.5e-6 off):
        // allow 1e-5 relative for that, or noise-free blocks (pure
        // environment) would demand agreement beyond its precision.
        const precision = 1e-5 * Math.abs(theirs);
        const sigma2 = variance * (1 + refVarianceScale) + precision * precision;
        if (sigma2 === 0) {
          if (ours !== theirs) return { chi2: Infinity, dof, maxAbsZ: Infinity };
          continue;
        }
        const z = (ours - theirs) / Math.sqrt(sigma2);
        chi2 += z * z;
        dof++;
        maxAbsZ = Math.max(maxAbsZ, Math.abs(z));
      }
    }
  }
  return { chi2, dof, maxAbsZ };
}

/**
 * Upper quantile of the χ² distribution with k degrees of freedom by the
 * Wilson–Hilferty approximation (accurate to well under 1% for k ≥ 10),
 * for a given standard-normal quantile z (3.09 ↔ p = 0.001).
 */
export function chiSquareQuantile(k: number, z: number): number {
  const a = 2 / (9 * k);
  return k * Math.pow(1 - a + z * Math.sqrt(a), 3);
}

/** Loads a canonical scene with the mesh and map files it names (scenes/ beside it). */
export async function loadSceneWithFiles(name: string): Promise<Scene> {
  const text = readFileSync(`${ROOT}scenes/${name}.json`, 'utf8');
  return loadSceneAndFiles(text, nodeSceneFiles(`${ROOT}scenes`));
}

/**
 * The reference at 1/k of its resolution: each pixel the mean of k×k pixels. With the
 * box pixel filter this is exactly the image rendered at that resolution, so a test can
 * render fewer, larger pixels against the same reference.
 */
export function downsample(ref: PfmImage, k: number): PfmImage {
  const width = ref.width / k;
  const height = ref.height / k;
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < ref.height; y++) {
    for (let x = 0; x < ref.width; x++) {
      for (let c = 0; c < 3; c++) {
        rgb[(Math.floor(y / k) * width + Math.floor(x / k)) * 3 + c] +=
          ref.rgb[(y * ref.width + x) * 3 + c] / (k * k);
      }
    }
  }
  return { width, height, rgb };
}

/**
 * Block test between two independent renders of the same image (two ways of
 * modelling one scene, two estimators): block averages z-scored by both renders' own
 * per-pixel sample variances; returns Σz², its degrees of freedom and the largest |z|.
 */
export function blockChiSquarePair(
  a: SampledImage,
  b: SampledImage,
  block: number,
): { chi2: number; dof: number; maxAbsZ: number } {
  let chi2 = 0;
  let dof = 0;
  let maxAbsZ = 0;
  for (let by = 0; by < a.height; by += block) {
    for (let bx = 0; bx < a.width; bx += block) {
      for (let c = 0; c < 3; c++) {
        let sa = 0,
          sb = 0,
          variance = 0;
        for (let y = by; y < Math.min(a.height, by + block); y++) {
          for (let x = bx; x < Math.min(a.width, bx + block); x++) {
            const i = (y * a.width + x) * 3 + c;
            sa += a.mean[i];
            sb += b.mean[i];
            variance += a.varianceOfMean[i] + b.varianceOfMean[i];
          }
        }
        if (variance === 0) {
          if (sa !== sb) return { chi2: Infinity, dof, maxAbsZ: Infinity };
          continue;
        }
        const z = (sa - sb) / Math.sqrt(variance);
        chi2 += z * z;
        dof++;
        maxAbsZ = Math.max(maxAbsZ, Math.abs(z));
      }
    }
  }
  return { chi2, dof, maxAbsZ };
}

/**
 * The block test between two independent renders of one image (tests/scenes): no sample
 * rejected, at least `minDof` 4×4 blocks with variance, χ² under its p = 0.001 quantile
 * and no |z| over 5 (about 0.2 % false alarms together).
 */
export function expectSameImage(a: SampledImage, b: SampledImage, minDof = 100, label = ''): void {
  expect(a.stats.rejected + b.stats.rejected, label).toBe(0);
  const { chi2, dof, maxAbsZ } = blockChiSquarePair(a, b, 4);
  expect(dof, label).toBeGreaterThan(minDof);
  expect(chi2, `${label} χ² ${chi2.toFixed(1)} over ${dof} blocks`).toBeLessThan(
    chiSquareQuantile(dof, 3.09),
  );
  expect(maxAbsZ, label).toBeLessThan(5);
}
