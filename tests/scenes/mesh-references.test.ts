/**
 * The canonical mesh and environment-map scenes converge to Mitsuba 3's renders (in
 * tests/references, made by ../shared/tools/mitsuba_ref.py; spp in references.json),
 * with the same two checks as references.test.ts: per-channel image means within 1%,
 * and the block test (16×16-pixel blocks z-scored by the render's own variance plus
 * the reference's, Σz² below the χ² quantile at p = 0.001, no |z| beyond 5.5).
 *
 * The scenes render at half the reference's resolution against the reference averaged
 * over 2×2 pixels: with the box pixel filter that is exactly the same expected image,
 * at a quarter of the cost.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import {
  ROOT,
  blockChiSquare,
  chiSquareQuantile,
  downsample,
  imageMean,
  loadReference,
  loadSceneWithFiles,
  referenceMean,
  renderSampled,
  type SampledImage,
} from '../helpers/render.ts';

const entries = JSON.parse(readFileSync(`${ROOT}tests/references/references.json`, 'utf8'))
  .entries as Record<string, { spp: number }>;

// spp per scene: the glass bunny's caustics (the lamp seen through glass, reachable only
// by BSDF sampling) are heavy-tailed, like the mirror scene's.
const cases = [
  { name: 'cornell-bunny', spp: 128 },
  { name: 'cornell-bunny-glass', spp: 1024 },
  { name: 'metal-sky', spp: 128 },
  { name: 'emissive-room', spp: 128 },
];

describe.each(cases)('$name converges to the Mitsuba reference', ({ name, spp }) => {
  const full = loadReference(name);
  const ref = downsample(full, 2);
  let img: SampledImage;

  it('renders with its files', { timeout: 600_000 }, async () => {
    const scene = await loadSceneWithFiles(name);
    img = renderSampled(scene, { width: ref.width, height: ref.height, spp, seed: 7 });
    expect(img.stats.rejected).toBe(0);
  });

  it('has per-channel image means within 1% of the reference', () => {
    const ours = imageMean(img).mean;
    const theirs = referenceMean(ref);
    for (let c = 0; c < 3; c++) expect(Math.abs(ours[c] / theirs[c] - 1)).toBeLessThan(0.01);
  });

  it('matches the reference block by block within its own noise', () => {
    // The reference's variance per pixel is ours × (our spp / its spp), 4× smaller for
    // its 2×2 averaged pixels.
    const { chi2, dof, maxAbsZ } = blockChiSquare(img, ref, 8, spp / (4 * entries[name].spp));
    expect(dof).toBeGreaterThan(100);
    expect(chi2).toBeLessThan(chiSquareQuantile(dof, 3.09));
    expect(maxAbsZ).toBeLessThan(5.5);
  });
});
