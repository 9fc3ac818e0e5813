/**
 * Analytic scenes with exact answers (shared/README.md):
 * - furnace-diffuse: a convex diffuse sphere (albedo 0.8) in a uniform
 *   environment of 1 reflects exactly 0.8: its bounce rays never meet it
 *   again. Background pixels read exactly 1.
 * - furnace-enclosure: a closed box of walls emitting 1 with albedo 0.5,
 *   four bounces: 1 + 0.5 + 0.25 + 0.125 + 0.0625 = 1.9375 everywhere.
 * - furnace-glass: a clear glass sphere in a uniform environment of 1
 *   reads 1 everywhere; every path that leaves carries weight exactly 1.
 * Tolerances come from the renders' own sample variance (z ≤ 4) unless the
 * estimator is exact per sample.
 */
import { describe, expect, it } from 'vitest';
import {
  chiSquareQuantile,
  imageMean,
  loadReference,
  loadScene,
  referenceMean,
  renderSampled,
} from '../helpers/render.ts';

describe('furnace-diffuse', () => {
  const img = renderSampled(loadScene('furnace-diffuse'), { spp: 16 });

  it('reads 0.8 on the sphere and 1 on the background, exactly per pixel', () => {
    let sphere = 0;
    let background = 0;
    let edge = 0;
    for (let p = 0; p < img.width * img.height; p++) {
      const v = img.mean[p * 3];
      if (Math.abs(v - 0.8) < 1e-12) sphere++;
      else if (Math.abs(v - 1) < 1e-12) background++;
      else {
        // Only pixels on the silhouette may mix the two, and then they vary.
        expect(v).toBeGreaterThan(0.8);
        expect(v).toBeLessThan(1);
        expect(img.varianceOfMean[p * 3]).toBeGreaterThan(1e-6);
        edge++;
      }
    }
    expect(sphere).toBeGreaterThan(500);
    expect(background).toBeGreaterThan(1000);
    // The silhouette of a sphere ~29 px across is ~90 px around.
    expect(edge).toBeLessThan(200);
  });

  it('matches the reference image mean within its noise (edge pixels mix the two)', () => {
    const ref = loadReference('furnace-diffuse');
    const big = renderSampled(loadScene('furnace-diffuse'), {
      width: ref.width,
      height: ref.height,
      spp: 16,
    });
    const { mean, stderr } = imageMean(big);
    const theirs = referenceMean(ref);
    for (let c = 0; c < 3; c++) {
      // The reference's own noise (65,536 spp) is negligible; 1e-5 covers its float32 sums.
      expect(Math.abs(mean[c] - theirs[c])).toBeLessThan(4 * stderr[c] + 1e-5);
    }
  });
});

describe('furnace-enclosure', () => {
  it('reads 1.9375 everywhere, within the render noise', () => {
    const img = renderSampled(loadScene('furnace-enclosure'), { spp: 64 });
    const { mean, stderr } = imageMean(img);
    for (let c = 0; c < 3; c++) {
      expect(stderr[c]).toBeGreaterThan(0);
      expect(Math.abs(mean[c] - 1.9375)).toBeLessThan(4 * stderr[c]);
    }
    // And block by block (8×8 pixels): Σz² within the χ² quantile at p = 0.001.
    let chi2 = 0;
    let dof = 0;
    for (let by = 0; by < img.height; by += 8) {
      for (let bx = 0; bx < img.width; bx += 8) {
        let sum = 0;
        let variance = 0;
        for (let y = by; y < by + 8; y++) {
          for (let x = bx; x < bx + 8; x++) {
            sum += img.mean[(y * img.width + x) * 3];
            variance += img.varianceOfMean[(y * img.width + x) * 3];
          }
        }
        chi2 += (sum - 64 * 1.9375) ** 2 / variance;
        dof++;
      }
    }
    expect(chi2).toBeLessThan(chiSquareQuantile(dof, 3.09));
  });

  it('agrees between the NEE+MIS and BSDF-only estimators', () => {
    const a = imageMean(
      renderSampled(loadScene('furnace-enclosure'), { spp: 32, width: 32, height: 32 }),
    );
    const b = imageMean(
      renderSampled(loadScene('furnace-enclosure'), {
        spp: 32,
        width: 32,
        height: 32,
        estimator: 'bsdf',
        seed: 3,
      }),
    );
    for (let c = 0; c < 3; c++) {
      expect(Math.abs(a.mean[c] - b.mean[c])).toBeLessThan(
        4 * Math.hypot(a.stderr[c], b.stderr[c]),
      );
      expect(Math.abs(b.mean[c] - 1.9375)).toBeLessThan(4 * b.stderr[c]);
    }
  });
});

describe('furnace-glass', () => {
  it('reads 1.0 within 1e-4 at 64 bounces (long specular chains keep unit directions)', () => {
    const img = renderSampled(loadScene('furnace-glass'), { spp: 32 });
    expect(img.stats.rejected).toBe(0);
    const { mean } = imageMean(img);
    for (let c = 0; c < 3; c++) expect(Math.abs(mean[c] - 1)).toBeLessThan(1e-4);
  });
});
