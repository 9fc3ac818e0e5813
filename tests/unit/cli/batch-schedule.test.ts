/**
 * The pieces of the batch loop that need no render: the fixed sample
 * counts at which --noise is checked, sample-range sets, and the progress
 * bar's arithmetic and text.
 */
import { describe, expect, it } from 'vitest';
import {
  findOverlap,
  formatRanges,
  missingRanges,
  normalizeRanges,
  rangeSamples,
} from '../../../src/core/index.ts';
import { isNoiseCheck, nextNoiseCheck } from '../../../src/cli/batch.ts';
import { estimateProgress, formatDuration, formatProgress } from '../../../src/cli/progress.ts';

describe('noise check points', () => {
  it('are A+2, A+3, … then every ⌊m/16⌋ samples, whatever point one asks from', () => {
    const points: number[] = [];
    for (let c = nextNoiseCheck(100, 100); c < 100 + 2000; c = nextNoiseCheck(100, c))
      points.push(c);
    expect(points.slice(0, 3)).toEqual([102, 103, 104]);
    const gaps = points.slice(1).map((p, i) => p - points[i]);
    for (let i = 0; i < gaps.length; i++) {
      expect(gaps[i]).toBe(Math.max(1, Math.floor((points[i] - 100) / 16)));
    }
    // Asking from inside a gap gives the next point of the same sequence.
    for (let n = 100; n < 2000; n += 37) {
      const next = nextNoiseCheck(100, n);
      expect(points).toContain(next);
      expect(next).toBeGreaterThan(n);
      expect(isNoiseCheck(100, next)).toBe(true);
    }
    expect(isNoiseCheck(100, 101)).toBe(false);
    // Few points even for the longest render (cheap to check).
    let count = 0;
    for (let c = nextNoiseCheck(0, 0); c <= 1 << 20; c = nextNoiseCheck(0, c)) count++;
    expect(count).toBeLessThan(300);
  });
});

describe('sample ranges', () => {
  it('normalizes, finds overlaps and gaps', () => {
    expect(
      normalizeRanges([
        [8, 12],
        [0, 4],
        [4, 6],
      ]),
    ).toEqual([
      [0, 6],
      [8, 12],
    ]);
    expect(
      normalizeRanges([
        [0, 5],
        [4, 6],
      ]),
    ).toBeNull();
    expect(
      findOverlap(
        [[0, 5]],
        [
          [7, 9],
          [3, 8],
        ],
      ),
    ).toEqual([3, 5]);
    expect(findOverlap([[0, 5]], [[5, 9]])).toBeNull();
    expect(
      missingRanges(
        [
          [2, 4],
          [6, 8],
        ],
        10,
      ),
    ).toEqual([
      [0, 2],
      [4, 6],
      [8, 10],
    ]);
    expect(missingRanges([[0, 10]], 10)).toEqual([]);
    expect(
      rangeSamples([
        [2, 4],
        [6, 9],
      ]),
    ).toBe(5);
    expect(
      formatRanges([
        [1, 2],
        [3, 4],
        [5, 6],
      ]),
    ).toBe('[1, 2), [3, 4) and [5, 6)');
  });
});

describe('progress bar', () => {
  it('takes the criterion that ends the render first, and its ETA', () => {
    // Half the samples in 10 s: 10 s left.
    expect(estimateProgress({ spp: 50, sppFrom: 0, sppTarget: 100, elapsed: 10 })).toEqual({
      fraction: 0.5,
      eta: 10,
    });
    // A time budget that ends sooner wins.
    const t = estimateProgress({ spp: 50, sppFrom: 0, sppTarget: 100, elapsed: 10, timeLeft: 2.5 });
    expect(t.fraction).toBeCloseTo(0.8);
    expect(t.eta).toBe(2.5);
    // Noise 0.04 at 100 spp towards 0.02 needs 400 spp: a quarter done.
    const n = estimateProgress({
      spp: 100,
      sppFrom: 0,
      sppTarget: 1 << 20,
      elapsed: 5,
      noise: 0.04,
      noiseTarget: 0.02,
      noiseSpp: 100,
    });
    expect(n.fraction).toBeCloseTo(0.25);
    expect(n.eta).toBeCloseTo(15);
    // A resumed render's rate counts only this process's samples.
    expect(estimateProgress({ spp: 60, sppFrom: 40, sppTarget: 100, elapsed: 10 }).eta).toBe(20);
  });

  it('formats one line that fits the terminal', () => {
    const line = formatProgress(
      {
        spp: 133,
        sppFrom: 0,
        sppTarget: 256,
        elapsed: 12,
        noise: 0.031,
        noiseTarget: 0.02,
        noiseSpp: 128,
      },
      100,
    );
    expect(line).toMatch(/^\[#+\.*\] +\d+%  133\/256 spp  0:12  ETA 0:\d\d  noise 0\.031 → 0\.02$/);
    expect(
      formatProgress({ spp: 1, sppFrom: 0, sppTarget: 2, elapsed: 1 }, 30).length,
    ).toBeLessThan(30);
    expect(formatDuration(3725)).toBe('1:02:05');
    expect(formatDuration(Infinity)).toBe('--:--');
  });
});
