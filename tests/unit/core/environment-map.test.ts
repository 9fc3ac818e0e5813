/**
 * The environment map's lookup, exactly as the spec writes it (checked against an
 * independent transcription of its formulas and against the conventions it states), and
 * the three faces of its sampling warp: sample, pdf and invert agree with each other,
 * the density integrates to one and is proportional to luminance.
 */
import { describe, expect, it } from 'vitest';
import {
  EnvironmentMap,
  EnvironmentSample,
  luminance,
} from '../../../src/core/lights/environment-map.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import type { EnvironmentMapDesc, Vec3 } from '../../../src/core/scene/format/types.ts';

export function makeMap(
  width: number,
  height: number,
  texel: (x: number, y: number) => Vec3,
  scale: Vec3 = [1, 1, 1],
  rotationY = 0,
): EnvironmentMap {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) rgb.set(texel(x, y), (y * width + x) * 3);
  }
  const desc: EnvironmentMapDesc = {
    type: 'map',
    file: 'test.pfm',
    scale,
    rotationY,
    image: { width, height, rgb },
  };
  return new EnvironmentMap(desc);
}

/** The spec's lookup, transcribed on its own: returns [column, row]. */
function specLookup(d: Vec3, w: number, h: number, rotationY: number): [number, number] {
  const th = (rotationY * Math.PI) / 180;
  const x = Math.cos(th) * d[0] - Math.sin(th) * d[2];
  const y = d[1];
  const z = Math.sin(th) * d[0] + Math.cos(th) * d[2];
  const a = Math.atan2(x, -z) / (2 * Math.PI);
  const u = a - Math.floor(a);
  const v = Math.acos(y) / Math.PI;
  return [Math.min(Math.floor(u * w), w - 1), Math.min(Math.floor(v * h), h - 1)];
}

function randomDirection(key: number): Vec3 {
  const z = 1 - 2 * hashToUnit(key, 0);
  const r = Math.sqrt(Math.max(0, 1 - z * z));
  const phi = 2 * Math.PI * hashToUnit(key, 1);
  return [r * Math.cos(phi), r * Math.sin(phi), z];
}

describe('environment map lookup', () => {
  it('follows the stated conventions: u = 0 looks along −z, 0.25 along +x, row 0 is +y', () => {
    const map = makeMap(4, 2, (x, y) => [x, y, 0]);
    const col = (d: Vec3) => map.texel(d[0], d[1], d[2]) % 4;
    const row = (d: Vec3) => Math.floor(map.texel(d[0], d[1], d[2]) / 4);
    const s = Math.SQRT1_2;
    expect(col([0.01, 0, -1])).toBe(0); // just right of u = 0 along −z
    expect(col([1, 0, -0.01])).toBe(0); // just before u = 0.25
    expect(col([1, 0, 0.01])).toBe(1);
    expect(col([0.01, 0, 1])).toBe(1);
    expect(col([-0.01, 0, 1])).toBe(2); // +z is the centre of the image
    expect(col([-1, 0, 0.01])).toBe(2);
    expect(col([-1, 0, -0.01])).toBe(3);
    expect(col([-0.01, 0, -1])).toBe(3); // wraps to the right edge
    expect(row([s, s, 0])).toBe(0);
    expect(row([s, -s, 0])).toBe(1);
    expect(row([0, 1, 0])).toBe(0);
    expect(row([0, -1, 0])).toBe(1);
    // Radiance is the texel times the scale.
    const scaled = makeMap(4, 2, (x, y) => [x + 1, y + 1, 1], [2, 3, 0.5]);
    const out = new EnvironmentSample();
    scaled.eval(-0.01, 0.5, 1, out);
    expect([out.r, out.g, out.b]).toEqual([6, 3, 0.5]);
  });

  it('turns the map about +y by rotationY degrees', () => {
    // Rotated by 90°, world +x sees what world +z saw unrotated (x' = −d.z, z' = d.x).
    const plain = makeMap(8, 4, (x, y) => [x, y, 0]);
    const turned = makeMap(8, 4, (x, y) => [x, y, 0], [1, 1, 1], 90);
    expect(turned.texel(1, 0.1, 0.02)).toBe(plain.texel(-0.02, 0.1, 1));
  });

  it('matches a transcription of the spec on random directions and rotations', () => {
    for (const rot of [0, 37, -200, 720.5]) {
      const map = makeMap(13, 7, () => [1, 1, 1], [1, 1, 1], rot);
      for (let i = 0; i < 3000; i++) {
        const d = randomDirection(sampleKey(2, i, 0));
        const [c, r] = specLookup(d, 13, 7, rot);
        expect(map.texel(d[0], d[1], d[2])).toBe(r * 13 + c);
      }
    }
  });
});

describe('environment map sampling', () => {
  const maps = [
    [
      'random',
      makeMap(16, 8, (x, y) => [((x * 7 + y * 3) % 5) / 4, ((x + y) % 3) / 2, (x % 4) / 3]),
    ],
    [
      'sun, scaled and rotated',
      makeMap(
        32,
        16,
        (x, y) => (x === 20 && y === 5 ? [5000, 4000, 3000] : [0.1, 0.2, 0.4]),
        [1, 0.5, 2],
        123,
      ),
    ],
    ['one texel', makeMap(1, 1, () => [0.5, 0.5, 0.5])],
  ] as const;

  it.each(maps)(
    '%s: sample, pdf, eval and invert agree; luminance / pdf is the integral',
    (_, map) => {
      const s = new EnvironmentSample();
      const v = new EnvironmentSample();
      const back = { x: 0, y: 0 };
      let inverted = 0;
      for (let i = 0; i < 5000; i++) {
        const key = sampleKey(9, i, 0);
        const u0 = hashToUnit(key, 0);
        const u1 = hashToUnit(key, 1);
        expect(map.sample(u0, u1, s)).toBe(true);
        expect(Math.hypot(s.wx, s.wy, s.wz)).toBeCloseTo(1, 12);
        expect(map.pdf(s.wx, s.wy, s.wz)).toBe(s.pdf);
        map.eval(s.wx, s.wy, s.wz, v);
        expect([v.r, v.g, v.b]).toEqual([s.r, s.g, s.b]);
        // Up to the Float32 rounding of the stored conditional CDF: absolute errors of
        // ~2^-24 in a texel's conditional probability p are relative errors of 2^-24 / p.
        const t = map.texel(s.wx, s.wy, s.wz);
        const row = Math.floor(t / map.width);
        const d = map.distribution;
        const conditional = d.prob(t % map.width, row) / d.marginal.prob(row);
        const tolerance = 1e-12 + 2 ** -22 / conditional;
        expect(Math.abs(luminance(s.r, s.g, s.b) / s.pdf / map.integral - 1)).toBeLessThan(
          tolerance,
        );
        map.invert(s.wx, s.wy, s.wz, back);
        if (Math.abs(back.x - u0) < 1e-7 && Math.abs(back.y - u1) < 1e-7) inverted++;
      }
      // Only directions that rounding moved across a texel border may invert elsewhere.
      expect(inverted).toBeGreaterThanOrEqual(4990);
    },
  );

  it('has a density that integrates to 1 over the sphere', () => {
    for (const [, map] of maps) {
      let sum = 0;
      for (let y = 0; y < map.height; y++) {
        for (let x = 0; x < map.width; x++) {
          // Direction through the texel's centre, then pdf times the texel's solid angle.
          const theta = (Math.PI * (y + 0.5)) / map.height;
          const phi = (2 * Math.PI * (x + 0.5)) / map.width;
          const xm = Math.sin(theta) * Math.sin(phi);
          const zm = -Math.sin(theta) * Math.cos(phi);
          const dx = map.cosRot * xm + map.sinRot * zm;
          const dz = -map.sinRot * xm + map.cosRot * zm;
          sum += (map.pdf(dx, Math.cos(theta), dz) * 2 * Math.PI * map.rowDelta[y]) / map.width;
        }
      }
      expect(sum).toBeCloseTo(1, 6);
    }
  });

  it('refuses to sample a black map, and gives density 0 to black texels', () => {
    const black = makeMap(4, 2, () => [0, 0, 0]);
    expect(black.integral).toBe(0);
    expect(black.sample(0.3, 0.3, new EnvironmentSample())).toBe(false);
    const half = makeMap(2, 1, (x) => (x === 0 ? [1, 1, 1] : [0, 0, 0]));
    expect(half.pdf(0.01, 0, -1)).toBeGreaterThan(0);
    expect(half.pdf(-1, 0, 0)).toBe(0);
    expect(half.integral).toBeCloseTo(2 * Math.PI, 12); // a hemisphere of luminance 1
  });
});
