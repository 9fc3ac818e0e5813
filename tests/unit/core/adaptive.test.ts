/**
 * Adaptive sampling's rules (src/core/film/adaptive.ts): the per-pixel sample counts
 * of a pass schedule, and the sample map built from a pilot film — which must not
 * read a pixel's own samples (the reason the render stays unbiased), must follow the
 * neighbours' error, and must stay in its rate bounds.
 */
import { describe, expect, it } from 'vitest';
import { Film } from '../../../src/core/index.ts';
import {
  ADAPTIVE_PILOT,
  RATE_MIN,
  RATE_ONE,
  adaptiveCount,
  buildSampleMap,
} from '../../../src/core/film/adaptive.ts';
import { mulberry32 as rng } from '../../helpers/faults.ts';

/** A pilot film whose pixel (x, y) has ADAPTIVE_PILOT grey samples of spread noise(x, y). */
function pilotFilm(
  width: number,
  height: number,
  noise: (x: number, y: number) => number,
  seed = 1,
): Film {
  const next = rng(seed);
  const film = new Film(width, height);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      for (let s = 0; s < ADAPTIVE_PILOT; s++) {
        const v = 0.5 + noise(x, y) * (next() - 0.5);
        film.addSample(x, y, v, v, v);
      }
    }
  }
  return film;
}

describe('adaptiveCount', () => {
  it('takes every pilot pass, then at most one sample a pass at the rate k/RATE_ONE', () => {
    for (let k = RATE_MIN; k <= RATE_ONE; k++) {
      let prev = 0;
      for (let s = 0; s <= 1000; s++) {
        const c = adaptiveCount(s, ADAPTIVE_PILOT, k);
        if (s <= ADAPTIVE_PILOT) expect(c).toBe(s);
        expect(c - prev === 0 || c - prev === 1).toBe(true);
        prev = c;
      }
      // Over 64·m passes after the pilot, exactly k·m samples.
      expect(adaptiveCount(ADAPTIVE_PILOT + 64 * 15, ADAPTIVE_PILOT, k)).toBe(
        ADAPTIVE_PILOT + 15 * k,
      );
    }
    expect(adaptiveCount(5000, ADAPTIVE_PILOT, RATE_ONE)).toBe(5000);
  });

  it('is additive over any split of the passes, so parts hold disjoint sample indices', () => {
    const k = 23;
    const cuts = [0, 3, 16, 17, 40, 41, 200, 1000];
    let total = 0;
    for (let i = 0; i + 1 < cuts.length; i++) {
      total +=
        adaptiveCount(cuts[i + 1], ADAPTIVE_PILOT, k) - adaptiveCount(cuts[i], ADAPTIVE_PILOT, k);
    }
    expect(total).toBe(adaptiveCount(1000, ADAPTIVE_PILOT, k));
  });
});

describe('buildSampleMap', () => {
  it('gives the noisy region more passes than the smooth one, inside the rate bounds', () => {
    const w = 32;
    const h = 16;
    // Left half smooth, right half noisy, a ramp of noise inside the right half.
    const film = pilotFilm(w, h, (x) => (x < w / 2 ? 0.01 : (x - 14) * 0.1));
    const map = buildSampleMap(film, new Uint8Array(w * h));
    let left = 0;
    let right = 0;
    for (let y = 1; y < h - 1; y++) {
      for (let x = 1; x < w - 1; x++) {
        const k = map[y * w + x];
        expect(k).toBeGreaterThanOrEqual(RATE_MIN);
        expect(k).toBeLessThanOrEqual(RATE_ONE);
        if (x < w / 2 - 1) left += k;
        if (x > w / 2) right += k;
      }
    }
    expect(right).toBeGreaterThan(4 * left);
    // The smooth side sits at the floor, the noisiest column at the full rate, and the
    // ramp between rises with the noise.
    expect(map[8 * w + 4]).toBe(RATE_MIN);
    expect(map[8 * w + w - 2]).toBe(RATE_ONE);
    for (let x = w / 2 + 2; x < w - 2; x++) {
      expect(map[8 * w + x]).toBeGreaterThanOrEqual(map[8 * w + x - 1]);
    }
    expect(map[8 * w + w / 2 + 3]).toBeLessThan(RATE_ONE);
  });

  it("never reads the pixel's own samples, only its 8 neighbours'", () => {
    const w = 9;
    const h = 9;
    const base = pilotFilm(w, h, (x, y) => 0.1 + 0.05 * ((x * 7 + y * 3) % 5));
    const before = buildSampleMap(base, new Uint8Array(w * h));
    // Pixel (4, 4) gets a wild extra sample: its own rate must not move, a neighbour's must.
    const changed = pilotFilm(w, h, (x, y) => 0.1 + 0.05 * ((x * 7 + y * 3) % 5));
    changed.addSample(4, 4, 1000, 1000, 1000);
    const after = buildSampleMap(changed, new Uint8Array(w * h));
    expect(after[4 * w + 4]).toBe(before[4 * w + 4]);
    expect(after[4 * w + 5]).toBe(RATE_ONE);
    expect(after[4 * w + 5]).not.toBe(before[4 * w + 5]);
    // Pixels two away see nothing of it.
    expect(after[4 * w + 6]).toBe(before[4 * w + 6]);
  });

  it('gives every pass to pixels with nothing to go by, and is the same bits each time', () => {
    // One pixel: no neighbour at all.
    expect([
      ...buildSampleMap(
        pilotFilm(1, 1, () => 0.3),
        new Uint8Array(1),
      ),
    ]).toEqual([RATE_ONE]);
    // Neighbours with every sample rejected (fewer than two accepted): unknown, full rate.
    const empty = buildSampleMap(new Film(3, 3), new Uint8Array(9));
    expect(empty.every((k) => k === RATE_ONE)).toBe(true);
    // A film of no variance anywhere: the floor, never zero.
    const flat = buildSampleMap(
      pilotFilm(8, 8, () => 0),
      new Uint8Array(64),
    );
    expect(flat.every((k) => k === RATE_MIN)).toBe(true);
    const film = pilotFilm(24, 12, (x, y) => ((x ^ y) & 3) * 0.1, 7);
    const a = buildSampleMap(film, new Uint8Array(24 * 12));
    const b = buildSampleMap(film, new Uint8Array(24 * 12));
    expect(Buffer.from(a).equals(Buffer.from(b))).toBe(true);
  });

  it('refuses a map of the wrong size', () => {
    expect(() => buildSampleMap(new Film(4, 4), new Uint8Array(15))).toThrow(/16 pixels/);
  });
});
