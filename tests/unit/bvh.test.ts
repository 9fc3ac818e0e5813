/**
 * The BVH finds the same nearest hits as the plain loop over shapes, and
 * the scene compiler builds only what a scene has.
 */
import { describe, expect, it } from 'vitest';
import { BVH_THRESHOLD, compileScene } from '../../src/core/index.ts';
import { randomSpheresScene } from '../../src/core/scene/random-spheres.ts';
import { loadScene, renderSampled } from '../helpers/render.ts';
import { Hit, Ray } from '../../src/core/geometry/ray.ts';
import { intersectScene, occluded } from '../../src/core/geometry/trace.ts';
import { pcgHash } from '../../src/core/rng/pcg.ts';

describe('BVH', () => {
  it('answers nearest-hit and occlusion queries exactly like the plain loop', () => {
    const scene = randomSpheresScene(300, 4);
    const list = compileScene(scene, { bvh: false });
    const bvh = compileScene(scene, { bvh: true });
    expect(list.bvh).toBeNull();
    expect(bvh.bvh).not.toBeNull();
    const ray = new Ray();
    const a = new Hit();
    const b = new Hit();
    let state = 7;
    const rand = (): number => (state = pcgHash(state + 1)) / 4294967296;
    let hits = 0;
    for (let i = 0; i < 20000; i++) {
      ray.ox = (rand() - 0.5) * 30;
      ray.oy = rand() * 4;
      ray.oz = (rand() - 0.5) * 30;
      // Include axis-parallel directions, where 1/d is infinite.
      let dx = i % 7 === 0 ? 0 : rand() - 0.5;
      let dy = i % 11 === 0 ? 0 : rand() - 0.5;
      let dz = rand() - 0.5;
      const l = Math.hypot(dx, dy, dz);
      [dx, dy, dz] = [dx / l, dy / l, dz / l];
      [ray.dx, ray.dy, ray.dz] = [dx, dy, dz];
      ray.tMax = i % 3 === 0 ? 5 : Infinity;
      const hitList = intersectScene(list, ray, a);
      const hitBvh = intersectScene(bvh, ray, b);
      expect(hitBvh).toBe(hitList);
      if (hitList) {
        hits++;
        expect(b.t).toBe(a.t);
        expect([b.kind, b.index]).toEqual([a.kind, a.index]);
      }
      expect(occluded(bvh, ray)).toBe(occluded(list, ray));
    }
    expect(hits).toBeGreaterThan(1000);
  });

  it('renders the same image with and without the BVH', () => {
    const scene = loadScene('spheres');
    const a = renderSampled(scene, { width: 40, height: 24, spp: 2, bvh: false });
    const b = renderSampled(scene, { width: 40, height: 24, spp: 2, bvh: true });
    expect(Array.from(b.mean)).toEqual(Array.from(a.mean));
  });

  it('is built only above the measured crossover', () => {
    expect(compileScene(loadScene('cornell')).bvh).toBeNull();
    expect(compileScene(randomSpheresScene(BVH_THRESHOLD)).bvh).not.toBeNull();
  });

  it('compiles no light list for a scene without emitters', () => {
    const compiled = compileScene(loadScene('furnace-diffuse'));
    expect(compiled.lights).toBeNull();
    expect(compiled.quadCount).toBe(0);
    expect(compiled.quads.length).toBe(0);
  });
});
