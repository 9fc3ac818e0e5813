/**
 * χ² goodness of fit of the environment map's `sample` against its `pdf`: directions
 * are histogrammed over a grid of the sphere that is not aligned with the texels (world
 * azimuth ψ = atan2(x, −z) and cos θ = y), and each cell's expected count is exact: the
 * density is constant per texel, so it is the sum over texels of the pdf times the solid
 * angle the texel and the cell share (a product of an azimuth overlap and a cos θ
 * overlap; the rotation shifts the texels' azimuths by −rotationY).
 *
 * Fixed seeds; each test rejects at p < 0.01 / (number of tests), a Šidák-style
 * correction as in the BSDF χ² tests, so the suite's false-alarm rate is below 1%.
 */
import { describe, expect, it } from 'vitest';
import { EnvironmentMap, EnvironmentSample } from '../../src/core/lights/environment-map.ts';
import { hashToUnit, sampleKey } from '../../src/core/rng/pcg.ts';
import type { Vec3 } from '../../src/core/scene/format/types.ts';
import { chi2Test } from '../helpers/chi2.ts';

const TWO_PI = 2 * Math.PI;

function makeMap(
  width: number,
  height: number,
  texel: (x: number, y: number) => Vec3,
  scale: Vec3,
  rotationY: number,
): EnvironmentMap {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) rgb.set(texel(x, y), (y * width + x) * 3);
  }
  return new EnvironmentMap({
    type: 'map',
    file: 'test.pfm',
    scale,
    rotationY,
    image: { width, height, rgb },
  });
}

/** Length of the overlap of [a0, a1) with [b0, b1) on the circle of circumference 2π. */
function circularOverlap(a0: number, a1: number, b0: number, b1: number): number {
  let total = 0;
  for (const k of [-2, -1, 0, 1, 2]) {
    const lo = Math.max(a0, b0 + k * TWO_PI);
    const hi = Math.min(a1, b1 + k * TWO_PI);
    if (hi > lo) total += hi - lo;
  }
  return total;
}

function expectedCounts(map: EnvironmentMap, nPsi: number, nCos: number, n: number): Float64Array {
  const expected = new Float64Array(nPsi * nCos);
  const rot = Math.atan2(map.sinRot, map.cosRot);
  const w = map.width;
  for (let ty = 0; ty < map.height; ty++) {
    const cHi = map.rowCos[ty];
    const cLo = map.rowCos[ty + 1];
    for (let tx = 0; tx < w; tx++) {
      const p = map.distribution.prob(tx, ty);
      if (p === 0) continue;
      const pdf = (p * w) / (TWO_PI * map.rowDelta[ty]);
      // Map azimuth φ = ψ + rotation, so the texel spans ψ ∈ [φ0 − rot, φ1 − rot).
      const psi0 = (TWO_PI * tx) / w - rot;
      const psi1 = (TWO_PI * (tx + 1)) / w - rot;
      for (let cy = 0; cy < nCos; cy++) {
        const c0 = -1 + (2 * cy) / nCos;
        const c1 = -1 + (2 * (cy + 1)) / nCos;
        const dc = Math.min(c1, cHi) - Math.max(c0, cLo);
        if (dc <= 0) continue;
        for (let cx = 0; cx < nPsi; cx++) {
          const dpsi = circularOverlap(
            (TWO_PI * cx) / nPsi,
            (TWO_PI * (cx + 1)) / nPsi,
            psi0,
            psi1,
          );
          if (dpsi > 0) expected[cy * nPsi + cx] += n * pdf * dpsi * dc;
        }
      }
    }
  }
  return expected;
}

const CASES: [string, EnvironmentMap][] = [
  [
    'random texels with black ones',
    makeMap(
      16,
      8,
      (x, y) => {
        const k = sampleKey(77, y * 16 + x, 0);
        return hashToUnit(k, 0) < 0.2
          ? [0, 0, 0]
          : [hashToUnit(k, 1), hashToUnit(k, 2) * 2, hashToUnit(k, 3)];
      },
      [1, 1, 1],
      0,
    ),
  ],
  [
    'a sun in a sky, rotated and scaled',
    makeMap(
      64,
      32,
      (x, y) => (Math.abs(x - 40) <= 1 && y === 9 ? [2000, 1800, 1500] : [0.3, 0.5, 1 - y / 40]),
      [1.5, 1, 0.5],
      -71,
    ),
  ],
  ['a single texel', makeMap(1, 1, () => [1, 2, 3], [1, 1, 1], 30)],
  ['one row, wide', makeMap(40, 1, (x) => [x % 3, 1, 0], [1, 1, 1], 180)],
];

describe('environment map sampling: χ² of sample against pdf', () => {
  const alpha = 0.01 / CASES.length;
  it.each(CASES)('%s', (_, map) => {
    const n = 200_000;
    const nPsi = 23;
    const nCos = 13;
    const observed = new Float64Array(nPsi * nCos);
    const s = new EnvironmentSample();
    let refused = 0;
    for (let i = 0; i < n; i++) {
      const key = sampleKey(1234, i, 0);
      if (!map.sample(hashToUnit(key, 0), hashToUnit(key, 1), s)) {
        refused++;
        continue;
      }
      let psi = Math.atan2(s.wx, -s.wz);
      if (psi < 0) psi += TWO_PI;
      const cx = Math.min(nPsi - 1, Math.floor((psi / TWO_PI) * nPsi));
      const cy = Math.min(nCos - 1, Math.floor(((s.wy + 1) / 2) * nCos));
      observed[cy * nPsi + cx]++;
    }
    expect(refused).toBe(0);
    const expected = expectedCounts(map, nPsi, nCos, n);
    const total = expected.reduce((a, b) => a + b, 0);
    expect(total / n).toBeCloseTo(1, 9);
    const result = chi2Test(observed, expected);
    expect(result.impossible).toBeNull();
    expect(result.pValue, `χ² = ${result.stat.toFixed(1)} on ${result.dof} dof`).toBeGreaterThan(
      alpha,
    );
  });

  it('would notice a density that ignores sin θ (the test has power)', () => {
    // Sampling rows by luminance alone (pbrt without the sin θ factor) over-samples the
    // poles; the same histogram must reject it.
    const map = CASES[0][1];
    const n = 200_000;
    const nPsi = 23;
    const nCos = 13;
    const observed = new Float64Array(nPsi * nCos);
    const w = map.width;
    const h = map.height;
    const weights = new Float64Array(w * h);
    let sum = 0;
    for (let t = 0; t < w * h; t++) {
      const o = 3 * t;
      weights[t] =
        0.2126 * map.rgb[o] * map.scaleR +
        0.7152 * map.rgb[o + 1] * map.scaleG +
        0.0722 * map.rgb[o + 2] * map.scaleB;
      sum += weights[t];
    }
    for (let i = 0; i < n; i++) {
      const key = sampleKey(99, i, 0);
      let u = hashToUnit(key, 0) * sum;
      let t = 0;
      while (t < w * h - 1 && u >= weights[t]) u -= weights[t++];
      const tx = t % w;
      const ty = Math.floor(t / w);
      const theta = (Math.PI * (ty + hashToUnit(key, 1))) / h;
      const phi = (TWO_PI * (tx + hashToUnit(key, 2))) / w;
      const c = Math.cos(theta);
      const cx = Math.min(nPsi - 1, Math.floor((phi / TWO_PI) * nPsi));
      const cy = Math.min(nCos - 1, Math.floor(((c + 1) / 2) * nCos));
      observed[cy * nPsi + cx]++;
    }
    const result = chi2Test(observed, expectedCounts(map, nPsi, nCos, n));
    expect(result.pValue).toBeLessThan(1e-6);
  });
});
