/**
 * The generated-scene consistency suite (issue 8, deliverable 3; issue 11
 * §5 for meshes and maps; issue 25 for glTF materials), shared by consistency-*.test.ts so vitest can run
 * its parts on both cores.
 *
 * For each of SCENE_COUNT classic generated scenes (seeds 1…SCENE_COUNT),
 * MESH_SCENE_COUNT of the mesh family (seeds MESH_FIRST_SEED…) and
 * GLTF_SCENE_COUNT of the glTF family (seeds GLTF_FIRST_SEED…), at
 * 32×24 pixels and SEEDS independent seeds per configuration,
 * NEE+MIS must agree with BSDF-only and Sobol with independent sampling
 * (consistency.ts) in every region and channel: 2 pairs × 17 regions × 3
 * channels = 102 two-sided Welch tests per scene. The PUNCTUAL_SCENE_COUNT scenes of
 * the punctual family (seeds PUNCTUAL_FIRST_SEED…, delta lights, which BSDF-only
 * sampling cannot reach) run 102 tests of their own pairs (punctual.ts): Sobol =
 * independent, and point lights = tiny spheres standing in for them.
 *
 * The MANY_SCENE_COUNT scenes of the many-light family (seeds MANY_FIRST_SEED…) run a
 * third pair besides: lights chosen by the light BVH = lights chosen by power (153 tests).
 *
 * False alarms: each test rejects at p < ALPHA_SUITE / ((SCENE_COUNT +
 * MESH_SCENE_COUNT + GLTF_SCENE_COUNT + PUNCTUAL_SCENE_COUNT) · 102 + MANY_SCENE_COUNT · 153)
 * (Bonferroni), so a correct renderer fails the whole suite, over a fresh
 * draw of seeds, with probability at most ALPHA_SUITE = 1e-3. The seeds
 * are fixed, so the suite itself cannot flake: it either passes on every
 * run or fails on every run.
 */
import { describe, expect, it } from 'vitest';
import {
  ALPHA_PER_TEST,
  MANY_OPTIONS,
  MANY_TESTS_PER_SCENE,
  MESH_OPTIONS,
  OPTIONS,
  TESTS_PER_SCENE,
  checkConsistency,
  type PairTest,
} from './consistency.ts';
import { generateScene, loadGltfModels, type Family } from './generate.ts';
import { checkPunctual, sphereVariant, type PunctualPairTest } from './punctual.ts';

export {
  GLTF_FIRST_SEED,
  GLTF_SCENE_COUNT,
  MANY_FIRST_SEED,
  MANY_SCENE_COUNT,
  MESH_FIRST_SEED,
  MESH_SCENE_COUNT,
  PUNCTUAL_FIRST_SEED,
  PUNCTUAL_SCENE_COUNT,
  SCENE_COUNT,
} from './consistency.ts';

function explain(t: PairTest | PunctualPairTest): string {
  return (
    `${t.pair} ${t.region} channel ${t.channel}: ${t.meanA.toPrecision(6)} vs ` +
    `${t.meanB.toPrecision(6)}, t = ${t.t.toFixed(2)} (ν = ${t.nu.toFixed(1)}), p = ${t.p.toExponential(2)}`
  );
}

/** Registers one test per scene for seeds first…last of a family. */
export function consistencySuite(first: number, last: number, family: Family = 'classic'): void {
  const what =
    family === 'mesh'
      ? 'generated mesh and map scenes'
      : family === 'gltf'
        ? 'generated glTF-material scenes'
        : family === 'many'
          ? 'generated many-light scenes'
          : 'generated scenes';
  describe(`${what} ${first}–${last}: NEE+MIS = BSDF-only, Sobol = independent`, () => {
    for (let seed = first; seed <= last; seed++) {
      const generated = generateScene(seed, { family });
      it(`scene ${seed} (${generated.archetype}, ${generated.features.join(' ')})`, async () => {
        const options =
          family === 'classic' ? OPTIONS : family === 'many' ? MANY_OPTIONS : MESH_OPTIONS;
        const scene = family === 'gltf' ? await loadGltfModels(generated) : generated.scene;
        const r = checkConsistency(scene, options, 100_003 * seed);
        expect(r.tests.length).toBe(family === 'many' ? MANY_TESTS_PER_SCENE : TESTS_PER_SCENE);
        expect(r.rejected, 'non-finite samples').toBe(0);
        // The premise of the BSDF-only variance floor (consistency.ts).
        expect(r.maxBsdfSample).toBeLessThanOrEqual(r.bsdfBound);
        const failures = r.tests.filter((t) => !(t.p >= ALPHA_PER_TEST)).map(explain);
        expect(failures, `p < ${ALPHA_PER_TEST.toExponential(2)}`).toEqual([]);
      });
    }
  });
}

/**
 * Registers one test per punctual-family scene, seeds first…last (punctual.ts): Sobol
 * = independent, and each point light = the tiny sphere standing in for it, under the
 * suite's one Bonferroni budget.
 */
export function punctualSuite(first: number, last: number): void {
  describe(`generated punctual-light scenes ${first}–${last}: Sobol = independent, point light = tiny sphere`, () => {
    for (let seed = first; seed <= last; seed++) {
      const generated = generateScene(seed, { family: 'punctual' });
      it(`scene ${seed} (${generated.archetype}, ${generated.features.join(' ')})`, async () => {
        const scene = await loadGltfModels(generated);
        const spheres = await sphereVariant(generated);
        const r = checkPunctual(scene, spheres, MESH_OPTIONS, 100_003 * seed, ALPHA_PER_TEST);
        expect(r.tests.length).toBe(TESTS_PER_SCENE);
        expect(r.spheres, 'every scene has a point light').toBeGreaterThan(0);
        expect(r.rejected, 'non-finite samples').toBe(0);
        const failures = r.tests.filter((t) => !(t.p >= ALPHA_PER_TEST)).map(explain);
        expect(failures, `p < ${ALPHA_PER_TEST.toExponential(2)}`).toEqual([]);
      });
    }
  });
}
