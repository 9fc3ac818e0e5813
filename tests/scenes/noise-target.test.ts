/**
 * `pathwise render --noise REL` on the Cornell box, checked against the
 * Mitsuba 3 reference (tests/references/cornell.pfm, 65,536 spp): when the
 * render stops, its true relative error — measured against the reference,
 * not estimated — is at most REL.
 *
 * Rendered at 32×32, each pixel covers exactly a 4×4 block of the 128×128
 * reference (box pixel filter, same camera), so the reference pixel is the
 * block's mean. Over pixels p of the luminance L, pooled over two seeds:
 *
 * - the true relative error e = √(mean_p (L_p − Lref_p)²) / mean_p Lref_p,
 *   with its standard error σ_e from the spread of the per-pixel squared
 *   errors (delta method: σ_e / e = ½ σ_E / E for E = mean squared error).
 *   Fails when e > REL + 3.09 σ_e (one-sided, false-alarm rate 0.1%);
 * - the calibration of the per-pixel standard errors SE_p that the
 *   estimate is made of (read from the .film's exact sums): z_p = (L_p −
 *   Lref_p) / SE_p over pixels with SE_p > 0. If SE_p is the true error,
 *   mean z² = 1, with a standard error from the spread of z².
 *
 * The calibration is of uniform sampling (--adaptive off); adaptive sampling, the
 * default of --noise, is checked for the true error alone (see its test).
 *
 * With --sampler independent the sample variance is the true variance of
 * the mean: mean z² must be 1 within ±3.29 standard errors (two-sided,
 * 0.1%). With the default Owen-scrambled Sobol sampler a pixel's samples
 * are stratified, the sample variance overstates the error of their mean,
 * and the criterion is conservative: mean z² must be below 1, e below REL.
 * The reference's own noise (about 1M samples per 32×32 pixel against a
 * few hundred here) adds under 0.1% to the variances and is left out.
 */
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { exactValue } from '../../src/core/film/exact-sum.ts';
import { pathwiseOk, readFilm, tempDir } from '../helpers/batch-cli.ts';
import { ROOT, loadReference } from '../helpers/render.ts';

const REL = 0.2;
const SIZE = 32;
const SEEDS = [1, 2];
const dir = tempDir('noise');

const lum = (r: number, g: number, b: number) => 0.2126 * r + 0.7152 * g + 0.0722 * b;

/** The reference's luminance, box-averaged down to SIZE×SIZE. */
function referenceLuminance(): Float64Array {
  const ref = loadReference('cornell');
  const k = ref.width / SIZE;
  const out = new Float64Array(SIZE * SIZE);
  for (let y = 0; y < ref.height; y++) {
    for (let x = 0; x < ref.width; x++) {
      const i = (y * ref.width + x) * 3;
      out[Math.floor(y / k) * SIZE + Math.floor(x / k)] +=
        lum(ref.rgb[i], ref.rgb[i + 1], ref.rgb[i + 2]) / (k * k);
    }
  }
  return out;
}

/** Mean and standard error of the mean of a list. */
function meanAndError(values: number[]): [number, number] {
  const n = values.length;
  const m = values.reduce((a, b) => a + b, 0) / n;
  const v = values.reduce((a, x) => a + (x - m) ** 2, 0) / (n - 1);
  return [m, Math.sqrt(v / n)];
}

interface Outcome {
  e: number;
  sigma: number;
  z2: number;
  z2Error: number;
  detail: string;
}

function renderAndCompare(sampler: string, ref: Float64Array, adaptive = 'off'): Outcome {
  const squared: number[] = [];
  const z2: number[] = [];
  const runs: string[] = [];
  for (const seed of SEEDS) {
    const out = join(dir, `${sampler}-${adaptive}-${seed}.film`);
    const json = JSON.parse(
      pathwiseOk([
        'render',
        join(ROOT, 'scenes/cornell.json'),
        '--width',
        String(SIZE),
        '--height',
        String(SIZE),
        '--noise',
        String(REL),
        '--seed',
        String(seed),
        '--sampler',
        sampler,
        '--adaptive',
        adaptive,
        '--out',
        out,
        '--json',
      ]).stdout,
    );
    expect(json.stopped_by).toBe('noise');
    expect(json.noise).toBeLessThanOrEqual(REL);
    runs.push(`seed ${seed}: ${json.spp} spp, estimate ${json.noise.toFixed(4)}`);
    const { film } = readFilm(out);
    const { sums, hi, lo } = film;
    for (let p = 0; p < SIZE * SIZE; p++) {
      const i = p * 4;
      const n = sums[i + 3];
      const mean =
        lum(exactValue(hi, lo, i), exactValue(hi, lo, i + 1), exactValue(hi, lo, i + 2)) / n;
      const variance = Math.max(0, exactValue(hi, lo, i + 3) - n * mean * mean) / (n - 1);
      const d = mean - ref[p];
      squared.push(d * d);
      if (variance > 0) z2.push((d * d) / (variance / n));
    }
  }
  const [E, errE] = meanAndError(squared);
  let refMean = 0;
  for (const v of ref) refMean += v / ref.length;
  const e = Math.sqrt(E) / refMean;
  const sigma = (e * errE) / E / 2;
  const [z2Mean, z2Error] = meanAndError(z2);
  const detail = `${sampler}, adaptive ${adaptive}: e = ${e.toFixed(4)} ± ${sigma.toFixed(4)}, mean z² = ${z2Mean.toFixed(3)} ± ${z2Error.toFixed(3)} (${runs.join('; ')})`;
  return { e, sigma, z2: z2Mean, z2Error, detail };
}

describe('--noise on the Cornell box against Mitsuba', () => {
  const ref = referenceLuminance();

  it('independent sampler: the true error reaches the target; the standard errors are calibrated', () => {
    const o = renderAndCompare('independent', ref);
    expect(o.e, o.detail).toBeLessThanOrEqual(REL + 3.09 * o.sigma);
    expect(Math.abs(o.z2 - 1), o.detail).toBeLessThanOrEqual(3.29 * o.z2Error);
  });

  it('Sobol sampler (the default): the true error reaches the target; the estimate is conservative', () => {
    const o = renderAndCompare('sobol', ref);
    expect(o.e, o.detail).toBeLessThanOrEqual(REL + 3.09 * o.sigma);
    expect(o.z2, o.detail).toBeLessThan(1 - 3.09 * o.z2Error);
  });

  // --noise samples adaptively by default (docs/adaptive-sampling.md): dark pixels whose
  // neighbours are smooth take 1/16 of the passes, and a pixel of rare bright samples (the
  // box's rim in a corner) may then see none of them, so its sample variance says nothing
  // of its error (one pixel of 2,048 had z² = 68,000). Such pixels weigh next to nothing in
  // the relative error the target is about, so only that is checked here.
  it.each(['independent', 'sobol'])(
    'adaptive sampling (the default of --noise), %s: the true error reaches the target',
    (sampler) => {
      const o = renderAndCompare(sampler, ref, 'on');
      expect(o.e, o.detail).toBeLessThanOrEqual(REL + 3.09 * o.sigma);
    },
  );
});

// The .film of a noise-stopped render holds what the estimate was made from.
it('the estimate in --json is the one the .film gives', () => {
  const out = join(dir, 'check.film');
  const json = JSON.parse(
    pathwiseOk([
      'render',
      join(ROOT, 'scenes/cornell.json'),
      '--width',
      '16',
      '--height',
      '16',
      '--noise',
      '0.2',
      '--out',
      out,
      '--json',
    ]).stdout,
  );
  const { header } = readFilm(out);
  expect(header.ranges).toEqual([[0, json.spp]]);
  expect(header.spp).toBe(json.spp);
});
