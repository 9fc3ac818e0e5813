/**
 * The validation suite's punctual-light generator (gltf-draw-lights.ts): each draw is
 * a valid KHR_lights_punctual light and a valid scene-format light, and the two are the
 * same light once the glTF node places it (position, direction, cone, intensity).
 */
import { describe, expect, it } from 'vitest';
import { parseScene } from '../../src/core/index.ts';
import { loadGltf } from '../../src/core/gltf/load.ts';
import { memoryOptions } from '../helpers/gltf.ts';
import { drawPunctualLight } from './gltf-draw-lights.ts';
import { Rng } from './rng.ts';

const SCENE = {
  format: 'pathwise-scene/1',
  camera: { position: [0, 1, 3], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
  materials: {},
  shapes: [],
};

describe('drawPunctualLight', () => {
  it('is a function of the stream alone', () => {
    expect(drawPunctualLight(new Rng(5))).toEqual(drawPunctualLight(new Rng(5)));
  });

  it('gives the same light in a glTF file and in a scene, for 30 draws', async () => {
    const rng = new Rng(20261203);
    const draws = Array.from({ length: 30 }, () => drawPunctualLight(rng, [0.5, 0, -1], 3));
    expect(new Set(draws.map((d) => d.gltf.type)).size).toBe(3);
    const json = {
      asset: { version: '2.0' },
      extensionsUsed: ['KHR_lights_punctual'],
      extensions: { KHR_lights_punctual: { lights: draws.map((d) => d.gltf) } },
      scenes: [{ nodes: draws.map((_, i) => i) }],
      scene: 0,
      nodes: draws.map((d, i) => ({
        ...d.placement,
        extensions: { KHR_lights_punctual: { light: i } },
      })),
    };
    const model = await loadGltf(
      new TextEncoder().encode(JSON.stringify(json)),
      'lights.gltf',
      await memoryOptions(),
    );
    const scene = parseScene(JSON.stringify({ ...SCENE, lights: draws.map((d) => d.scene) }));
    expect(model.lights!.length).toBe(30);
    model.lights!.forEach((g, i) => {
      const s = scene.lights![i];
      expect(g.type).toBe(s.type);
      for (const k of ['position', 'direction', 'color'] as const)
        for (let a = 0; a < 3; a++) expect(Math.abs(g[k][a] - s[k][a])).toBeLessThan(1e-9);
      expect(g.intensity).toBe(s.intensity);
      expect(Math.abs(g.innerConeAngle - s.innerConeAngle)).toBeLessThan(1e-9);
      expect(Math.abs(g.outerConeAngle - s.outerConeAngle)).toBeLessThan(1e-9);
    });
  });
});
