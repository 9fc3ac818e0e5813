/**
 * The radiance bound (docs/scene-format.md, "Bad input"): `emission`, a constant
 * `environment` and every environment-map texel times its `scale` are at most 1e12.
 *
 * Why 1e12: the film sums samples in Float32 (max ≈ 3.4e38). A sample's radiance is an
 * emitted radiance times path weights of order one, so with at most 2^20 samples per
 * pixel (LIMITS.spp) a pixel sum stays below ~1e18, twenty orders of magnitude short of
 * overflow; the film still rejects (and counts) a sample that would overflow a sum.
 */

import type { Vec3 } from '../format/types.ts';
import type { NumberRule, Problems } from './validate-helpers.ts';

export const MAX_RADIANCE = 1e12;

const BOUND = 'be at most 1e12 (the radiance bound, so that sums of samples cannot overflow)';

/** A radiance component: finite (checked by expectNumber), >= 0 and <= MAX_RADIANCE. */
export const RADIANCE: NumberRule = {
  ok: (x) => x >= 0 && x <= MAX_RADIANCE,
  rule: (x) => (x < 0 ? 'be >= 0' : BOUND),
};

const CHANNELS = ['r', 'g', 'b'];

/**
 * Checks the texels of an environment map against the bound: each of r, g, b must be
 * finite and >= 0, and times its `scale` at most MAX_RADIANCE (computed in double
 * precision, so a product that overflows is caught too). `texels` is row-major RGB (or
 * `stride` floats per texel, RGB first), row 0 at the top. Records one problem naming the
 * first offending texel and how many texels break the rule; returns true when all pass.
 *
 * Call it before building anything from the map (its sampling distribution, say), so a
 * bad map costs one pass over data already in memory.
 */
export function checkTexelRadiance(
  texels: ArrayLike<number>,
  width: number,
  scale: Vec3,
  path: string,
  problems: Problems,
  stride = 3,
): boolean {
  let bad = 0;
  let first = '';
  const count = Math.floor(texels.length / stride);
  for (let t = 0; t < count; t++) {
    for (let c = 0; c < 3; c++) {
      const value = texels[t * stride + c];
      const scaled = value * scale[c];
      if (value >= 0 && scaled <= MAX_RADIANCE) continue; // false for NaN, as wanted
      if (bad === 0) {
        const where = `texel (${t % width}, ${Math.floor(t / width)}) ${CHANNELS[c]}`;
        first =
          !(value >= 0) || !Number.isFinite(value)
            ? `${where} must be a finite number >= 0, got ${value}`
            : `${where} times scale (${value} * ${scale[c]} = ${scaled}) must ${BOUND}`;
      }
      bad++;
      break;
    }
  }
  if (bad === 0) return true;
  const more = bad > 1 ? ` (${bad} texels break this rule)` : '';
  problems.push(`${path}: ${first}${more}`);
  return false;
}
