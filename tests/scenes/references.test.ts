/**
 * The canonical scenes converge to Mitsuba 3's renders (65,536 spp, in
 * tests/references). Two checks per scene, both with fixed seeds:
 * - per-channel image means within 1% of the reference's;
 * - a block test: 16×16-pixel block averages against the reference's,
 *   z-scored by the render's own per-pixel sample variance; Σz² must stay
 *   below the χ² quantile at p = 0.001 and no block beyond |z| = 5.5
 *   (Šidák-corrected p ≈ 0.001 over all blocks and channels).
 */
import { describe, expect, it } from 'vitest';
import {
  blockChiSquare,
  chiSquareQuantile,
  imageMean,
  loadReference,
  loadScene,
  referenceMean,
  renderSampled,
} from '../helpers/render.ts';

// spp per scene: mirror's caustics (light seen through glass and in the
// mirror ball, reachable only by BSDF sampling) are heavy-tailed, and a
// sample variance from few samples underestimates them; 512 spp is where
// its block statistics settle.
const cases = [
  { name: 'cornell', spp: 64 },
  { name: 'spheres', spp: 128 },
  { name: 'mirror', spp: 512 },
];

describe.each(cases)('$name converges to the Mitsuba reference', ({ name, spp }) => {
  const ref = loadReference(name);
  const img = renderSampled(loadScene(name), {
    width: ref.width,
    height: ref.height,
    spp,
    seed: 7,
  });

  it('has per-channel image means within 1% of the reference', () => {
    const ours = imageMean(img).mean;
    const theirs = referenceMean(ref);
    for (let c = 0; c < 3; c++) expect(Math.abs(ours[c] / theirs[c] - 1)).toBeLessThan(0.01);
  });

  it('matches the reference block by block within its own noise', () => {
    const { chi2, dof, maxAbsZ } = blockChiSquare(img, ref, 16, spp / 65536);
    expect(dof).toBeGreaterThan(100);
    expect(chi2).toBeLessThan(chiSquareQuantile(dof, 3.09));
    expect(maxAbsZ).toBeLessThan(5.5);
  });

  it('rejects no sample', () => {
    expect(img.stats.rejected).toBe(0);
  });
});
