/**
 * Numerically hard cases: grazing and parallel rays, origins on surfaces,
 * cameras inside spheres and inside glass, huge spheres, scale invariance.
 */
import { describe, expect, it } from 'vitest';
import { validateScene, type Scene, type Vec3 } from '../../../src/core/index.ts';
import { intersectQuad, intersectSphere } from '../../../src/core/geometry/intersect.ts';
import { compileQuads, compileSpheres } from '../../../src/core/geometry/shapes.ts';
import { imageMean, loadScene, renderSampled } from '../../helpers/render.ts';

const quad = compileQuads([
  { type: 'quad', corner: [0, 0, 0], u: [1, 0, 0], v: [0, 0, 1], material: 'm' },
]);
const unitSphere = compileSpheres([
  { type: 'sphere', center: [0, 0, 0], radius: 1, material: 'm' },
]);

function scene(partial: Partial<Record<string, unknown>>): Scene {
  return validateScene({
    format: 'pathwise-scene/1',
    camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
    settings: { width: 24, height: 24, maxBounces: 8, spp: 8 },
    ...partial,
  });
}

function scaled(s: Scene, k: number): Scene {
  const v = (a: Vec3): Vec3 => [a[0] * k, a[1] * k, a[2] * k];
  return {
    ...s,
    camera: {
      ...s.camera,
      position: v(s.camera.position),
      target: v(s.camera.target),
      focusDistance: s.camera.focusDistance * k,
    },
    shapes: s.shapes.map((sh) =>
      sh.type === 'sphere'
        ? { ...sh, center: v(sh.center), radius: sh.radius * k }
        : sh.type === 'quad'
          ? { ...sh, corner: v(sh.corner), u: v(sh.u), v: v(sh.v) }
          : sh,
    ),
  };
}

describe('ray–shape intersection edge cases', () => {
  it('misses a quad the ray runs parallel to, in or off its plane, without NaN', () => {
    expect(intersectQuad(quad, 0, 0.5, 0, -1, 0, 0, 1, Infinity)).toBe(Infinity);
    expect(intersectQuad(quad, 0, 0.5, 1, -1, 0, 0, 1, Infinity)).toBe(Infinity);
    expect(intersectQuad(quad, 0, -1, 0, 0.5, 1, 0, 0, Infinity)).toBe(Infinity);
  });

  it('handles grazing rays at a quad with finite t or a miss', () => {
    for (const e of [1e-8, 1e-12, 1e-15, 1e-300]) {
      const len = Math.hypot(1, e);
      const t = intersectQuad(quad, 0, -0.5, e * 0.5, 0.5, 1 / len, -e / len, 0, Infinity);
      expect(Number.isNaN(t)).toBe(false);
      if (t !== Infinity) expect(t).toBeGreaterThan(0);
    }
  });

  it('handles tangent and grazing rays at a sphere without NaN', () => {
    expect(Number.isNaN(intersectSphere(unitSphere, 0, -5, 1, 0, 1, 0, 0, Infinity))).toBe(false);
    for (const y of [1 - 1e-9, 1 - 1e-15, 1, 1 + 1e-15]) {
      const t = intersectSphere(unitSphere, 0, -5, y, 0, 1, 0, 0, Infinity);
      expect(Number.isNaN(t)).toBe(false);
    }
  });

  it('finds the far side from an origin on (or inside) the sphere', () => {
    expect(intersectSphere(unitSphere, 0, 0, 0, 0, 0, 0, 1, Infinity)).toBeCloseTo(1, 12);
    // Origin on the surface heading inward: the only hit ahead is the far side.
    expect(intersectSphere(unitSphere, 0, 0, 0, -1, 0, 0, 1, Infinity)).toBeCloseTo(2, 12);
    // Heading outward from the surface: nothing ahead (t = 0 is not a hit).
    expect(intersectSphere(unitSphere, 0, 0, 0, 1, 0, 0, 1, Infinity)).toBe(Infinity);
  });

  it('misses a quad from an origin on it', () => {
    expect(intersectQuad(quad, 0, 0.5, 0, 0.5, 0, 1, 0, Infinity)).toBe(Infinity);
  });

  it('hits spheres of radius 2^1000 and 2^-1000 at the right distance (r² over- or underflows)', () => {
    for (const e of [1000, 600, 450, -450, -600, -1000]) {
      const s = 2 ** e;
      const sphere = new Float64Array([s, -s, 0, s]);
      // From 4 radii away along x, straight at the centre, and past its edge.
      expect(intersectSphere(sphere, 0, -3 * s, -s, 0, 1, 0, 0, Infinity) / s, `2^${e}`).toBe(3);
      expect(intersectSphere(sphere, 0, -3 * s, 0.99 * -s + s, 0, 1, 0, 0, Infinity)).toBe(
        Infinity,
      );
      // From inside: the far side.
      expect(intersectSphere(sphere, 0, s, -s, 0, 0, 1, 0, Infinity) / s).toBe(1);
    }
  });

  it('keeps precision for a sphere of radius 1e5', () => {
    const ground = compileSpheres([
      { type: 'sphere', center: [0, -1e5, 0], radius: 1e5, material: 'm' },
    ]);
    const t = intersectSphere(ground, 0, 0.3, 1, 0.2, 0, -1, 0, Infinity);
    // The surface under (0.3, 0.2) lies 0.13 / (2·1e5) below y = 0 (its sagitta).
    const surfaceY = -0.13 / (1e5 + Math.sqrt(1e10 - 0.13));
    expect(Math.abs(t - (1 - surfaceY))).toBeLessThan(1e-9);
  });
});

describe('hard scenes', () => {
  it('renders every pixel finite when the camera looks along a quad (edge-on)', () => {
    const s = scene({
      camera: { position: [0.5, 0, -3], target: [0.5, 0, 0.5], up: [0, 1, 0], fovY: 30 },
      materials: { m: { type: 'diffuse', albedo: [0.5, 0.5, 0.5], emission: [1, 1, 1] } },
      shapes: [{ type: 'quad', corner: [0, 0, 0], u: [1, 0, 0], v: [0, 0, 1], material: 'm' }],
      environment: [1, 1, 1],
    });
    const img = renderSampled(s, { spp: 8 });
    expect(img.stats.rejected).toBe(0);
    expect(img.mean.every(Number.isFinite)).toBe(true);
  });

  it('shows no acne on a sphere of radius 1e5 used as the ground', () => {
    // Diffuse ground (albedo 0.5) under a uniform sky of 1: a ray leaving a
    // convex surface never meets it again, so each ground sample is exactly
    // 0.5 and the sky 1. Any self-intersection would darken pixels.
    for (const k of [1e-4, 1, 1e4]) {
      const s = scaled(
        scene({
          camera: { position: [0, 2, -6], target: [0, 0, 4], up: [0, 1, 0], fovY: 60 },
          materials: { g: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
          shapes: [{ type: 'sphere', center: [0, -1e5, 0], radius: 1e5, material: 'g' }],
          environment: [1, 1, 1],
        }),
        k,
      );
      const img = renderSampled(s, { spp: 4 });
      let ground = 0;
      for (let i = 0; i < img.mean.length; i++) {
        const v = img.mean[i];
        const exact = Math.abs(v - 0.5) < 1e-12 || Math.abs(v - 1) < 1e-12;
        // Pixels straddling the horizon may mix the two.
        if (!exact) expect(img.varianceOfMean[i]).toBeGreaterThan(0);
        if (Math.abs(v - 0.5) < 1e-12) ground++;
      }
      expect(ground).toBeGreaterThan(img.mean.length / 3);
    }
  });

  it('lets no light leak into a closed box of quads', () => {
    const box = loadScene('furnace-enclosure');
    const s = {
      ...box,
      materials: {
        m: {
          type: 'diffuse' as const,
          albedo: [0.8, 0.8, 0.8] as Vec3,
          emission: [0, 0, 0] as Vec3,
        },
        lamp: {
          type: 'diffuse' as const,
          albedo: [0, 0, 0] as Vec3,
          emission: [50, 50, 50] as Vec3,
        },
      },
      shapes: [
        ...box.shapes,
        // A lamp just outside the top wall, facing it, and a bright sky.
        {
          type: 'quad' as const,
          corner: [-1, 1.001, -1] as Vec3,
          u: [0, 0, 2] as Vec3,
          v: [2, 0, 0] as Vec3,
          material: 'lamp',
        },
      ],
      environment: [10, 10, 10] as Vec3,
    };
    const img = renderSampled(s, { spp: 8, width: 24, height: 24 });
    expect(img.mean.every((v) => v === 0)).toBe(true);
  });

  it('reads n² = 2.25 from a camera at the centre of a glass sphere in a unit furnace', () => {
    // Radiance is not invariant across the boundary: leaving glass (n = 1.5)
    // into air multiplies by (n1/n2)² = 2.25 — every path ends that way.
    const s = scene({
      camera: { position: [0, 0, 0], target: [0, 0, 1], up: [0, 1, 0], fovY: 60 },
      materials: { glass: { type: 'dielectric', ior: 1.5 } },
      shapes: [{ type: 'sphere', center: [0, 0, 0], radius: 1, material: 'glass' }],
      environment: [1, 1, 1],
      settings: { width: 16, height: 16, maxBounces: 64, spp: 8 },
    });
    const { mean } = imageMean(renderSampled(s, { spp: 8 }));
    for (let c = 0; c < 3; c++) expect(Math.abs(mean[c] - 2.25)).toBeLessThan(1e-9);
  });

  it('sees nothing from inside an emissive sphere (emission leaves the outside only)', () => {
    const s = scene({
      camera: { position: [0.2, 0.1, 0], target: [0, 0, 1], up: [0, 1, 0], fovY: 60 },
      materials: { lamp: { type: 'diffuse', albedo: [0.5, 0.5, 0.5], emission: [5, 5, 5] } },
      shapes: [{ type: 'sphere', center: [0, 0, 0], radius: 1, material: 'lamp' }],
      environment: [1, 1, 1],
    });
    const img = renderSampled(s, { spp: 4 });
    expect(img.mean.every((v) => v === 0)).toBe(true);
  });

  it('reads exactly 1 for a white mirror sphere (roughness 0, F0 = 1) in a unit furnace', () => {
    const s = scene({
      materials: { chrome: { type: 'conductor', color: [1, 1, 1], roughness: 0 } },
      shapes: [{ type: 'sphere', center: [0, 0, 0], radius: 1, material: 'chrome' }],
      environment: [1, 1, 1],
    });
    const img = renderSampled(s, { spp: 4 });
    expect(img.mean.every((v) => Math.abs(v - 1) < 1e-12)).toBe(true);
  });

  it.each([0.3, 1])(
    'agrees between NEE+MIS and BSDF-only for a rough conductor (roughness %s)',
    (roughness) => {
      const s = scene({
        camera: { position: [0, 1.5, -4], target: [0, 0.5, 0], up: [0, 1, 0], fovY: 40 },
        materials: {
          metal: { type: 'conductor', color: [0.9, 0.7, 0.4], roughness },
          floor: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
          lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [4, 4, 4] },
        },
        shapes: [
          { type: 'sphere', center: [0, 0.7, 0], radius: 0.7, material: 'metal' },
          { type: 'quad', corner: [-4, 0, -4], u: [0, 0, 8], v: [8, 0, 0], material: 'floor' },
          { type: 'sphere', center: [1.5, 3, -1], radius: 0.8, material: 'lamp' },
        ],
        settings: { width: 20, height: 20, maxBounces: 4, spp: 8 },
      });
      const a = imageMean(renderSampled(s, { spp: 64 }));
      const b = imageMean(renderSampled(s, { spp: 256, estimator: 'bsdf', seed: 5 }));
      for (let c = 0; c < 3; c++) {
        expect(Math.abs(a.mean[c] - b.mean[c])).toBeLessThan(
          4 * Math.hypot(a.stderr[c], b.stderr[c]),
        );
      }
    },
  );

  it('renders the same image for the scene scaled by 1e-4 and by 1e4', () => {
    for (const name of ['cornell', 'mirror']) {
      const base = loadScene(name);
      const a = renderSampled(base, { width: 32, height: 32, spp: 4 });
      for (const k of [1e-4, 1e4]) {
        const b = renderSampled(scaled(base, k), { width: 32, height: 32, spp: 4 });
        // Same random numbers, relative offsets: paths coincide up to
        // rounding; rarely a path decision flips, so allow 0.1% of values.
        let differing = 0;
        for (let i = 0; i < a.mean.length; i++) {
          if (Math.abs(a.mean[i] - b.mean[i]) > 1e-9 * (Math.abs(a.mean[i]) + 1e-9)) differing++;
        }
        expect(differing).toBeLessThanOrEqual(a.mean.length / 1000);
        const ma = imageMean(a).mean;
        const mb = imageMean(b).mean;
        for (let c = 0; c < 3; c++) expect(Math.abs(mb[c] / ma[c] - 1)).toBeLessThan(1e-4);
      }
    }
  });
});
