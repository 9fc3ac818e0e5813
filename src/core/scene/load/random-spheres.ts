/**
 * A stress scene: `count` random spheres over a ground quad under one area
 * light, deterministic for a given seed. Used by the BVH crossover
 * benchmark and by the test that a 10,000-sphere scene traces at a speed
 * per segment comparable to the Cornell box.
 */
import { pcgHash, INV_2_32 } from '../../rng/pcg.ts';
import type { Scene, ShapeDesc } from '../format/types.ts';

export function randomSpheresScene(count: number, seed = 1): Scene {
  let state = seed >>> 0;
  const rand = (): number => {
    state = pcgHash(state + 1);
    return state * INV_2_32;
  };
  // Spheres fill a square field whose area grows with the count, so the
  // density (and the depth complexity seen by a ray) stays moderate.
  const half = Math.sqrt(count) * 0.6 + 1;
  const shapes: ShapeDesc[] = [
    {
      type: 'quad',
      corner: [-half, 0, -half],
      u: [0, 0, 2 * half],
      v: [2 * half, 0, 0],
      material: 'ground',
    },
    {
      type: 'quad',
      corner: [-half / 2, 2 * half, -half / 2],
      u: [half, 0, 0],
      v: [0, 0, half],
      material: 'lamp',
    },
  ];
  for (let i = 0; i < count; i++) {
    const r = 0.1 + 0.25 * rand();
    shapes.push({
      type: 'sphere',
      center: [(2 * rand() - 1) * half, r + rand() * 0.5, (2 * rand() - 1) * half],
      radius: r,
      material: i % 3 === 0 ? 'red' : i % 3 === 1 ? 'white' : 'metal',
    });
  }
  return {
    format: 'pathwise-scene/1',
    name: `${count} random spheres`,
    camera: {
      position: [0, half * 0.9, -half * 1.6],
      target: [0, 0, 0],
      up: [0, 1, 0],
      fovY: 45,
      aperture: 0,
      focusDistance: Math.hypot(half * 0.9, half * 1.6),
    },
    settings: { width: 128, height: 128, maxBounces: 6, spp: 16 },
    materials: {
      ground: { type: 'diffuse', albedo: [0.6, 0.6, 0.6], emission: [0, 0, 0] },
      red: { type: 'diffuse', albedo: [0.7, 0.2, 0.15], emission: [0, 0, 0] },
      white: { type: 'diffuse', albedo: [0.75, 0.75, 0.75], emission: [0, 0, 0] },
      metal: { type: 'conductor', color: [0.9, 0.8, 0.6], roughness: 0.3, emission: [0, 0, 0] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [20, 20, 20] },
    },
    shapes,
    environment: [0.02, 0.02, 0.03],
  };
}
