/**
 * The accumulator: compensated Float32 sums stay accurate over long runs,
 * non-finite samples are rejected and counted, never added.
 */
import { describe, expect, it } from 'vitest';
import { Film } from '../../src/core/index.ts';

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

  it('rejects (and leaves out) a finite sample whose sum would overflow Float32', () => {
    const film = new Film(1, 1);
    // A pixel after a long run of huge samples: its red sum is near the Float32 maximum.
    film.sums[0] = 3.3e38;
    film.sums[3] = 1000;
    // 3.3e38 + 1e37 is finite in double but overflows the Float32 sum to Infinity.
    expect(film.addSample(0, 0, 1e17, 1, 1)).toBe(true);
    expect(film.addSample(0, 0, 1e37, 1, 1)).toBe(false);
    expect(film.sums.every(Number.isFinite)).toBe(true);
    expect(film.extra.every(Number.isFinite)).toBe(true);
    expect(film.sums[3]).toBe(1001);
  });

  it('rejects a sample whose squared luminance would overflow the noise sum', () => {
    const film = new Film(1, 1);
    expect(film.addSample(0, 0, 1e19, 1e19, 1e19)).toBe(true); // (1e19)^2 = 1e38 fits
    expect(film.addSample(0, 0, 1e19, 1e19, 1e19)).toBe(true);
    expect(film.addSample(0, 0, 1e19, 1e19, 1e19)).toBe(true);
    expect(film.addSample(0, 0, 1e19, 1e19, 1e19)).toBe(false); // 4e38 does not
    expect(film.addSample(0, 0, 1e19, 0, 0)).toBe(true); // lum 2.1e18: still fits
    expect(film.extra.every(Number.isFinite)).toBe(true);
    expect(film.sums.every(Number.isFinite)).toBe(true);
    expect(film.sums[3]).toBe(4);
  });

  it('addresses a window of rows through y0', () => {
    const film = new Film(3, 2, undefined, 5);
    film.addSample(2, 6, 1, 2, 3);
    expect(Array.from(film.sums.subarray(20, 24))).toEqual([1, 2, 3, 1]);
  });

  it('refuses a buffer too small for its size', () => {
    expect(() => new Film(4, 4, new ArrayBuffer(16))).toThrow(/too small/);
  });
});
