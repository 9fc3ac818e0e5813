/**
 * The scene generator (generate.ts): valid, deterministic, and covering
 * every situation issue 8 lists over the seeds the consistency suite uses;
 * and the consistency test's power: it must catch a known 3 % bias.
 */
import { describe, expect, it } from 'vitest';
import { parseScene, type QuadDesc, type Scene } from '../../src/core/index.ts';
import { ARCHETYPES } from './archetypes.ts';
import { FEATURES } from './builder.ts';
import { ALPHA_PER_TEST, OPTIONS, SCENE_COUNT, checkConsistency } from './consistency.ts';
import { generateScene } from './generate.ts';
import { cross, normalize } from './vec.ts';

const normal = (q: QuadDesc) => normalize(cross(q.u, q.v));

describe('scene generator', () => {
  const scenes = Array.from({ length: SCENE_COUNT }, (_, i) => generateScene(i + 1));

  it('makes valid scenes for many seeds (each passes parseScene)', () => {
    for (let seed = 1; seed <= 1000; seed++) {
      const g = generateScene(seed);
      expect(parseScene(JSON.stringify(g.json))).toEqual(g.scene);
    }
  });

  it('is deterministic: a seed gives the same file every time', () => {
    for (const seed of [1, 17, 99]) {
      expect(JSON.stringify(generateScene(seed).json)).toBe(JSON.stringify(scenes[seed - 1].json));
    }
    expect(JSON.stringify(scenes[0].json)).not.toBe(JSON.stringify(scenes[1].json));
  });

  it('covers every feature and archetype over the consistency suite’s seeds', () => {
    const seen = new Set(scenes.flatMap((g) => g.features));
    for (const f of FEATURES) expect(seen.has(f), f).toBe(true);
    const archetypes = new Set(scenes.map((g) => g.archetype));
    for (const a of ARCHETYPES) expect(archetypes.has(a.name), a.name).toBe(true);
  });

  it('spans the issue’s ranges: maxBounces 0–12, scales 1e-4–1e4, ground spheres to 1e5, d/r to 1.01', () => {
    const bounces = new Set(scenes.map((g) => g.scene.settings.maxBounces));
    for (let b = 0; b <= 12; b++) expect(bounces.has(b), `maxBounces ${b}`).toBe(true);
    const scales = scenes.map((g) => g.scale);
    expect(Math.min(...scales)).toBeLessThanOrEqual(1e-4);
    expect(Math.max(...scales)).toBeGreaterThanOrEqual(1e4);
    const radii = scenes.flatMap((g) =>
      g.scene.shapes.flatMap((s) => (s.type === 'sphere' ? [s.radius / g.scale] : [])),
    );
    expect(Math.max(...radii)).toBeGreaterThanOrEqual(1e5 * (1 - 1e-12));
    // Light-to-receiver distance over the light's radius, d/r (shapes 0 and 1 of the archetype).
    let closest = Infinity;
    for (let seed = 1; seed <= 400; seed++) {
      const { shapes } = generateScene(seed, { archetype: 'sphere-over-receiver' }).scene;
      const [receiver, light] = shapes;
      if (light.type !== 'sphere') continue;
      const d =
        receiver.type === 'sphere'
          ? Math.hypot(...light.center.map((x, i) => x - receiver.center[i])) - receiver.radius
          : receiver.type === 'quad'
            ? Math.abs(
                light.center.reduce(
                  (sum, x, i) => sum + (x - receiver.corner[i]) * normal(receiver)[i],
                  0,
                ),
              )
            : Infinity;
      closest = Math.min(closest, d / light.radius);
    }
    expect(closest).toBeLessThan(1.05);
  });
});

describe('consistency test power', () => {
  /** The scene with every emission and the environment scaled by k: the image scales by k. */
  function brighter(scene: Scene, k: number): Scene {
    const materials = Object.fromEntries(
      Object.entries(scene.materials).map(([n, m]) => [
        n,
        { ...m, emission: m.emission.map((e) => e * k) as [number, number, number] },
      ]),
    );
    const environment = scene.environment.map((e) => e * k) as [number, number, number];
    return { ...scene, materials, environment };
  }

  it('catches a 3 % bias in NEE+MIS, against both BSDF-only and independent sampling', () => {
    // Scene 32 (a ground sphere, two quad lights, 12 bounces), which the suite itself
    // checks unbiased, 3 % brighter for A only.
    const g = generateScene(32);
    const biased = checkConsistency(g.scene, OPTIONS, 100_003 * 32, { A: brighter(g.scene, 1.03) });
    for (const pair of ['nee-vs-bsdf', 'sobol-vs-independent']) {
      const caught = biased.tests.filter((t) => t.pair === pair && t.p < ALPHA_PER_TEST);
      expect(caught.length, pair).toBeGreaterThan(0);
    }
  });
});
