/**
 * MIS needs the light's density twice: from `sampleLight` when a light sample is taken,
 * and from `lightPdf` / `environmentLightPdf` when a BSDF-sampled ray happens to land
 * on the same point. The two must agree for every kind of light; and the choice among
 * lights must be in proportion to power.
 */
import { describe, expect, it } from 'vitest';
import { compileScene, validateScene } from '../../../src/core/index.ts';
import { LIGHT_ENVIRONMENT, SHAPE_TRIANGLE } from '../../../src/core/geometry/ray.ts';
import { LightSample, sampleLight } from '../../../src/core/lights/lights.ts';
import { environmentLightPdf, lightPdf } from '../../../src/core/lights/light-pdf.ts';
import { MeshLightSample } from '../../../src/core/lights/mesh-light.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import { lampMeshes, stripedMap } from '../../helpers/light-scenes.ts';

function lightsScene() {
  const scene = validateScene({
    format: 'pathwise-scene/1',
    camera: { position: [0, 1, -4], target: [0, 1, 0], up: [0, 1, 0], fovY: 40 },
    materials: {
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [5, 4, 3] },
      dim: { type: 'diffuse', albedo: [0, 0, 0], emission: [0.5, 0.5, 0.5] },
      floor: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
    },
    shapes: [
      ...lampMeshes(),
      { type: 'sphere', center: [-1, 1.5, 0], radius: 0.2, material: 'lamp' },
      { type: 'quad', corner: [-2, 0, -2], u: [0, 0, 4], v: [4, 0, 0], material: 'floor' },
      { type: 'quad', corner: [1, 2.5, -1], u: [0.5, 0, 0], v: [0, 0, 0.5], material: 'dim' },
    ],
  });
  scene.environmentMap = stripedMap();
  return compileScene(scene);
}

describe('light densities', () => {
  it('agree between sampleLight and lightPdf / environmentLightPdf for every light', () => {
    const scene = lightsScene();
    const lights = scene.lights!;
    expect(lights.count).toBe(5);
    const ls = new LightSample();
    const checked = new Map<number, number>();
    for (let i = 0; i < 4000; i++) {
      const key = sampleKey(12, i, 0);
      const l = i % lights.count;
      ls.refX = 3 * hashToUnit(key, 0) - 1.5;
      ls.refY = 0.01 + hashToUnit(key, 1);
      ls.refZ = 3 * hashToUnit(key, 2) - 1.5;
      ls.u0 = hashToUnit(key, 3);
      ls.u1 = hashToUnit(key, 4);
      // Chosen by power (the light BVH's choice: light-bvh.test.ts).
      ls.pick = lights.prob[l];
      ls.triangle = -1;
      if (!sampleLight(lights, scene.spheres, scene.quads, l, ls)) continue;
      const kind = lights.kind[l];
      let pdf: number;
      if (kind === LIGHT_ENVIRONMENT) {
        pdf = environmentLightPdf(lights, null, ls.wx, ls.wy, ls.wz);
      } else if (kind === SHAPE_TRIANGLE) {
        // The emitter's cosine as the integrator computes it where a ray hits: the
        // triangle's normal against the direction back to the reference point.
        const n = new MeshLightSample();
        lights.meshLights[lights.shape[l]]!.sample(ls.u0, ls.u1, n);
        const cos = -(n.nx * ls.wx + n.ny * ls.wy + n.nz * ls.wz);
        pdf = lightPdf(
          lights,
          null,
          scene.spheres,
          scene.quads,
          l,
          -1,
          ls.refX,
          ls.refY,
          ls.refZ,
          0,
          0,
          0,
          ls.distance,
          cos,
        );
      } else {
        continue; // spheres and quads: tested with the integrator (hard-cases, furnaces)
      }
      expect(Math.abs(pdf / ls.pdf - 1), `light ${l} (kind ${kind})`).toBeLessThan(1e-9);
      checked.set(kind, (checked.get(kind) ?? 0) + 1);
    }
    expect(checked.get(SHAPE_TRIANGLE)).toBeGreaterThan(500);
    expect(checked.get(LIGHT_ENVIRONMENT)).toBeGreaterThan(500);
  });

  it('choose lights in proportion to power: luminance × area, and ∫L dω × r² for the map', () => {
    const scene = lightsScene();
    const lights = scene.lights!;
    const env = scene.envMap!;
    const lum = (r: number, g: number, b: number) => 0.2126 * r + 0.7152 * g + 0.0722 * b;
    const weights: number[] = [];
    for (let l = 0; l < lights.count; l++) {
      const kind = lights.kind[l];
      if (kind === SHAPE_TRIANGLE) {
        const e = lights.material[l] === 0 ? lum(5, 4, 3) : lum(0.5, 0.5, 0.5);
        weights.push(e * lights.meshLights[lights.shape[l]]!.area);
      } else if (kind === LIGHT_ENVIRONMENT) {
        // Bounding box of the shapes: x ∈ [−2, 5], y ∈ [0, 2.5], z ∈ [−2, 2].
        const r = Math.hypot(7, 2.5, 4) / 2;
        weights.push(env.integral * r * r);
      } else if (kind === 0) weights.push(lum(5, 4, 3) * 4 * Math.PI * 0.04);
      else weights.push(lum(0.5, 0.5, 0.5) * 0.25);
    }
    const total = weights.reduce((a, b) => a + b);
    for (let l = 0; l < lights.count; l++) {
      expect(lights.prob[l]).toBeCloseTo(weights[l] / total, 12);
    }
  });
});
