/**
 * The four scenes of issue 8, as files: a sphere light over a 100 × 100 floor
 * (the floor's size set the bias: −3.4 % at this size), the
 * same over ground spheres of radius 1e3 and 1e5, and a thin quad light
 * tilted 0.001 rad off a floor, facing down, lighting a back wall.
 */
import type { SceneJson } from './builder.ts';

function sphereOver(ground: 'quad' | number): SceneJson {
  const receiver =
    ground === 'quad'
      ? { type: 'quad' as const, corner: [-50, 0, -50], u: [0, 0, 100], v: [100, 0, 0] }
      : { type: 'sphere' as const, center: [0, -ground, 0], radius: ground };
  return {
    format: 'pathwise-scene/1',
    name: `issue 8: sphere light (r 0.25, L 10, 5 above) over ${ground === 'quad' ? 'a floor' : `a ground sphere of radius ${ground}`}`,
    // Between the light and the floor, looking straight down: the camera is not an occluder.
    camera: { position: [0, 2, 0], target: [0, 0, 0], up: [0, 0, 1], fovY: 5 },
    settings: { width: 32, height: 24, maxBounces: 1, spp: 64 },
    materials: {
      floor: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [10, 10, 10] },
    },
    shapes: [
      { ...receiver, material: 'floor' } as SceneJson['shapes'][number],
      { type: 'sphere', center: [0, 5, 0], radius: 0.25, material: 'lamp' },
    ],
  };
}

/** Tilt of the grazing light off horizontal, in radians. */
export const GRAZING_TILT = 0.001;

function grazingQuad(): SceneJson {
  const s = Math.sin(GRAZING_TILT);
  const c = Math.cos(GRAZING_TILT);
  return {
    format: 'pathwise-scene/1',
    name: 'issue 8: 2 × 1 quad light 0.3 above a floor, tilted 0.001 rad, facing down, lighting a back wall',
    camera: { position: [0, 0.6, -3], target: [0, 0.25, 2], up: [0, 1, 0], fovY: 30 },
    settings: { width: 32, height: 24, maxBounces: 4, spp: 64 },
    materials: {
      floor: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
      wall: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [10, 10, 10] },
    },
    shapes: [
      { type: 'quad', corner: [-5, 0, -5], u: [0, 0, 7], v: [10, 0, 0], material: 'floor' },
      { type: 'quad', corner: [-5, 0, 2], u: [10, 0, 0], v: [0, 5, 0], material: 'wall' },
      // cross(u, v) = 2·(0, −cos, sin): facing down, tilted towards the wall.
      { type: 'quad', corner: [-1, 0.3, 0.5], u: [2, 0, 0], v: [0, s, c], material: 'lamp' },
    ],
  };
}

export const ISSUE_SCENES: Record<string, SceneJson> = {
  'issue-sphere-floor': sphereOver('quad'),
  'issue-ground-sphere-1e3': sphereOver(1e3),
  'issue-ground-sphere-1e5': sphereOver(1e5),
  'issue-grazing-quad': grazingQuad(),
};
