/**
 * An estimate of how noisy the image still is, from the per-pixel sums the
 * film already keeps: for each pixel with n ≥ 2 samples of luminance L,
 *
 *   mean = ΣL / n,   s² = (ΣL² − n·mean²) / (n − 1),   SE² = s² / n
 *
 * (the sample variance and the squared standard error of the pixel's mean).
 * The result is the root-mean-square SE over pixels divided by the image's
 * mean luminance: a relative standard error, the typical error of one
 * pixel's luminance as a fraction of the image's brightness. It falls as
 * 1/√N, which is what the demo shows the user.
 *
 * ΣL is recomputed from the film's exact RGB sums with its luminance
 * weights; ΣL² is the exact sum at plane index i + 3 (squared luminance
 * is capped at 2^40 per sample, see film.ts). Both are read in double
 * precision from the exact sums, so the estimate is the same bits however
 * the samples were split; rounding can still leave ΣL² − n·mean² slightly
 * negative for a nearly constant pixel, so it is clamped at zero.
 */
import { exactValue } from './exact-sum.ts';

/** The planes of a Film (or of any window of one) that the estimate reads. */
export interface NoiseInput {
  /** RGBA per pixel; A is the sample count. */
  sums: Float32Array;
  /** Exact sums of R, G, B and squared luminance (see exact-sum.ts). */
  hi: Float64Array;
  lo: Float64Array;
}

/**
 * Relative standard error of the per-pixel mean luminance (see above).
 * Returns NaN while fewer than two samples per pixel exist or the image is
 * black. `stride` > 1 visits every stride-th pixel, for a cheaper estimate
 * of a large image.
 */
export function estimateNoise(film: NoiseInput, stride = 1): number {
  const sums = film.sums;
  const step = Math.max(1, Math.floor(stride)) * 4;
  let sumSe2 = 0;
  let sumMean = 0;
  let pixels = 0;
  for (let i = 0, n = sums.length; i < n; i += step) {
    const count = sums[i + 3];
    if (count < 2) continue;
    const mean = meanLuminance(film, i, count);
    sumSe2 += luminanceVariance(film, i, count, mean) / count;
    sumMean += mean;
    pixels++;
  }
  if (pixels === 0 || !(sumMean > 0)) return NaN;
  return Math.sqrt(sumSe2 / pixels) / (sumMean / pixels);
}

/** Mean luminance of the pixel whose record starts at plane index i (count ≥ 1 samples). */
export function meanLuminance(film: NoiseInput, i: number, count: number): number {
  const hi = film.hi;
  const lo = film.lo;
  return (
    (0.2126 * exactValue(hi, lo, i) +
      0.7152 * exactValue(hi, lo, i + 1) +
      0.0722 * exactValue(hi, lo, i + 2)) /
    count
  );
}

/**
 * Sample variance of the luminance of the pixel at plane index i (count ≥ 2 samples,
 * mean from meanLuminance), clamped at zero (see the header).
 */
export function luminanceVariance(
  film: NoiseInput,
  i: number,
  count: number,
  mean: number,
): number {
  const ss = exactValue(film.hi, film.lo, i + 3) - count * mean * mean;
  return ss > 0 ? ss / (count - 1) : 0;
}
