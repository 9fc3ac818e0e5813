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
 * ΣL is recomputed from the RGB sums with the film's luminance weights;
 * ΣL² is film.extra[i + 3]. In Float32 the difference ΣL² − n·mean² can
 * come out slightly negative for a nearly constant pixel, so it is clamped
 * at zero.
 */

/** Sums and extra of a Film (or of any window of one), RGBA per pixel. */
export interface NoiseInput {
  sums: Float32Array;
  extra: Float32Array;
}

/**
 * Relative standard error of the per-pixel mean luminance (see above).
 * Returns NaN while fewer than two samples per pixel exist or the image is
 * black. `stride` > 1 visits every stride-th pixel, for a cheaper estimate
 * of a large image.
 */
export function estimateNoise(film: NoiseInput, stride = 1): number {
  const sums = film.sums;
  const extra = film.extra;
  const step = Math.max(1, Math.floor(stride)) * 4;
  let sumSe2 = 0;
  let sumMean = 0;
  let pixels = 0;
  for (let i = 0, n = sums.length; i < n; i += step) {
    const count = sums[i + 3];
    if (count < 2) continue;
    const lumSum = 0.2126 * sums[i] + 0.7152 * sums[i + 1] + 0.0722 * sums[i + 2];
    const mean = lumSum / count;
    const ss = extra[i + 3] - count * mean * mean;
    const variance = ss > 0 ? ss / (count - 1) : 0;
    sumSe2 += variance / count;
    sumMean += mean;
    pixels++;
  }
  if (pixels === 0 || !(sumMean > 0)) return NaN;
  return Math.sqrt(sumSe2 / pixels) / (sumMean / pixels);
}
