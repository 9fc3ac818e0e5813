/**
 * The Charlie sheen lobe (src/core/bsdf/sheen.ts) and its albedo table (sheen-lut.ts):
 * the table is what scripts/gen-sheen-lut.ts computes from the lobe's own D·V (cells
 * recomputed here to 1e-3, with the table's nodes at μ = (i/31)²), its interpolation
 * returns the nodes exactly, the distribution is normalised (∫ D cosθh dωh = 1), and
 * the lobe is symmetric in its two directions.
 */
import { describe, expect, it } from 'vitest';
import {
  charlieD,
  charlieDV,
  sheenAlbedo,
  sheenAlbedoQuadrature,
  sheenAlpha,
} from '../../../src/core/bsdf/sheen.ts';
import { SHEEN_LUT, SHEEN_LUT_SIZE } from '../../../src/core/bsdf/sheen-lut.ts';

const N1 = SHEEN_LUT_SIZE - 1;

describe('sheen albedo table', () => {
  it('matches the quadrature of the lobe at sampled cells', () => {
    for (const [i, j] of [
      [0, 31],
      [3, 10],
      [10, 10],
      [20, 25],
      [31, 31],
      [5, 2],
    ]) {
      const mu = (i / N1) ** 2;
      const e = sheenAlbedoQuadrature(mu, j / N1, 256);
      expect(Math.abs(SHEEN_LUT[j * SHEEN_LUT_SIZE + i] - e), `cell ${i}, ${j}`).toBeLessThan(
        1e-3 * Math.max(1, e),
      );
      // The interpolation is exact at the nodes.
      expect(sheenAlbedo(mu, j / N1)).toBeCloseTo(SHEEN_LUT[j * SHEEN_LUT_SIZE + i], 6);
    }
  });

  it('is finite and non-negative everywhere, and at most 1 from roughness 0.3 up away from grazing', () => {
    for (let k = 0; k < SHEEN_LUT.length; k++) {
      expect(Number.isFinite(SHEEN_LUT[k]) && SHEEN_LUT[k] >= 0).toBe(true);
      const j = Math.floor(k / SHEEN_LUT_SIZE);
      const i = k % SHEEN_LUT_SIZE;
      if (j / N1 >= 0.3 && (i / N1) ** 2 >= 0.1) expect(SHEEN_LUT[k]).toBeLessThanOrEqual(1);
    }
  });
});

describe('Charlie lobe', () => {
  it('D is normalised: ∫ D(h) cosθh dωh = 1', () => {
    for (const r of [0.3, 0.5, 1]) {
      const alpha = sheenAlpha(r);
      const n = 20_000;
      let sum = 0;
      for (let k = 0; k < n; k++) {
        const t = ((k + 0.5) / n) * (Math.PI / 2);
        sum += charlieD(Math.cos(t), alpha) * Math.cos(t) * Math.sin(t);
      }
      expect(sum * (Math.PI / 2 / n) * 2 * Math.PI).toBeCloseTo(1, 4);
    }
  });

  it('D·V is symmetric in μo and μi', () => {
    for (const r of [0.1, 0.5, 1]) {
      const alpha = sheenAlpha(r);
      for (const [a, b] of [
        [0.1, 0.9],
        [0.45, 0.55],
        [0.02, 0.7],
      ]) {
        expect(charlieDV(a, b, 0.3, alpha)).toBe(charlieDV(b, a, 0.3, alpha));
      }
    }
  });
});
