import { describe, expect, it } from 'vitest';
import { hashToUnit, pcgHash, sampleKey } from '../../../src/core/rng/pcg.ts';
import {
  DIM_BOUNCE,
  DIM_BSDF,
  DIM_BSDF_LOBE,
  DIM_FILM,
  DIM_LENS,
  DIM_LIGHT_CHOICE,
  DIM_LIGHT_POINT,
  DIM_PER_BOUNCE,
  DIM_ROULETTE,
  Sampler,
} from '../../../src/core/sampling/sampler.ts';
import {
  SOBOL_DIMENSIONS,
  SOBOL_GROUPS,
  owenScramble,
  reverseBits32,
  sobol1,
  sobolSample,
} from '../../../src/core/sampling/sobol.ts';

/** The 2D pairs of the sampler's layout (first dimension of each). */
const PAIRS = SOBOL_GROUPS.filter(([, size]) => size === 2).map(([first]) => first);
const SINGLES = SOBOL_GROUPS.filter(([, size]) => size === 1).map(([first]) => first);

/** True when the n = 2^k points have exactly one point in every 2^a × 2^(k−a) elementary interval. */
function isNet(xs: number[], ys: number[], k: number): boolean {
  for (let a = 0; a <= k; a++) {
    const nx = 2 ** a;
    const ny = 2 ** (k - a);
    const seen = new Uint8Array(nx * ny);
    for (let i = 0; i < xs.length; i++) {
      const cell = Math.floor(xs[i] * nx) * ny + Math.floor(ys[i] * ny);
      if (seen[cell]++) return false;
    }
  }
  return true;
}

describe('sobol sampler building blocks', () => {
  it('reverses bits', () => {
    expect(reverseBits32(1)).toBe(0x80000000);
    expect(reverseBits32(0x80000000)).toBe(1);
    expect(reverseBits32(0x12345678)).toBe(0x1e6a2c48);
  });

  it('has the textbook second Sobol dimension', () => {
    // Direct (not Gray-code) order of Sobol dimension 2 (Joe & Kuo numbering).
    const expected = [0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875];
    expect(Array.from({ length: 8 }, (_, i) => sobol1(i) / 2 ** 32)).toEqual(expected);
  });

  it('Owen scrambling is a bijection that keeps aligned blocks together', () => {
    // Scrambling the top 8 bits (low bits 0) must permute the 256 values.
    for (const seed of [0, 1, 0xdeadbeef]) {
      const seen = new Set<number>();
      for (let i = 0; i < 256; i++) {
        const y = owenScramble(i << 24, seed);
        seen.add(y >>> 24);
      }
      expect(seen.size).toBe(256);
      // An index prefix [0, 2^k) stays within one aligned block of 2^k.
      const hi = new Set<number>();
      for (let i = 0; i < 64; i++) hi.add(owenScramble(i, seed) >>> 6);
      expect(hi.size).toBe(1);
    }
  });

  it('matches the dimension layout of the sampler', () => {
    const bounce0 = DIM_BOUNCE;
    expect(PAIRS).toEqual([DIM_FILM, DIM_LENS, bounce0 + DIM_LIGHT_POINT, bounce0 + DIM_BSDF]);
    expect(SINGLES).toEqual([]);
    // The 1D choices of the first bounce stay on the hash (see SOBOL_GROUPS).
    const sampler = new Sampler(5, 'sobol');
    sampler.startPixelSample(3, 4);
    for (const d of [DIM_LIGHT_CHOICE, DIM_BSDF_LOBE, DIM_ROULETTE, DIM_PER_BOUNCE - 1]) {
      expect(sampler.get1D(bounce0 + d)).toBe(hashToUnit(sampleKey(5, 3, 4), bounce0 + d));
    }
    expect(SOBOL_DIMENSIONS).toBe(DIM_BOUNCE + DIM_PER_BOUNCE);
  });
});

describe('sobol samples', () => {
  const seed = 7;

  it('lie in [0, 1)', () => {
    for (let pixel = 0; pixel < 50; pixel++) {
      for (let s = 0; s < 64; s++) {
        for (let d = 0; d < SOBOL_DIMENSIONS; d++) {
          const v = sobolSample(seed, pixel, s, d);
          expect(v >= 0 && v < 1).toBe(true);
        }
      }
    }
  });

  it('stratify every 2D pair: the first 2^k samples of a pixel form a (0,k,2)-net, k ≤ 8', () => {
    for (const pixel of [0, 1, 12345, 2 ** 20 + 3]) {
      for (const d of PAIRS) {
        for (let k = 0; k <= 8; k++) {
          const xs: number[] = [];
          const ys: number[] = [];
          for (let s = 0; s < 2 ** k; s++) {
            xs.push(sobolSample(seed, pixel, s, d));
            ys.push(sobolSample(seed, pixel, s, d + 1));
          }
          expect(isNet(xs, ys, k), `pixel ${pixel} dims ${d},${d + 1} k=${k}`).toBe(true);
        }
      }
    }
  });

  it('stratify each dimension alone: 2^k samples fall one per interval of width 2^-k', () => {
    for (const d of [...SINGLES, ...PAIRS, ...PAIRS.map((p) => p + 1)]) {
      for (let k = 0; k <= 8; k++) {
        const seen = new Uint8Array(2 ** k);
        for (let s = 0; s < 2 ** k; s++) seen[Math.floor(sobolSample(seed, 3, s, d) * 2 ** k)]++;
        expect(seen.every((c) => c === 1)).toBe(true);
      }
    }
  });

  it('gives different pixels different points and decorrelates the pairs', () => {
    const a = Array.from({ length: 16 }, (_, s) => sobolSample(seed, 10, s, 0));
    const b = Array.from({ length: 16 }, (_, s) => sobolSample(seed, 11, s, 0));
    const c = Array.from({ length: 16 }, (_, s) => sobolSample(seed + 1, 10, s, 0));
    expect(a).not.toEqual(b);
    expect(a).not.toEqual(c);
    // Within one pixel, the film x and lens x sequences are not the same order.
    const lens = Array.from({ length: 16 }, (_, s) => sobolSample(seed, 10, s, 2));
    expect(lens).not.toEqual(a);
  });

  it('is statistically uniform: the mean over many pixels is 0.5 within 5 sigma', () => {
    // Per pixel the mean of a randomised net is exactly uniform in
    // expectation; across independent pixels the mean of N draws has
    // variance at most 1/(12 N).
    for (let d = 0; d < SOBOL_DIMENSIONS; d++) {
      let sum = 0;
      let sumSq = 0;
      const n = 4000;
      for (let pixel = 0; pixel < n; pixel++) {
        const v = sobolSample(seed, pixel, pixel % 5, d);
        sum += v;
        sumSq += v * v;
      }
      const mean = sum / n;
      const variance = sumSq / n - mean * mean;
      expect(Math.abs(mean - 0.5)).toBeLessThan(5 * Math.sqrt(1 / 12 / n));
      // Uniform on [0,1) has variance 1/12.
      expect(Math.abs(variance - 1 / 12)).toBeLessThan(0.01);
    }
  });

  it('matches a direct evaluation of shuffle, Sobol point and scramble', () => {
    // The fill works in the bit-reversed domain to save reversals; check it
    // against the textbook composition owen(sobol_d(owen(index))).
    for (const [pixel, s] of [
      [0, 0],
      [5, 9],
      [777, 300],
    ]) {
      for (const [g, first] of [
        [1, 0],
        [3, 5],
        [4, 7],
      ]) {
        const key = pcgHash((seed + pcgHash(pixel)) >>> 0);
        const gk = pcgHash((key + Math.imul(g, 0x9e3779b9)) >>> 0);
        const index = owenScramble(s, gk);
        const x = owenScramble(reverseBits32(index), pcgHash(gk ^ 0x68e31da4)) / 2 ** 32;
        const y = owenScramble(sobol1(index), pcgHash(gk ^ 0xb5297a4d)) / 2 ** 32;
        expect(sobolSample(seed, pixel, s, first)).toBe(x);
        expect(sobolSample(seed, pixel, s, first + 1)).toBe(y);
      }
    }
  });

  it('the Sampler returns the same numbers, and the hash beyond the Sobol dimensions', () => {
    const sampler = new Sampler(seed, 'sobol');
    for (const [pixel, s] of [
      [0, 0],
      [99, 5],
      [4242, 1023],
    ]) {
      sampler.startPixelSample(pixel, s);
      for (let d = 0; d < SOBOL_DIMENSIONS; d++) {
        expect(sampler.get1D(d)).toBe(sobolSample(seed, pixel, s, d));
      }
      const key = sampleKey(seed, pixel, s);
      for (let d = SOBOL_DIMENSIONS; d < SOBOL_DIMENSIONS + 16; d++) {
        expect(sampler.get1D(d)).toBe(hashToUnit(key, d));
      }
    }
  });

  it('keeps the numbers of a pixel when other pixels come between its samples', () => {
    // The sampler keeps the Sobol keys of the last pixel; switching back and
    // forth must recompute them, never reuse another pixel's.
    const sampler = new Sampler(seed, 'sobol');
    for (const [pixel, s] of [
      [5, 0],
      [5, 1],
      [6, 0],
      [5, 2],
      [6, 1],
      [6, 2],
    ]) {
      sampler.startPixelSample(pixel, s);
      for (let d = 0; d < SOBOL_DIMENSIONS; d++) {
        expect(sampler.get1D(d)).toBe(sobolSample(seed, pixel, s, d));
      }
    }
  });

  it('fillRange writes dimension + k into out[k] for k in [from, to) and nothing else', () => {
    for (const kind of ['sobol', 'independent'] as const) {
      const sampler = new Sampler(seed, kind);
      for (const base of [0, DIM_BOUNCE, DIM_BOUNCE + 3 * DIM_PER_BOUNCE]) {
        sampler.startPixelSample(321, 9);
        const out = new Float64Array(DIM_PER_BOUNCE).fill(-1);
        sampler.fillRange(base, 1, 5, out);
        for (let k = 0; k < DIM_PER_BOUNCE; k++) {
          expect(out[k]).toBe(k >= 1 && k < 5 ? sampler.get1D(base + k) : -1);
        }
      }
    }
  });

  it('is a pure function of (seed, pixel, sample, dimension): order does not matter', () => {
    const forward = new Sampler(3, 'sobol');
    const backward = new Sampler(3, 'sobol');
    const got: number[] = [];
    for (let s = 0; s < 8; s++) {
      forward.startPixelSample(77, s);
      got.push(forward.get1D(0), forward.get1D(7));
    }
    for (let s = 7; s >= 0; s--) {
      backward.startPixelSample(77, s);
      expect(backward.get1D(0)).toBe(got[2 * s]);
      expect(backward.get1D(7)).toBe(got[2 * s + 1]);
    }
  });
});
