/**
 * Furnace tests and estimator agreement for meshes and environment maps:
 * - a constant environment map renders what the constant environment does;
 * - a diffuse closed mesh sphere in a white map reads its albedo (exactly, by BSDF
 *   sampling alone; within noise with NEE + MIS);
 * - an emissive mesh lights a room the same through NEE + MIS as by BSDF sampling
 *   alone, and the same as the emissive quads it is made of;
 * - an environment map lights meshes the same through NEE + MIS as by BSDF sampling.
 * Tolerances are 4 standard errors of the difference of two independent renders, each
 * from its own per-pixel sample variance (fixed seeds; about 6e-5 two-sided per check).
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import {
  decodeHdr,
  validateScene,
  type EnvironmentMapDesc,
  type Scene,
} from '../../src/core/index.ts';
import { ROOT, imageMean, loadScene, renderSampled, type SampledImage } from '../helpers/render.ts';
import { icosphere } from '../helpers/mesh-gen.ts';

function constantMap(value: number, width = 8, height = 4): EnvironmentMapDesc {
  return {
    type: 'map',
    file: 'constant.pfm',
    scale: [1, 1, 1],
    rotationY: 0,
    image: { width, height, rgb: new Float32Array(width * height * 3).fill(value) },
  };
}

function skyMap(rotationY = 0): EnvironmentMapDesc {
  const image = decodeHdr(readFileSync(`${ROOT}scenes/sky.hdr`), {
    maxWidth: 16384,
    maxHeight: 8192,
  });
  return { type: 'map', file: 'sky.hdr', scale: [1, 1, 1], rotationY, image };
}

function meshSphere(levels: number, radius: number, center: number[]) {
  const s = icosphere(levels, radius, center);
  return { positions: Array.from(s.positions), indices: Array.from(s.indices) };
}

/** Image means of two renders agree within 4 standard errors of their difference. */
function expectSameMean(a: SampledImage, b: SampledImage, what: string): void {
  const ma = imageMean(a);
  const mb = imageMean(b);
  for (let c = 0; c < 3; c++) {
    const sigma = Math.hypot(ma.stderr[c], mb.stderr[c]);
    expect(sigma, `${what}: channel ${c} has noise`).toBeGreaterThan(0);
    expect(Math.abs(ma.mean[c] - mb.mean[c]), `${what}: channel ${c}`).toBeLessThan(4 * sigma);
  }
  expect(a.stats.rejected + b.stats.rejected).toBe(0);
}

describe('environment map furnaces', () => {
  it('a constant map renders like the constant environment', () => {
    const base = loadScene('furnace-diffuse');
    const mapped: Scene = { ...base, environment: [0, 0, 0], environmentMap: constantMap(1) };
    const opts = { width: 24, height: 24, spp: 64 };
    const a = renderSampled(base, { ...opts, seed: 1 });
    const b = renderSampled(mapped, { ...opts, seed: 2 });
    expectSameMean(a, b, 'constant map vs constant environment');
    // Paths that escape at once see exactly 1 either way.
    expect(b.mean[0]).toBe(a.mean[0]);
  });

  it('a diffuse closed mesh sphere in a white map reads its albedo', () => {
    const scene = validateScene({
      format: 'pathwise-scene/1',
      camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
      settings: { width: 24, height: 24, maxBounces: 16, spp: 16 },
      materials: { m: { type: 'diffuse', albedo: [0.8, 0.8, 0.8] } },
      shapes: [{ type: 'mesh', material: 'm', ...meshSphere(3, 1, [0, 0, 0]) }],
    });
    scene.environmentMap = constantMap(1);
    // BSDF sampling: every path leaves the convex mesh at once and sees exactly 1, so
    // a pixel on the sphere reads 0.8 in every sample: no leak, no self-hit.
    const exact = renderSampled(scene, { spp: 16, estimator: 'bsdf' });
    let sphere = 0;
    for (let i = 0; i < exact.mean.length; i++) {
      const v = exact.mean[i];
      const clean = Math.abs(v - 0.8) < 1e-12 || Math.abs(v - 1) < 1e-12;
      if (!clean) expect(exact.varianceOfMean[i], `pixel value ${v}`).toBeGreaterThan(0);
      if (Math.abs(v - 0.8) < 1e-12) sphere++;
    }
    expect(sphere).toBeGreaterThan(exact.mean.length / 6);
    // NEE + MIS on the same pixels: 0.8 within the noise.
    const nee = renderSampled(scene, { spp: 64 });
    let sum = 0;
    let variance = 0;
    let n = 0;
    for (let i = 0; i < exact.mean.length; i++) {
      if (Math.abs(exact.mean[i] - 0.8) >= 1e-12) continue;
      sum += nee.mean[i];
      variance += nee.varianceOfMean[i];
      n++;
    }
    const sigma = Math.sqrt(variance) / n;
    expect(sigma).toBeGreaterThan(0);
    expect(Math.abs(sum / n - 0.8)).toBeLessThan(4 * sigma);
  });
});

function roomWithLamp(lamp: unknown[]): Scene {
  return validateScene({
    format: 'pathwise-scene/1',
    camera: { position: [0, 1, -3.5], target: [0, 1, 0], up: [0, 1, 0], fovY: 50 },
    settings: { width: 24, height: 24, maxBounces: 4, spp: 16 },
    materials: {
      wall: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
      red: { type: 'diffuse', albedo: [0.7, 0.2, 0.2] },
      metal: { type: 'conductor', color: [0.9, 0.8, 0.6], roughness: 0.4 },
      lamp: { type: 'diffuse', albedo: [0.5, 0.5, 0.5], emission: [6, 5, 4] },
    },
    shapes: [
      { type: 'quad', corner: [-2, 0, -2], u: [0, 0, 4], v: [4, 0, 0], material: 'wall' },
      { type: 'quad', corner: [-2, 2, -2], u: [4, 0, 0], v: [0, 0, 4], material: 'wall' },
      { type: 'quad', corner: [-2, 0, 2], u: [4, 0, 0], v: [0, 2, 0], material: 'wall' },
      { type: 'quad', corner: [-2, 0, -2], u: [0, 2, 0], v: [0, 0, 4], material: 'red' },
      { type: 'quad', corner: [2, 0, -2], u: [0, 0, 4], v: [0, 2, 0], material: 'wall' },
      { type: 'mesh', material: 'metal', ...meshSphere(2, 0.5, [0.6, 0.5, 0.5]) },
      ...lamp,
    ],
  });
}

describe('emissive meshes', () => {
  const lampQuad = { corner: [-0.5, 1.99, -0.2], u: [1, 0, 0], v: [0, 0, 0.6] };
  const quadLamp = { type: 'quad', ...lampQuad, material: 'lamp' };
  // The same rectangle as two triangles facing down, like the quad (normal u × v).
  const c = lampQuad.corner;
  const meshLamp = {
    type: 'mesh',
    material: 'lamp',
    positions: [
      c[0],
      c[1],
      c[2],
      c[0] + 1,
      c[1],
      c[2],
      c[0] + 1,
      c[1],
      c[2] + 0.6,
      c[0],
      c[1],
      c[2] + 0.6,
    ],
    indices: [0, 1, 2, 0, 2, 3],
  };

  it('light a room the same through NEE + MIS as by BSDF sampling alone', () => {
    const scene = roomWithLamp([
      { type: 'mesh', material: 'lamp', ...meshSphere(1, 0.25, [-0.6, 1.3, 0.3]) },
    ]);
    const a = renderSampled(scene, { spp: 64, seed: 3 });
    const b = renderSampled(scene, { spp: 256, seed: 4, estimator: 'bsdf' });
    expectSameMean(a, b, 'emissive mesh: NEE+MIS vs BSDF');
  });

  it('light a room the same as the emissive quad they are made of', () => {
    const a = renderSampled(roomWithLamp([quadLamp]), { spp: 64, seed: 5 });
    const b = renderSampled(roomWithLamp([meshLamp]), { spp: 64, seed: 6 });
    expectSameMean(a, b, 'quad lamp vs mesh lamp');
  });
});

describe('environment maps as lights', () => {
  it('light meshes the same through NEE + MIS as by BSDF sampling alone', () => {
    const scene = validateScene({
      format: 'pathwise-scene/1',
      camera: { position: [0, 1, -3], target: [0, 0.4, 0], up: [0, 1, 0], fovY: 45 },
      settings: { width: 24, height: 24, maxBounces: 3, spp: 16 },
      materials: {
        ground: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
        metal: { type: 'conductor', color: [0.95, 0.8, 0.5], roughness: 0.3 },
      },
      shapes: [
        {
          type: 'mesh',
          material: 'ground',
          positions: [-3, 0, -3, -3, 0, 3, 3, 0, 3, 3, 0, -3],
          indices: [0, 1, 2, 0, 2, 3],
        },
        { type: 'mesh', material: 'metal', ...meshSphere(2, 0.5, [0, 0.5, 0]) },
      ],
    });
    scene.environmentMap = skyMap(30);
    const a = renderSampled(scene, { spp: 64, seed: 8 });
    const b = renderSampled(scene, { spp: 1024, seed: 9, estimator: 'bsdf' });
    expectSameMean(a, b, 'sky: NEE+MIS vs BSDF');
  });
});
