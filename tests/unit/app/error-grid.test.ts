/**
 * The comparison grid of the demo's error plot (src/app/error-grid.ts):
 * film and reference pixels tile the same cells exactly for every film
 * shape the demo makes, so an image equal to the reference has a relMSE
 * of 0 (up to Float32 rounding), and an image one pixel off does not.
 */
import { describe, expect, it } from 'vitest';
import {
  errorFigures,
  gridLayout,
  gridStep,
  referenceLuminance,
} from '../../../src/app/error-grid.ts';

/** A reference with a distinct luminance per pixel. */
function reference(w: number, h: number) {
  const rgb = new Float32Array(w * h * 3);
  for (let p = 0; p < w * h; p++) rgb.fill(0.05 + ((p * 7919) % 997) / 500, p * 3, p * 3 + 3);
  return referenceLuminance(w, h, rgb);
}

/** Overlaps of the interval [a, b) with the unit cells [i, i+1): [i, length] pairs. */
function overlaps(a: number, b: number): [number, number][] {
  const out: [number, number][] = [];
  for (let i = Math.floor(a); i < b; i++) {
    const l = Math.min(b, i + 1) - Math.max(a, i);
    if (l > 1e-12) out.push([i, l]);
  }
  return out;
}

/**
 * A film of width × height framing the reference's vertical field of view
 * (pathwise-scene/1), shifted by `shift` film pixels: each pixel holds four
 * equal samples of the reference's box average over the pixel's square
 * (black outside the reference), which is what a converged render's pixel
 * is.
 */
function filmOf(ref: ReturnType<typeof reference>, width: number, height: number, shift = 0) {
  const sums = new Float32Array(width * height * 4);
  const extra = new Float32Array(width * height * 4);
  const s = height / ref.height; // film pixels per reference pixel
  const left = (width - ref.width * s) / 2;
  for (let y = 0; y < height; y++) {
    const rows = overlaps(y / s, (y + 1) / s);
    for (let x = 0; x < width; x++) {
      let v = 0;
      for (const [rx, wx] of overlaps((x + shift - left) / s, (x + shift + 1 - left) / s)) {
        if (rx < 0 || rx >= ref.width) continue;
        for (const [ry, wy] of rows) v += wx * wy * ref.lum[ry * ref.width + rx];
      }
      v *= s * s;
      const i = (y * width + x) * 4;
      // Grey, so luminance = v; equal samples: zero variance.
      sums.set([4 * v, 4 * v, 4 * v, 4], i);
      extra[i + 3] = 4 * v * v;
    }
  }
  return { sums, extra };
}

describe('error grid', () => {
  it('gives the finest tiling grid: 64 rows for 128² references, 45 for 160×90', () => {
    expect(gridStep(128, 128)).toBe(64);
    expect(gridStep(160, 90)).toBe(45);
    expect(gridLayout(64, 64, 128, 128)).toEqual({
      rows: 64,
      columns: 64,
      k: 1,
      g: 2,
      filmX0: 0,
      refColumn0: 0,
    });
    // A wide film: the reference is the centred square.
    expect(gridLayout(450, 384, 128, 128)).toMatchObject({
      rows: 64,
      columns: 64,
      k: 6,
      filmX0: 33,
    });
    // A narrow film sees only the middle columns of a 16:9 reference.
    expect(gridLayout(450, 360, 160, 90)).toMatchObject({ rows: 45, k: 8, g: 2, refColumn0: 12 });
    // Sizes that do not tile: an odd offset, or too few common rows.
    expect(gridLayout(451, 384, 128, 128)).toBeNull();
    expect(gridLayout(300, 300, 128, 128)).toBeNull();
  });

  const shapes: [number, number, number, number][] = [
    [128, 128, 64, 64],
    [128, 128, 256, 256],
    [128, 128, 450, 384], // landscape
    [128, 128, 250, 320], // portrait: cells beyond the film's sides are skipped
    [160, 90, 450, 360],
    [160, 90, 160, 90],
    [160, 90, 900, 270],
  ];
  for (const [rw, rh, w, h] of shapes) {
    it(`a ${w}×${h} film showing the ${rw}×${rh} reference has relMSE 0; shifted by a pixel it has not`, () => {
      const ref = reference(rw, rh);
      const layout = gridLayout(w, h, rw, rh)!;
      expect(layout).not.toBeNull();
      const exact = filmOf(ref, w, h);
      const f = errorFigures(w, exact.sums, exact.extra, layout, ref);
      expect(f.cells).toBeGreaterThan((layout.rows * layout.columns) / 2 - 1);
      // Zero up to Float32 rounding of the film's sums.
      expect(f.relMse).toBeLessThan(1e-12);
      expect(f.estimatedRelMse).toBeLessThan(1e-8);
      const shifted = filmOf(ref, w, h, 1);
      expect(errorFigures(w, shifted.sums, shifted.extra, layout, ref).relMse).toBeGreaterThan(
        1e-3,
      );
    });
  }

  it('skips cells with unsampled pixels and needs two samples for the estimate', () => {
    const ref = reference(128, 128);
    const layout = gridLayout(64, 64, 128, 128)!;
    const { sums, extra } = filmOf(ref, 64, 64);
    for (let i = 3; i < sums.length; i += 4) sums[i] = 1; // one sample each: no variance
    expect(Number.isNaN(errorFigures(64, sums, extra, layout, ref).estimatedRelMse)).toBe(true);
    sums.fill(0);
    const none = errorFigures(64, sums, extra, layout, ref);
    expect(none.cells).toBe(0);
    expect(Number.isNaN(none.relMse)).toBe(true);
    expect(Number.isNaN(errorFigures(64, sums, extra, layout, null).relMse)).toBe(true);
  });
});
