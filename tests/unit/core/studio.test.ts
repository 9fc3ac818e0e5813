/**
 * The studio environment of a bare model (src/core/lights/studio.ts): every texel
 * finite and within the scene format's radiance bound; the dome, the floor and the key
 * light where its header says (the key up and to the left of a camera on +z looking
 * at the model, as framing.ts places it); each texel the radiance at its centre
 * direction in the scene format's lat–long convention (u = atan2(x, −z) / 2π, v = θ / π).
 */
import { describe, expect, it } from 'vitest';
import {
  STUDIO_HEIGHT,
  STUDIO_WIDTH,
  studioEnvironment,
  studioRadiance,
} from '../../../src/core/lights/studio.ts';

const at = (x: number, y: number, z: number) => {
  const l = Math.hypot(x, y, z);
  const out: [number, number, number] = [0, 0, 0];
  studioRadiance(x / l, y / l, z / l, out);
  return out;
};

describe('the studio environment', () => {
  const map = studioEnvironment();
  const rgb = map.image!.rgb;

  it('is a finite, non-negative map within the radiance bound', () => {
    expect([map.image!.width, map.image!.height]).toEqual([STUDIO_WIDTH, STUDIO_HEIGHT]);
    expect(rgb.length).toBe(STUDIO_WIDTH * STUDIO_HEIGHT * 3);
    const bad = rgb.filter((v) => !(Number.isFinite(v) && v >= 0 && v < 1e12));
    expect(bad.length).toBe(0);
  });

  it('has a grey dome over a darker floor and a key light up left of the camera', () => {
    expect(at(0, 1, 0)[0]).toBeCloseTo(0.5, 6);
    expect(at(0, -1, 0)[0]).toBeCloseTo(0.12, 6);
    // The key softbox: up (+y), left (−x), on the camera's side (+z).
    expect(at(-1, 1.1, 0.9)[0]).toBeGreaterThan(7);
    expect(at(1, 1.1, 0.9)[0]).toBeLessThan(2);
  });

  it('stores at each texel the radiance of its centre direction (scene-format lat–long)', () => {
    const c: [number, number, number] = [0, 0, 0];
    for (const [i, j] of [
      [0, 0],
      [64, 30],
      [100, 40],
      [200, 100],
      [255, 127],
    ]) {
      const theta = ((j + 0.5) / STUDIO_HEIGHT) * Math.PI;
      const phi = ((i + 0.5) / STUDIO_WIDTH) * 2 * Math.PI;
      // Inverse of u = atan2(x, −z) / 2π, v = θ / π.
      const x = Math.sin(theta) * Math.sin(phi);
      const z = -Math.sin(theta) * Math.cos(phi);
      expect((Math.atan2(x, -z) / (2 * Math.PI) + 1) % 1).toBeCloseTo((i + 0.5) / STUDIO_WIDTH, 9);
      studioRadiance(x, Math.cos(theta), z, c);
      const o = (j * STUDIO_WIDTH + i) * 3;
      for (let k = 0; k < 3; k++) expect(rgb[o + k]).toBeCloseTo(c[k], 5);
    }
  });
});
