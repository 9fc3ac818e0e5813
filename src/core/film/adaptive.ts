/**
 * Adaptive sampling: after a uniform pilot of ADAPTIVE_PILOT passes, each
 * pixel takes later passes at its own rate, in proportion to the error its
 * neighbourhood showed in the pilot.
 *
 * The rule, per pixel p with rate k_p / RATE_ONE (an integer k_p in
 * [RATE_MIN, RATE_ONE]): after pass s it holds
 *
 *   count(s) = s                                   for s ≤ P (the pilot)
 *   count(s) = P + ⌊(s − P) · k_p / RATE_ONE⌋      for s > P
 *
 * samples, its own sample indices 0, 1, …, count − 1 in order (so a Sobol
 * pixel keeps its stratified prefix). A pass range [a, b) of the render
 * therefore adds sample indices [count(a), count(b)) of each pixel: passes
 * stay the unit of rounds, `--samples A:B` parts, checkpoints and the
 * --noise schedule, and integer arithmetic makes the counts the same bits
 * everywhere.
 *
 * Why it stays unbiased. A pixel's estimate is the mean of its first n
 * samples, and n depends on the pilot only through the *neighbours'*
 * samples (the 3×3 window without its centre): they are independent of
 * the pixel's own, so E[mean | n] = μ for every n. Using the pixel's own
 * pilot would not be: a pixel whose pilot happened to read dark looks
 * noisier relative to its mean, takes more samples, and the stopping rule
 * correlates with the values (the bias of sequential stopping rules).
 * The map never changes after the pilot for the same reason: later samples
 * are not uniform, so deciding again from them would reintroduce the
 * dependence through the neighbours' counts.
 *
 * The allocation. For relMSE, Σ v_p / n_p with a budget Σ n_p, the optimum
 * is n_p ∝ √v_p (Lagrange), where v_p is the variance of one sample
 * relative to the pixel's squared value; v is estimated as the neighbours'
 * mean of s² / (mean² + 0.01) in luminance (the 0.01 of relMSE keeps dark
 * pixels finite). The rate is √v / E_CAP clamped to [RATE_MIN, RATE_ONE] /
 * RATE_ONE. E_CAP is a constant, not a percentile of the image: a
 * percentile would move with every pixel's neighbours, the pixel's own
 * samples among them, and break the independence above. Its value, 0.75,
 * is near the 90th percentile of √v in the canonical scenes' pilots
 * (0.52–0.73): pixels noisier than that take every pass, which keeps a few
 * fireflies of the pilot from starving the rest. The floor (1/16) keeps a
 * pixel whose neighbours showed no variance in 128 pilot samples (a rare
 * caustic) from starving.
 */
import { luminanceVariance, meanLuminance, type NoiseInput } from './noise.ts';

/** Uniform passes before the map is built (every pixel takes all of them). */
export const ADAPTIVE_PILOT = 16;
/** The rate of a pixel that takes every pass. */
export const RATE_ONE = 64;
/** The lowest rate, 4/64: one pass in 16. */
export const RATE_MIN = 4;
/** The estimated one-sample relative deviation √v that takes rate 1 (see the header). */
export const E_CAP = 0.75;

/** Samples a pixel of rate `k` holds after `passes` passes (see the header). */
export function adaptiveCount(passes: number, pilot: number, k: number): number {
  if (passes <= pilot) return passes;
  return pilot + Math.floor(((passes - pilot) * k) / RATE_ONE);
}

/** A film's planes and size, as the map reads them. */
export interface PilotFilm extends NoiseInput {
  width: number;
  rows: number;
}

/**
 * The per-pixel rates (Uint8, k in [RATE_MIN, RATE_ONE]) from a pilot film: every
 * pixel's sums over the same uniform passes. Written into `out` (width·rows).
 */
export function buildSampleMap(film: PilotFilm, out: Uint8Array): Uint8Array {
  const width = film.width;
  const rows = film.rows;
  const n = width * rows;
  if (out.length !== n) throw new RangeError(`sample map of ${out.length} for ${n} pixels`);
  const v = relativeVariance(film);
  const e = new Float64Array(n);
  for (let y = 0; y < rows; y++) {
    for (let x = 0; x < width; x++) {
      let sum = 0;
      let count = 0;
      for (let dy = -1; dy <= 1; dy++) {
        const yy = y + dy;
        if (yy < 0 || yy >= rows) continue;
        for (let dx = -1; dx <= 1; dx++) {
          const xx = x + dx;
          // The pixel itself is left out: the header says why.
          if ((dx === 0 && dy === 0) || xx < 0 || xx >= width) continue;
          const vq = v[yy * width + xx];
          if (vq >= 0) {
            sum += vq;
            count++;
          }
        }
      }
      // No neighbour with a variance: nothing is known, so the pixel takes every pass.
      e[y * width + x] = count > 0 ? Math.sqrt(sum / count) : Infinity;
    }
  }
  for (let p = 0; p < n; p++) {
    const ep = e[p];
    out[p] = ep < E_CAP ? Math.max(RATE_MIN, Math.ceil((RATE_ONE * ep) / E_CAP)) : RATE_ONE;
  }
  return out;
}

/**
 * Per pixel, the sample variance of luminance over (mean² + 0.01) (noise.ts's
 * statistics); −1 where fewer than two samples were accepted.
 */
function relativeVariance(film: NoiseInput): Float64Array {
  const sums = film.sums;
  const v = new Float64Array(sums.length / 4);
  for (let p = 0, i = 0; p < v.length; p++, i += 4) {
    const count = sums[i + 3];
    if (count < 2) {
      v[p] = -1;
      continue;
    }
    const mean = meanLuminance(film, i, count);
    v[p] = luminanceVariance(film, i, count, mean) / (mean * mean + 0.01);
  }
  return v;
}
