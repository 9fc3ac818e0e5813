/**
 * The light BVH (src/core/lights/light-bvh.ts): its choice of light is distributed as
 * its `pmf` says (Pearson's χ² at several reference points, with the false-alarm rate
 * below), the densities MIS reads back (`lightPdf`, `environmentLightPdf` given the
 * BVH) equal those of the samples drawn through it for every kind of emitter, and the
 * shares of the emitters sum to the probability of choosing one at all. Splitting
 * (`chooseSplit`) chooses each emitter with the probability its `pmf` gives, and MIS
 * reads the same densities back.
 *
 * False alarms: each χ² test rejects at p < 1e-4 (Bonferroni over the 8 points keeps
 * the file's rate below 1e-3); the numbers are fixed hashes, so it cannot flake.
 */
import { describe, expect, it } from 'vitest';
import { compileScene, validateScene } from '../../../src/core/index.ts';
import {
  LIGHT_ENVIRONMENT,
  LIGHT_POINT,
  SHAPE_QUAD,
  SHAPE_SPHERE,
  SHAPE_TRIANGLE,
} from '../../../src/core/geometry/ray.ts';
import { QUAD_STRIDE, Q_NORMAL } from '../../../src/core/geometry/shapes.ts';
import { MATERIAL_STRIDE, M_EMISSION } from '../../../src/core/bsdf/materials.ts';
import { LightSample, sampleLight } from '../../../src/core/lights/lights.ts';
import { LIGHT_SPLIT } from '../../../src/core/lights/light-bvh.ts';
import { environmentLightPdf, lightPdf } from '../../../src/core/lights/light-pdf.ts';
import { hashToUnit, sampleKey } from '../../../src/core/rng/pcg.ts';
import { chi2Test } from '../../helpers/chi2.ts';
import { lampMeshes, stripedMap } from '../../helpers/light-scenes.ts';

/** A room of many emitters of every kind: meshes, spheres, quads, point and spot lights, a map, a sun. */
function manyLightScene(withInfinite: boolean) {
  const shapes: unknown[] = [
    ...lampMeshes(),
    { type: 'quad', corner: [-2, 0, -2], u: [0, 0, 4], v: [4, 0, 0], material: 'floor' },
  ];
  for (let i = 0; i < 60; i++) {
    const key = sampleKey(91, i, 0);
    const x = 4 * hashToUnit(key, 0) - 2;
    const y = 0.3 + 2.5 * hashToUnit(key, 1);
    const z = 4 * hashToUnit(key, 2) - 2;
    const s = 0.02 + 0.1 * hashToUnit(key, 3);
    if (i % 2 === 0) {
      shapes.push({
        type: 'sphere',
        center: [x, y, z],
        radius: s,
        material: i % 4 ? 'lamp' : 'dim',
      });
    } else {
      // Quads facing every way.
      const a = 2 * Math.PI * hashToUnit(key, 4);
      shapes.push({
        type: 'quad',
        corner: [x, y, z],
        u: [s * Math.cos(a), 0, s * Math.sin(a)],
        v: [0, i % 3 === 0 ? s : -s, 0],
        material: 'lamp',
      });
    }
  }
  const scene = validateScene({
    format: 'pathwise-scene/1',
    camera: { position: [0, 1, -4], target: [0, 1, 0], up: [0, 1, 0], fovY: 40 },
    materials: {
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [5, 4, 3] },
      dim: { type: 'diffuse', albedo: [0, 0, 0], emission: [0.5, 0.5, 0.5] },
      floor: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
    },
    shapes,
    lights: [
      { type: 'point', position: [0.2, 2.2, 0.1], intensity: 3 },
      { type: 'point', position: [-1.5, 0.5, 1.2], intensity: 0.5, color: [1, 0.2, 0.2] },
      {
        type: 'spot',
        position: [1, 2.5, -1],
        direction: [0, -1, 0.3],
        intensity: 20,
        outerConeAngle: 25,
      },
      ...(withInfinite ? [{ type: 'directional', direction: [-1, -2, -1], intensity: 0.3 }] : []),
    ],
  });
  if (withInfinite) scene.environmentMap = stripedMap();
  return compileScene(scene);
}

/**
 * A ceiling of 400 small lamps facing down, of powers spread over 100×: below a node far
 * from the point, whose lamps all face one way, the BVH chooses by power (light-bvh.ts,
 * FAR2), and above it by importance.
 */
function lampCeiling() {
  const shapes: unknown[] = [
    { type: 'quad', corner: [-2, 0, -2], u: [0, 0, 4], v: [4, 0, 0], material: 'floor' },
  ];
  const materials: Record<string, unknown> = {
    floor: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
  };
  for (let i = 0; i < 400; i++) {
    const key = sampleKey(93, i, 0);
    const x = -2 + 0.2 * (i % 20) + 0.15 * hashToUnit(key, 0);
    const z = -2 + 0.2 * Math.floor(i / 20) + 0.15 * hashToUnit(key, 1);
    const e = 100 ** hashToUnit(key, 2);
    materials[`lamp${i}`] = { type: 'diffuse', albedo: [0, 0, 0], emission: [e, e, e] };
    // u × v points down.
    shapes.push({
      type: 'quad',
      corner: [x, 3, z],
      u: [0.04, 0, 0],
      v: [0, 0, 0.04],
      material: `lamp${i}`,
    });
  }
  return compileScene(
    validateScene({
      format: 'pathwise-scene/1',
      camera: { position: [0, 1, -4], target: [0, 1, 0], up: [0, 1, 0], fovY: 40 },
      materials,
      shapes,
    }),
  );
}

/** The scenes the tests below run on, with their count of bounded emitters. */
const CASES: { what: string; make: () => ReturnType<typeof compileScene>; count: number }[] = [
  { what: 'bounded lights only', make: () => manyLightScene(false), count: 145 },
  { what: 'with a map and a sun', make: () => manyLightScene(true), count: 145 },
  { what: 'a ceiling of lamps facing down', make: lampCeiling, count: 400 },
];

/** Reference points with normals: on the floor, in the air, on a wall. */
const POINTS: [number, number, number, number, number, number][] = [
  [0, 0, 0, 0, 1, 0],
  [1.5, 0, -1.5, 0, 1, 0],
  [0.4, 1.6, 0.2, 1, 0, 0],
  [-1.9, 1, 0.5, 1, 0, 0],
  [0, 2.9, 0, 0, -1, 0],
  [0.5, 1.5, 0.2, 0, 0.6, 0.8],
  [3, 3, 3, -0.577, -0.577, -0.577],
  [-1, 0.3, -1.9, 0, 0, 1],
];

/** A point in the room with a normal tilted 37° from up, from the hash key. */
function randomPoint(key: number): [number, number, number, number, number, number] {
  const a = 2 * Math.PI * hashToUnit(key, 3);
  return [
    4 * hashToUnit(key, 0) - 2,
    0.01 + 2.8 * hashToUnit(key, 1),
    4 * hashToUnit(key, 2) - 2,
    Math.cos(a) * 0.6,
    0.8,
    Math.sin(a) * 0.6,
  ];
}

/**
 * What MIS reads back (`lightPdf`) for area-light sample `ls` of light l, drawn from the
 * point (x, y, z) with normal n: the emitter's cosine as the integrator computes it where
 * a ray hits (a sphere seen from outside: lightPdf does not read it).
 */
function misPdf(
  scene: ReturnType<typeof manyLightScene>,
  l: number,
  ls: LightSample,
  p: readonly number[],
  split = 1,
): number {
  const lights = scene.lights!;
  const kind = lights.kind[l];
  let cos = 1;
  if (kind === SHAPE_QUAD) {
    const o = lights.shape[l] * QUAD_STRIDE + Q_NORMAL;
    cos = -(scene.quads[o] * ls.wx + scene.quads[o + 1] * ls.wy + scene.quads[o + 2] * ls.wz);
  } else if (kind === SHAPE_TRIANGLE) {
    const ms = lights.meshSample;
    cos = -(ms.nx * ls.wx + ms.ny * ls.wy + ms.nz * ls.wz);
  }
  const [x, y, z, nx, ny, nz] = p as [number, number, number, number, number, number];
  const bvh = scene.lightBvh();
  const s = scene.spheres;
  return lightPdf(
    lights,
    bvh,
    s,
    scene.quads,
    l,
    ls.triangle,
    x,
    y,
    z,
    nx,
    ny,
    nz,
    ls.distance,
    cos,
    split,
  );
}

describe('light BVH', () => {
  for (const { what, make, count } of CASES) {
    it(`chooses every emitter with the probability pmf gives (χ², ${what})`, () => {
      const scene = make();
      const bvh = scene.lightBvh()!;
      const lights = scene.lights!;
      expect(bvh.count).toBe(count);
      const cells = bvh.count + bvh.infinite.length;
      const ls = new LightSample();
      const n = 200_000;
      for (const [i, [x, y, z, nx, ny, nz]] of POINTS.entries()) {
        bvh.setPoint(x, y, z, nx, ny, nz);
        const expected = new Float64Array(cells + 1);
        const picks = new Float64Array(bvh.count);
        let total = 0;
        for (let p = 0; p < bvh.count; p++) {
          const pick = bvh.pmf(p);
          picks[p] = pick;
          expected[p] = n * pick;
          total += pick;
        }
        bvh.infinite.forEach((_, k) => {
          expected[bvh.count + k] = n * bvh.infinitePick;
          total += bvh.infinitePick;
        });
        // The last cell: no light chosen.
        expected[cells] = n * Math.max(0, 1 - total);
        const observed = new Float64Array(cells + 1);
        let mismatched = 0;
        for (let s = 0; s < n; s++) {
          const u = hashToUnit(sampleKey(7, i, s), 0);
          if (!bvh.choose(u, ls)) {
            observed[cells]++;
            continue;
          }
          const inf = bvh.infinite.indexOf(ls.light);
          const p = inf >= 0 ? bvh.count + inf : bvh.primOf(ls.light, ls.triangle);
          // The probability the choice reports is the one pmf gives, to the bit.
          if (inf < 0 && ls.pick !== picks[p]) mismatched++;
          observed[p]++;
        }
        expect(mismatched).toBe(0);
        expect(total).toBeLessThanOrEqual(1 + 1e-12);
        const r = chi2Test(observed, expected);
        expect(r.impossible, `point ${i}`).toBeNull();
        expect(r.pValue, `point ${i}: χ² ${r.stat.toFixed(1)}, ${r.dof} dof`).toBeGreaterThan(1e-4);
        // Most emitters are seen from most points: the test is not vacuous.
        expect(r.dof).toBeGreaterThan(20);
      }
      expect(lights.bvh).toBe(bvh);
    });
  }

  it('gives MIS the density of each sample drawn through it, for every kind of emitter', () => {
    const scene = manyLightScene(true);
    const bvh = scene.lightBvh()!;
    const lights = scene.lights!;
    const ls = new LightSample();
    const checked = new Map<number, number>();
    for (let i = 0; i < 20_000; i++) {
      const key = sampleKey(13, i, 0);
      const point = randomPoint(key);
      const [x, y, z, nx, ny, nz] = point;
      bvh.setPoint(x, y, z, nx, ny, nz);
      if (!bvh.choose(hashToUnit(key, 4), ls)) continue;
      const l = ls.light;
      ls.refX = x;
      ls.refY = y;
      ls.refZ = z;
      ls.u0 = hashToUnit(key, 5);
      ls.u1 = hashToUnit(key, 6);
      if (!sampleLight(lights, scene.spheres, scene.quads, l, ls)) continue;
      const kind = lights.kind[l];
      let pdf: number;
      if (kind === LIGHT_ENVIRONMENT) {
        pdf = environmentLightPdf(lights, bvh, ls.wx, ls.wy, ls.wz);
      } else if (kind >= LIGHT_POINT) {
        // Delta lights: the pdf is the choice alone, and no ray finds them.
        expect(ls.pdf).toBe(ls.pick);
        checked.set(kind, (checked.get(kind) ?? 0) + 1);
        continue;
      } else {
        pdf = misPdf(scene, l, ls, point);
      }
      expect(Math.abs(pdf / ls.pdf - 1), `light ${l} (kind ${kind})`).toBeLessThan(1e-9);
      checked.set(kind, (checked.get(kind) ?? 0) + 1);
    }
    for (const kind of [SHAPE_SPHERE, SHAPE_QUAD, SHAPE_TRIANGLE, LIGHT_ENVIRONMENT, LIGHT_POINT]) {
      expect(checked.get(kind) ?? 0, `kind ${kind}`).toBeGreaterThan(100);
    }
  });

  for (const { what, make } of CASES) {
    it(`splits: each light is among the chosen with the probability pmf gives (${what})`, () => {
      // Each emitter is chosen at most once per call, so its count over n calls is
      // binomial(n, pmf): a two-sided z test per emitter expected at least 20 times,
      // |z| < 5.3 (false alarm 1.2e-7 each; with at most 8 × 2 × 150 emitters and the
      // estimates below, the file's rate stays below 1e-3). The numbers are fixed
      // hashes, so it cannot flake. And Σ w / pick over the chosen, for weights w, has
      // the mean Σ w over the emitters pmf does not rule out (|z| < 5.3 again).
      const scene = make();
      const bvh = scene.lightBvh()!;
      const n = 40_000;
      let split = 0;
      for (const max of [4, LIGHT_SPLIT]) {
        for (const [i, [x, y, z, nx, ny, nz]] of POINTS.entries()) {
          bvh.setPoint(x, y, z, nx, ny, nz);
          const cells = bvh.count + bvh.infinite.length;
          const picks = new Float64Array(cells);
          const weight = new Float64Array(cells);
          let exact = 0;
          for (let p = 0; p < cells; p++) {
            picks[p] = p < bvh.count ? bvh.pmf(p, max) : bvh.infinitePick;
            weight[p] = 0.5 + hashToUnit(sampleKey(29, p, 0), 0);
            if (picks[p] > 0) exact += weight[p];
          }
          const observed = new Float64Array(cells);
          let mismatched = 0;
          let chosen = 0;
          let sum = 0;
          let sum2 = 0;
          for (let s = 0; s < n; s++) {
            const u = hashToUnit(sampleKey(17, i, s), 0);
            const k = bvh.chooseSplit(u, max);
            let est = 0;
            for (let c = 0; c < k; c++) {
              const l = bvh.chosenLight[c];
              const inf = bvh.infinite.indexOf(l);
              const p = inf >= 0 ? bvh.count + inf : bvh.primOf(l, bvh.chosenTriangle[c]);
              if (bvh.chosenPick[c] !== picks[p]) mismatched++;
              observed[p]++;
              est += weight[p] / bvh.chosenPick[c];
            }
            chosen += k;
            sum += est;
            sum2 += est * est;
          }
          // The probability each choice reports is pmf's, to the bit.
          expect(mismatched, `point ${i}, max ${max}`).toBe(0);
          let tested = 0;
          for (let p = 0; p < cells; p++) {
            if (picks[p] === 0) {
              expect(observed[p], `emitter ${p} has pmf 0`).toBe(0);
              continue;
            }
            const e = n * picks[p];
            if (e < 20) continue;
            const zp = (observed[p] - e) / Math.sqrt(e * (1 - Math.min(picks[p], 1 - 1e-12)));
            expect(Math.abs(zp), `point ${i}, max ${max}, emitter ${p}`).toBeLessThan(5.3);
            tested++;
          }
          expect(tested, `point ${i}`).toBeGreaterThan(10);
          const mean = sum / n;
          const se = Math.sqrt(Math.max(0, sum2 / n - mean * mean) / n);
          expect(Math.abs(mean - exact), `point ${i}, max ${max}: ${mean} ± ${se}`).toBeLessThan(
            5.3 * se + 1e-9 * exact,
          );
          expect(chosen / n).toBeLessThanOrEqual(max);
          if (chosen / n > 1.5) split++;
        }
      }
      // Splitting happens: at several points more than one light is sampled on average.
      expect(split).toBeGreaterThan(4);
    });
  }

  it('gives MIS the density of each light a split chooses', () => {
    const scene = manyLightScene(true);
    const bvh = scene.lightBvh()!;
    const lights = scene.lights!;
    const ls = new LightSample();
    let checked = 0;
    let several = 0;
    for (let i = 0; i < 5_000; i++) {
      const key = sampleKey(31, i, 0);
      const point = randomPoint(key);
      const [x, y, z, nx, ny, nz] = point;
      bvh.setPoint(x, y, z, nx, ny, nz);
      const k = bvh.chooseSplit(hashToUnit(key, 4), LIGHT_SPLIT);
      if (k > 1) several++;
      for (let c = 0; c < k; c++) {
        const l = bvh.chosenLight[c];
        const kind = lights.kind[l];
        if (kind !== SHAPE_QUAD && kind !== SHAPE_TRIANGLE && kind !== SHAPE_SPHERE) continue;
        ls.light = l;
        ls.triangle = bvh.chosenTriangle[c];
        ls.pick = bvh.chosenPick[c];
        ls.refX = x;
        ls.refY = y;
        ls.refZ = z;
        ls.u0 = hashToUnit(key, 5 + 2 * c);
        ls.u1 = hashToUnit(key, 6 + 2 * c);
        if (!sampleLight(lights, scene.spheres, scene.quads, l, ls)) continue;
        const pdf = misPdf(scene, l, ls, point, LIGHT_SPLIT);
        expect(Math.abs(pdf / ls.pdf - 1), `light ${l} (kind ${kind})`).toBeLessThan(1e-9);
        checked++;
      }
    }
    expect(checked).toBeGreaterThan(2_000);
    expect(several).toBeGreaterThan(500);
  });

  it('chooses by power below a far node whose emitters face one way', () => {
    // From 100 m below the ceiling the root itself is far: every lamp's probability is
    // its share of the power (to rounding). From the floor, importance decides at the
    // top, so nearer lamps weigh more than their power (up to 28 % here).
    const scene = lampCeiling();
    const bvh = scene.lightBvh()!;
    const power = (p: number): number => {
      const m = scene.lights!.material[bvh.primLight[p]!]!;
      return scene.materials[m * MATERIAL_STRIDE + M_EMISSION]!;
    };
    let total = 0;
    for (let p = 0; p < bvh.count; p++) total += power(p);
    const worst = (y: number): number => {
      bvh.setPoint(0.1, y, 0.1, 0, 1, 0);
      let err = 0;
      for (let p = 0; p < bvh.count; p++) {
        err = Math.max(err, Math.abs(bvh.pmf(p) / (power(p) / total) - 1));
      }
      return err;
    };
    expect(worst(-100)).toBeLessThan(1e-12);
    expect(worst(0)).toBeGreaterThan(0.1);
  });

  it('is not built for a single light, where the choice by power is the same', () => {
    const scene = compileScene(
      validateScene({
        format: 'pathwise-scene/1',
        camera: { position: [0, 1, -4], target: [0, 1, 0], up: [0, 1, 0], fovY: 40 },
        materials: { lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [1, 1, 1] } },
        shapes: [{ type: 'quad', corner: [0, 2, 0], u: [1, 0, 0], v: [0, 0, 1], material: 'lamp' }],
      }),
    );
    expect(scene.lightBvh()).toBeNull();
  });
});
