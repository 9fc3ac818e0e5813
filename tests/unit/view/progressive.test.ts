/**
 * The pure pieces of the progressive display: the order in which a pass
 * visits its stripes (a permutation that spreads the pass over the frame
 * and leaves every pixel's sums unchanged), the backdrop composite shown
 * under unsampled pixels, and the automatic render scale.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import {
  Film,
  PathTracer,
  RenderStats,
  compileScene,
  parseScene,
  tonemapSums,
} from '../../../src/core/index.ts';
import { chooseRenderScale, MIN_AUTO_PIXELS, SpeedProbe } from '../../../src/view/auto-scale.ts';
import { compositeBackdrop, tonemapOverBackdrop } from '../../../src/view/backdrop.ts';
import { stripeOrder } from '../../../workers/browser/render-protocol.ts';

describe('stripeOrder', () => {
  it('is a permutation of the stripes for every count', () => {
    for (let n = 1; n <= 300; n++) {
      const order = stripeOrder(n);
      expect([...order].sort((a, b) => a - b)).toEqual([...Array(n).keys()]);
    }
  });

  it('spreads each prefix of a pass over the frame (coarse to fine)', () => {
    for (const n of [16, 81, 100, 256, 270]) {
      const order = stripeOrder(n);
      // After the first m claims, no run of untouched stripes is longer
      // than about n/m: the covered stripes lie evenly over the frame.
      for (let m = 2; m <= n; m *= 2) {
        const covered = new Uint8Array(n);
        for (let i = 0; i < m; i++) covered[order[i]] = 1;
        let gap = 0;
        let longest = 0;
        for (let s = 0; s < n; s++) {
          gap = covered[s] ? 0 : gap + 1;
          longest = Math.max(longest, gap);
        }
        expect(longest, `n=${n} m=${m}`).toBeLessThanOrEqual(Math.ceil((2 * n) / m));
      }
    }
  });

  it('leaves the image bit-identical: passes over stripes in this order equal the plain render', () => {
    const scene = parseScene(readFileSync('scenes/cornell.json', 'utf8'));
    const options = { width: 24, height: 20, maxBounces: 4, seed: 3, camera: scene.camera };
    const plain = new Film(24, 20);
    new PathTracer(compileScene(scene), options).renderRows(plain, 0, 20, 0, 3, new RenderStats());
    const spread = new Film(24, 20);
    const tracer = new PathTracer(compileScene(scene), options);
    const rows = 3;
    const order = stripeOrder(Math.ceil(20 / rows));
    for (let pass = 0; pass < 3; pass++) {
      for (const stripe of order) {
        const y1 = Math.min(20, stripe * rows + rows);
        tracer.renderRows(spread, stripe * rows, y1, pass, pass + 1, new RenderStats());
      }
    }
    expect(Buffer.from(spread.buffer).equals(Buffer.from(plain.buffer))).toBe(true);
  });
});

/** A film of w × h whose pixel (x, y) has `n` samples of value v(x, y). */
function film(w: number, h: number, v: (x: number, y: number) => number, n = 1): Float32Array {
  const sums = new Float32Array(w * h * 4);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      const i = (y * w + x) * 4;
      sums.set([v(x, y) * n, 2 * v(x, y) * n, 0, n], i);
    }
  }
  return sums;
}

describe('backdrop', () => {
  it('a fully sampled film becomes the backdrop at its own resolution, as means', () => {
    const b = compositeBackdrop(
      film(4, 3, (x, y) => x + y, 4),
      4,
      3,
      null,
    )!;
    expect([b.width, b.height]).toEqual([4, 3]);
    expect(Array.from(b.rgba.subarray(4 * 5, 4 * 6))).toEqual([2, 4, 0, 1]); // pixel (1, 1)
  });

  it('unsampled pixels keep the old picture, scaled, at the larger resolution', () => {
    const under = compositeBackdrop(
      film(8, 8, () => 1),
      8,
      8,
      null,
    )!;
    // A 2 × 2 preview whose top-left pixel alone has a sample.
    const preview = film(2, 2, () => 5).map((v, i) => (i >= 4 ? 0 : v));
    const b = compositeBackdrop(preview, 2, 2, under)!;
    expect([b.width, b.height]).toEqual([8, 8]);
    expect(b.rgba[0]).toBe(5); // under the sampled preview pixel
    expect(b.rgba[(7 * 8 + 7) * 4]).toBe(1); // the old picture
    expect(b.rgba[(7 * 8 + 7) * 4 + 3]).toBe(1);
  });

  it('a film without any sample leaves the backdrop as it was; none at all stays none', () => {
    const under = compositeBackdrop(
      film(2, 2, () => 1),
      2,
      2,
      null,
    );
    expect(compositeBackdrop(new Float32Array(16), 2, 2, under)).toBe(under);
    expect(compositeBackdrop(new Float32Array(16), 2, 2, null)).toBeNull();
  });

  it('Canvas 2D tone mapping over the backdrop equals tonemapSums where there are samples', () => {
    const sums = film(6, 4, (x, y) => 0.1 * (x + 2 * y), 3);
    for (let i = 3; i < sums.length; i += 8) sums.fill(0, i - 3, i + 1); // every other pixel empty
    const backdrop = compositeBackdrop(
      film(3, 2, () => 0.7),
      3,
      2,
      null,
    );
    const out = new Uint8ClampedArray(6 * 4 * 4);
    tonemapOverBackdrop(sums, 6, 4, 0, 4, backdrop, 1.5, out);
    const plain = new Uint8ClampedArray(out.length);
    tonemapSums(sums, 1.5, plain);
    const filled = new Uint8ClampedArray(out.length);
    tonemapSums(
      film(6, 4, () => 0.7),
      1.5,
      filled,
    );
    for (let p = 0; p < 24; p++) {
      const want = sums[p * 4 + 3] > 0 ? plain : filled;
      expect(Array.from(out.subarray(p * 4, p * 4 + 4))).toEqual(
        Array.from(want.subarray(p * 4, p * 4 + 4)),
      );
    }
  });
});

describe('automatic render scale', () => {
  it('picks the scale whose pass takes the budget, at most 1, never below MIN_AUTO_PIXELS', () => {
    // 1000 × 800 CSS pixels at a pixel ratio of 2: 3.2 M device pixels.
    const scale = chooseRenderScale(800_000, 1000 * 800, 2, 0.2);
    const pixels = 1000 * 800 * 4 * scale * scale;
    expect(pixels / 800_000).toBeCloseTo(0.2, 10);
    expect(chooseRenderScale(1e12, 1000 * 800, 2)).toBe(1);
    // A slow (or unmeasured) machine still gets MIN_AUTO_PIXELS.
    for (const rate of [1, NaN]) {
      const floor = chooseRenderScale(rate, 1000 * 800, 2);
      expect(1000 * 800 * 4 * floor * floor).toBeCloseTo(MIN_AUTO_PIXELS, 6);
    }
    // A view smaller than that renders at full size, however slow.
    expect(chooseRenderScale(1, 64 * 64, 1)).toBe(1);
  });

  it('measures samples per second from progress between two frames, after a whole pass', () => {
    const probe = new SpeedProbe(0.5, 50);
    expect(probe.update(0, 0.2, 0, 1000)).toBeNull(); // before the window opens
    expect(probe.update(10, 0.5, 0, 1000)).toBeNull(); // opens: 0.5 passes at 10 ms
    expect(probe.update(40, 1.5, 1, 1000)).toBeNull(); // too short a window
    // 2 passes of 1000 pixels in 100 ms.
    expect(probe.update(110, 2.5, 2, 1000)).toBeCloseTo(20_000, 6);
  });

  it('times a film that reached its target before a window fitted from its start', () => {
    const probe = new SpeedProbe(Number.MIN_VALUE, 50, 100);
    expect(probe.update(120, 2, 2, 500)).toBeNull(); // the window opens only now
    expect(probe.update(125, 2, 2, 500)).toBeNull(); // and the progress stalls (target 2)
    // Finished: 2 passes of 500 pixels in the 50 ms since the start.
    expect(probe.update(150, 2, 2, 500, true)).toBeCloseTo(20_000, 6);
  });
});
