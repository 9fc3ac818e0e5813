/**
 * Normal mapping (src/core/gltf-material/normal-map.ts) and the barycentric
 * interpolation of glTF vertex attributes (hit-attributes.ts).
 */
import { describe, expect, it } from 'vitest';
import {
  interpolateAttributes,
  interpolateTangent,
} from '../../../src/core/gltf-material/hit-attributes.ts';
import { applyNormalMap } from '../../../src/core/gltf-material/normal-map.ts';
import { HitAttributes } from '../../../src/core/gltf-material/shading-fill.ts';

const out = { x: 0, y: 0, z: 0 };
const map = (
  n: number[],
  t: number[],
  m: number[],
  g: number[] = [0, 0, 1],
): [boolean, number[]] => {
  const ok = applyNormalMap(
    n[0],
    n[1],
    n[2],
    t[0],
    t[1],
    t[2],
    t[3],
    m[0],
    m[1],
    m[2],
    g[0],
    g[1],
    g[2],
    out,
  );
  return [ok, [out.x, out.y, out.z]];
};
const close = (a: number[], b: number[], eps = 1e-12): void =>
  a.forEach((v, i) => expect(Math.abs(v - b[i])).toBeLessThan(eps));

describe('normal mapping', () => {
  it('maps tangent space to the TBN frame, B = (N × T)·w', () => {
    close(map([0, 0, 1], [1, 0, 0, 1], [0, 0, 1])[1], [0, 0, 1]);
    close(map([0, 0, 1], [1, 0, 0, 1], [0.6, 0, 0.8])[1], [0.6, 0, 0.8]);
    close(map([0, 0, 1], [1, 0, 0, 1], [0, 0.6, 0.8])[1], [0, 0.6, 0.8]);
    close(map([0, 0, 1], [1, 0, 0, -1], [0, 0.6, 0.8])[1], [0, -0.6, 0.8]);
    // A frame turned about N: T = +y, so B = N × T = −x.
    close(map([0, 0, 1], [0, 1, 0, 1], [0.6, 0, 0.8])[1], [0, 0.6, 0.8]);
    close(map([0, 0, 1], [0, 1, 0, 1], [0, 0.6, 0.8])[1], [-0.6, 0, 0.8]);
  });

  it('orthogonalises an interpolated tangent against N', () => {
    const s = Math.SQRT1_2;
    close(map([0, 0, 1], [s, 0, s, 1], [0.6, 0, 0.8])[1], [0.6, 0, 0.8]);
  });

  it('leaves N unperturbed for a degenerate frame', () => {
    expect(map([0, 0, 1], [0, 0, 0, 0], [0.6, 0, 0.8])).toEqual([false, [0, 0, 1]]);
    expect(map([0, 0, 1], [0, 0, 2, 1], [0.6, 0, 0.8])).toEqual([false, [0, 0, 1]]);
  });

  it('keeps the result on the geometric normal side', () => {
    const [ok, n] = map([0, 0, 1], [1, 0, 0, 1], [1, 0, 0]);
    expect(ok).toBe(true);
    expect(n[2]).toBeGreaterThan(0);
    expect(n[0]).toBeGreaterThan(0.999);
    // The same with the geometric normal on the other side (a back-facing frame).
    const [, m] = map([0, 0, -1], [1, 0, 0, 1], [1, 0, 0], [0, 0, -1]);
    expect(m[2]).toBeLessThan(0);
    expect(Math.hypot(...m)).toBeCloseTo(1, 12);
  });
});

describe('vertex attributes at a hit', () => {
  const uv0 = Float32Array.of(0, 0, 1, 0, 0, 1);
  const colors = Float32Array.of(1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 0.5);
  const tangents = Float32Array.of(1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1);
  const h = new HitAttributes();

  it('interpolates barycentrically; absent arrays give the glTF defaults', () => {
    interpolateAttributes({ uv0, uv1: null, colors, tangents }, 0, 1, 2, 0.25, 0.5, h);
    close([h.u0, h.v0, h.u1, h.v1], [0.25, 0.5, 0, 0], 1e-7);
    close([h.r, h.g, h.b, h.a], [0.25, 0.25, 0.5, 0.75], 1e-7);
    interpolateAttributes(
      { uv0: null, uv1: null, colors: null, tangents: null },
      0,
      1,
      2,
      0.3,
      0.3,
      h,
    );
    expect([h.u0, h.v0, h.r, h.g, h.b, h.a]).toEqual([0, 0, 1, 1, 1, 1]);
    const t = new Float64Array(4);
    interpolateTangent(tangents, 0, 1, 2, 1, 0, t);
    expect(Array.from(t)).toEqual([0, 1, 0, 1]);
  });
});
