/**
 * The accumulator: exact fixed-point sums stay accurate over long runs and
 * give the same bits for any order or grouping of the samples; non-finite
 * and out-of-range samples are rejected and counted, never added.
 */
import { describe, expect, it } from 'vitest';
import { Film, estimateNoise } from '../../../src/core/index.ts';
import { LIMB, MAX_COUNT, SAMPLE_LIMIT, SCALE } from '../../../src/core/film/exact-sum.ts';
import { LUM2_LIMIT } from '../../../src/core/film/film.ts';
import { mulberry32 as rng } from '../../helpers/faults.ts';

/** Samples over many magnitudes, a few negative, a few fireflies, as the tracer can make. */
function sampleValues(count: number, seed: number): number[] {
  const next = rng(seed);
  const out: number[] = [];
  for (let i = 0; i < count; i++) {
    const e = Math.floor(next() * 40) - 30; // 2^-30 … 2^9
    const sign = next() < 0.05 ? -1 : 1;
    const v = next() < 0.01 ? next() * 1e7 : sign * next() * 2 ** e;
    out.push(v);
  }
  return out;
}

/** v · 2^40 rounded to the nearest integer, ties to even (the film's rounding), as a BigInt. */
function fixedPoint(v: number): bigint {
  const x = v * SCALE;
  const f = Math.floor(x);
  const d = x - f;
  const q = d > 0.5 || (d === 0.5 && f % 2 !== 0) ? f + 1 : f;
  return BigInt(q);
}

function bytes(film: Film): Buffer {
  return Buffer.from(film.buffer as ArrayBuffer);
}

describe('Film', () => {
  it('keeps 65,536 samples of 0.1 within 1e-5 relative, where naive Float32 drifts', () => {
    const film = new Film(1, 1);
    const naive = new Float32Array(1);
    for (let i = 0; i < 65536; i++) {
      film.addSample(0, 0, 0.1, 0.1, 0.1);
      naive[0] += 0.1;
    }
    const mean = film.mean();
    for (let c = 0; c < 3; c++) expect(Math.abs(mean[c] / 0.1 - 1)).toBeLessThan(1e-5);
    expect(film.sums[3]).toBe(65536);
    // The naive sum is what the compensation prevents (the test can fail).
    expect(Math.abs(naive[0] / 65536 / 0.1 - 1)).toBeGreaterThan(1e-4);
  });

  it('stays accurate for a million samples of mixed magnitude', () => {
    const film = new Film(1, 1);
    let exact = 0;
    for (let i = 0; i < 1_000_000; i++) {
      const v = i % 1000 === 0 ? 18.387 : 0.0123;
      film.addSample(0, 0, v, v, v);
      exact += v;
    }
    expect(Math.abs(film.mean()[0] / (exact / 1e6) - 1)).toBeLessThan(1e-6);
  });

  it('rejects NaN and ±Infinity samples without touching the pixel', () => {
    const film = new Film(2, 1);
    expect(film.addSample(1, 0, 0.5, 0.25, 1)).toBe(true);
    expect(film.addSample(1, 0, NaN, 0, 0)).toBe(false);
    expect(film.addSample(1, 0, 0, Infinity, 0)).toBe(false);
    expect(film.addSample(1, 0, 0, 0, -Infinity)).toBe(false);
    expect(Array.from(film.mean().subarray(3, 6))).toEqual([0.5, 0.25, 1]);
    expect(film.sums[7]).toBe(1);
  });

  it('keeps the sums exact and finite at the far end of their range', () => {
    // The most a pixel can hold: MAX_COUNT samples at ±SAMPLE_LIMIT. Start one sample
    // short of it (the state after 2^24 − 1 such samples) and add the last one.
    const film = new Film(1, 1);
    const units = BigInt(SAMPLE_LIMIT) * BigInt(SCALE) * BigInt(MAX_COUNT - 1);
    film.hi[0] = Number(units / BigInt(LIMB));
    film.lo[0] = Number(units % BigInt(LIMB));
    film.sums[3] = MAX_COUNT - 1;
    expect(film.addSample(0, 0, SAMPLE_LIMIT, 0, 0)).toBe(true);
    const total = BigInt(film.hi[0]) * BigInt(LIMB) + BigInt(film.lo[0]);
    expect(total).toBe(BigInt(SAMPLE_LIMIT) * BigInt(SCALE) * BigInt(MAX_COUNT));
    expect(film.sums[0]).toBe(SAMPLE_LIMIT * MAX_COUNT);
    expect(film.sums.every(Number.isFinite)).toBe(true);
    expect(Number.isSafeInteger(film.hi[0])).toBe(true);
  });

  it('caps the squared luminance of huge samples (noise sum only); the image keeps them', () => {
    const film = new Film(1, 1);
    // Luminance 1e7: its square, 1e14, is above the cap of 2^40 ≈ 1.1e12.
    expect(film.addSample(0, 0, 1e7, 1e7, 1e7)).toBe(true);
    expect(film.mean()[0]).toBe(1e7);
    expect(film.hi[3] * LIMB + film.lo[3]).toBe(LUM2_LIMIT * SCALE);
    expect(film.hi.every(Number.isSafeInteger) && film.lo.every(Number.isSafeInteger)).toBe(true);
  });

  it('addresses a window of rows through y0', () => {
    const film = new Film(3, 2, undefined, 5);
    film.addSample(2, 6, 1, 2, 3);
    expect(Array.from(film.sums.subarray(20, 24))).toEqual([1, 2, 3, 1]);
  });

  it('holds the exact integer sum of the rounded samples (checked with BigInt)', () => {
    const film = new Film(1, 1);
    const values = sampleValues(5000, 7);
    let exact = 0n;
    let exactNeg = 0n;
    for (const v of values) {
      film.addSample(0, 0, v, -v, v * 3);
      exact += fixedPoint(v);
      exactNeg += fixedPoint(-v);
    }
    const total = (i: number) => BigInt(film.hi[i]) * BigInt(LIMB) + BigInt(film.lo[i]);
    expect(total(0)).toBe(exact);
    expect(total(1)).toBe(exactNeg);
    expect(film.lo[1]).toBeGreaterThanOrEqual(0);
    expect(film.lo[1]).toBeLessThan(LIMB);
  });

  it('gives the same bits for any order and any split of the samples', () => {
    const width = 3;
    const values = sampleValues(3 * 400, 11);
    const sample = (k: number): [number, number, number] => [
      values[k],
      values[(k * 7) % values.length],
      Math.abs(values[(k * 13) % values.length]),
    ];
    const n = values.length / width;
    const inOrder = new Film(width, 1);
    for (let s = 0; s < n; s++)
      for (let x = 0; x < width; x++) inOrder.addSample(x, 0, ...sample(s * width + x));
    // Reversed order.
    const reversed = new Film(width, 1);
    for (let s = n - 1; s >= 0; s--)
      for (let x = 0; x < width; x++) reversed.addSample(x, 0, ...sample(s * width + x));
    expect(bytes(reversed).equals(bytes(inOrder))).toBe(true);
    // Random ranges in separate films, merged in a shuffled order.
    const next = rng(3);
    const cuts = [0, n];
    for (let c = 0; c < 6; c++) cuts.push(1 + Math.floor(next() * (n - 1)));
    cuts.sort((a, b) => a - b);
    const parts: Film[] = [];
    for (let c = 0; c + 1 < cuts.length; c++) {
      const part = new Film(width, 1);
      for (let s = cuts[c]; s < cuts[c + 1]; s++)
        for (let x = 0; x < width; x++) part.addSample(x, 0, ...sample(s * width + x));
      parts.push(part);
    }
    parts.sort(() => next() - 0.5);
    const merged = new Film(width, 1);
    for (const part of parts) merged.add(part);
    expect(bytes(merged).equals(bytes(inOrder))).toBe(true);
    expect(estimateNoise(merged)).toBe(estimateNoise(inOrder));
    // A film that missed one sample differs (the comparison can fail).
    const missing = new Film(width, 1);
    for (let s = 1; s < n; s++)
      for (let x = 0; x < width; x++) missing.addSample(x, 0, ...sample(s * width + x));
    expect(bytes(missing).equals(bytes(inOrder))).toBe(false);
  });

  it('rounds to nearest with ties to even, symmetrically', () => {
    const unit = 1 / SCALE;
    const film = new Film(6, 1);
    const values = [0.5 * unit, 1.5 * unit, 2.5 * unit, -0.5 * unit, -1.5 * unit, -2.5 * unit];
    values.forEach((v, x) => film.addSample(x, 0, v, 0, 0));
    const units = Array.from({ length: 6 }, (_, x) => film.hi[x * 4] * LIMB + film.lo[x * 4]);
    expect(units).toEqual([0, 2, 2, 0, -2, -2]);
  });

  it('rejects samples beyond ±2^40 and keeps those at the limit exactly', () => {
    const film = new Film(1, 1);
    expect(film.addSample(0, 0, SAMPLE_LIMIT * 1.0000001, 0, 0)).toBe(false);
    expect(film.addSample(0, 0, 0, -SAMPLE_LIMIT * 2, 0)).toBe(false);
    expect(film.sums[3]).toBe(0);
    for (let i = 0; i < 1000; i++)
      expect(film.addSample(0, 0, SAMPLE_LIMIT, -SAMPLE_LIMIT, 1)).toBe(true);
    expect(film.sums[0]).toBe(1000 * SAMPLE_LIMIT);
    expect(film.sums[1]).toBe(-1000 * SAMPLE_LIMIT);
    expect(film.sums[2]).toBe(1000);
  });

  it('copies every plane of shared rows between windows', () => {
    const full = new Film(2, 4);
    full.addSample(1, 2, 0.3, 0.2, 0.1);
    const window = new Film(2, 2, undefined, 2);
    window.copyRowsFrom(full);
    window.addSample(1, 2, 0.3, 0.2, 0.1);
    full.copyRowsFrom(window);
    const direct = new Film(2, 4);
    direct.addSample(1, 2, 0.3, 0.2, 0.1);
    direct.addSample(1, 2, 0.3, 0.2, 0.1);
    expect(bytes(full).equals(bytes(direct))).toBe(true);
  });

  it('refuses a buffer too small for its size', () => {
    expect(() => new Film(4, 4, new ArrayBuffer(16))).toThrow(/too small/);
  });
});
