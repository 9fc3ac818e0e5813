/**
 * Triangles in the tracer: the BVH and the plain loop find the same hits; a scene whose
 * quads are replaced by the same surfaces as triangle meshes renders the same paths;
 * shading normals change the BSDF's frame exactly as the spec says (an analytic case).
 */
import { describe, expect, it } from 'vitest';
import {
  compileScene,
  validateScene,
  type EnvironmentMapDesc,
  type QuadDesc,
  type Scene,
  type ShapeDesc,
} from '../../../src/core/index.ts';
import { Hit, Ray } from '../../../src/core/geometry/ray.ts';
import { intersectScene, occluded } from '../../../src/core/accel/trace.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import { imageMean, loadScene, loadSceneWithFiles, renderSampled } from '../../helpers/render.ts';
import { Film, PathTracer, RenderStats } from '../../../src/core/index.ts';
import { packScene, unpackScene } from '../../../src/core/scene/compile/pack.ts';
import { icosphere } from '../../helpers/mesh-gen.ts';

/** The quad as an inline mesh of two triangles with the same front side. */
export function quadAsMesh(q: QuadDesc): ShapeDesc {
  const c = q.corner;
  const p = (s: number, t: number) => [0, 1, 2].map((k) => c[k] + s * q.u[k] + t * q.v[k]);
  return validateScene({
    format: 'pathwise-scene/1',
    camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
    materials: { [q.material]: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
    shapes: [
      {
        type: 'mesh',
        material: q.material,
        positions: [...p(0, 0), ...p(1, 0), ...p(1, 1), ...p(0, 1)],
        indices: [0, 1, 2, 0, 2, 3],
      },
    ],
  }).shapes[0];
}

describe('triangles in the BVH', () => {
  it('give the same nearest hits and occlusion as the plain loop', () => {
    const sphere = icosphere(2, 0.8, [0.2, 0.1, 0.3]);
    const scene = validateScene({
      format: 'pathwise-scene/1',
      camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
      materials: { m: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
      shapes: [
        {
          type: 'mesh',
          material: 'm',
          positions: Array.from(sphere.positions),
          indices: Array.from(sphere.indices),
        },
        { type: 'sphere', center: [1, 1, 1], radius: 0.5, material: 'm' },
        { type: 'quad', corner: [-2, -1, -2], u: [4, 0, 0], v: [0, 0, 4], material: 'm' },
      ],
    });
    const withBvh = compileScene(scene, { bvh: true });
    const plain = compileScene(scene, { bvh: false });
    expect(withBvh.bvh).not.toBeNull();
    expect(plain.bvh).toBeNull();
    const ray = new Ray();
    const a = new Hit();
    const b = new Hit();
    let hits = 0;
    for (let i = 0; i < 3000; i++) {
      const key = sampleKey(6, i, 0);
      ray.ox = 4 * hashToUnit(key, 0) - 2;
      ray.oy = 4 * hashToUnit(key, 1) - 2;
      ray.oz = 4 * hashToUnit(key, 2) - 2;
      const z = 1 - 2 * hashToUnit(key, 3);
      const r = Math.sqrt(1 - z * z);
      const phi = 2 * Math.PI * hashToUnit(key, 4);
      ray.dx = r * Math.cos(phi);
      ray.dy = r * Math.sin(phi);
      ray.dz = z;
      ray.tMax = i % 3 === 0 ? 1 : Infinity;
      const ha = intersectScene(withBvh, ray, a);
      const hb = intersectScene(plain, ray, b);
      expect(ha).toBe(hb);
      if (ha) {
        hits++;
        expect([a.kind, a.index, a.t]).toEqual([b.kind, b.index, b.t]);
        if (a.kind === 2) expect([a.b0, a.b1, a.b2]).toEqual([b.b0, b.b1, b.b2]);
      }
      expect(occluded(withBvh, ray)).toBe(occluded(plain, ray));
    }
    expect(hits).toBeGreaterThan(500);
  });
});

describe('meshes render like the shapes they replace', () => {
  it('renders the Cornell box with its walls and boxes as triangles like the quads', () => {
    const base = loadScene('cornell');
    const lamp = base.shapes.findIndex(
      (s) => s.type === 'quad' && base.materials[s.material].emission.some((e) => e > 0),
    );
    const meshed: Scene = {
      ...base,
      shapes: base.shapes.map((s, i) => (i === lamp || s.type !== 'quad' ? s : quadAsMesh(s))),
    };
    expect(meshed.shapes.filter((s) => s.type === 'mesh').length).toBeGreaterThan(10);
    for (const bvh of [false, true]) {
      const a = renderSampled(base, { width: 32, height: 32, spp: 4, bvh });
      const b = renderSampled(meshed, { width: 32, height: 32, spp: 4, bvh });
      // Same random numbers, the same surfaces: the same paths, up to rounding that
      // rarely flips a decision (as in the scale test of hard-cases.test.ts).
      let differing = 0;
      for (let i = 0; i < a.mean.length; i++) {
        if (Math.abs(a.mean[i] - b.mean[i]) > 1e-9 * (Math.abs(a.mean[i]) + 1e-9)) differing++;
      }
      expect(differing, `bvh ${bvh}`).toBeLessThanOrEqual(a.mean.length / 100);
      const ma = imageMean(a).mean;
      const mb = imageMean(b).mean;
      for (let c = 0; c < 3; c++) expect(Math.abs(mb[c] / ma[c] - 1)).toBeLessThan(2e-3);
      expect(b.stats.rejected).toBe(0);
    }
  });
});

/** An environment map: the upper half white, the lower half black (two rows). */
function horizonMap(): EnvironmentMapDesc {
  return {
    type: 'map',
    file: 'horizon.pfm',
    scale: [1, 1, 1],
    rotationY: 0,
    image: { width: 1, height: 2, rgb: Float32Array.from([1, 1, 1, 0, 0, 0]) },
  };
}

describe('shading normals', () => {
  it('tilt the diffuse lobe: a plane under a white upper hemisphere reads ρ(1 + cos α)/2', () => {
    // A horizontal square facing up whose vertex normals lean by α toward +x. The
    // cosine lobe about the shading normal sees the white sky with probability
    // (1 + cos α)/2 (the view factor of a tilted plane to the sky).
    for (const alpha of [0, Math.PI / 4, Math.PI / 3]) {
      const n = [Math.sin(alpha), Math.cos(alpha), 0];
      const scene = validateScene({
        format: 'pathwise-scene/1',
        camera: { position: [0, 3, -0.5], target: [0, 0, 0], up: [0, 0, 1], fovY: 20 },
        settings: { width: 8, height: 8, maxBounces: 1, spp: 1 },
        materials: { m: { type: 'diffuse', albedo: [0.6, 0.6, 0.6] } },
        shapes: [
          {
            type: 'mesh',
            material: 'm',
            positions: [-2, 0, -2, -2, 0, 2, 2, 0, 2, 2, 0, -2],
            indices: [0, 1, 2, 0, 2, 3],
            normals: [...n, ...n, ...n, ...n],
          },
        ],
      });
      scene.environmentMap = horizonMap();
      const expected = (0.6 * (1 + Math.cos(alpha))) / 2;
      for (const estimator of ['bsdf', 'nee-mis'] as const) {
        const img = renderSampled(scene, { spp: 512, estimator });
        const { mean, stderr } = imageMean(img);
        expect(Math.abs(mean[0] - expected), `α ${alpha} ${estimator}`).toBeLessThan(
          4 * stderr[0] + 1e-12,
        );
      }
    }
  });

  it("flip to the back when wo is below the shading hemisphere, as Mitsuba 3's two-sided BSDFs do", () => {
    // The same square, normals leaning by α = 60° toward +x, under a white map in every
    // direction. Seen from the -x side at 20° elevation, wo is in front of the geometric
    // surface but behind the shading normal: the BSDF is then looked up on the back, in
    // the frame of the negated shading normal (Mitsuba 3's 'twosided'), where every
    // direction of the cosine lobe sees white: the plane reads ρ. A frame from the
    // negated geometric normal instead (the bug this guards) has wo below it: 0.
    const alpha = Math.PI / 3;
    const n = [Math.sin(alpha), Math.cos(alpha), 0];
    for (const elevation of [20, -20, 70]) {
      const e = (elevation * Math.PI) / 180;
      const scene = validateScene({
        format: 'pathwise-scene/1',
        camera: {
          position: [-3 * Math.cos(e), 3 * Math.sin(e), 0],
          target: [0, 0, 0],
          up: [0, 1, 0],
          fovY: 10,
        },
        settings: { width: 8, height: 8, maxBounces: 1, spp: 1 },
        materials: { m: { type: 'diffuse', albedo: [0.6, 0.6, 0.6] } },
        shapes: [
          {
            type: 'mesh',
            material: 'm',
            positions: [-2, 0, -2, -2, 0, 2, 2, 0, 2, 2, 0, -2],
            indices: [0, 1, 2, 0, 2, 3],
            normals: [...n, ...n, ...n, ...n],
          },
        ],
      });
      scene.environmentMap = {
        type: 'map',
        file: 'white.pfm',
        scale: [1, 1, 1],
        rotationY: 0,
        image: { width: 1, height: 1, rgb: Float32Array.from([1, 1, 1]) },
      };
      for (const estimator of ['bsdf', 'nee-mis'] as const) {
        const img = renderSampled(scene, { spp: 64, estimator });
        const { mean, stderr } = imageMean(img);
        expect(Math.abs(mean[0] - 0.6), `elevation ${elevation} ${estimator}`).toBeLessThan(
          4 * stderr[0] + 1e-9,
        );
      }
    }
  });
});

describe('meshes and maps in the packed scene', () => {
  it.each(['metal-sky', 'emissive-room'])(
    '%s renders bit-identically after a round trip through packScene, shared or copied',
    async (name) => {
      const scene = await loadSceneWithFiles(name);
      const compiled = compileScene(scene);
      const draw = (c: ReturnType<typeof compileScene>) => {
        const tracer = new PathTracer(c, {
          width: 16,
          height: 16,
          maxBounces: 4,
          seed: 3,
          camera: scene.camera,
        });
        const film = new Film(16, 16);
        tracer.renderRows(film, 0, 16, 0, 2, new RenderStats());
        return Array.from(film.sums);
      };
      const reference = draw(compiled);
      expect(reference.some((v) => v > 0)).toBe(true);
      for (const shared of [true, false]) {
        const unpacked = unpackScene(structuredClone(packScene(compiled, shared)));
        expect(unpacked.triCount).toBe(compiled.triCount);
        expect(draw(unpacked)).toEqual(reference);
      }
    },
  );
});
