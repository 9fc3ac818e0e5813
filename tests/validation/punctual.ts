/**
 * Estimator consistency for punctual lights (KHR_lights_punctual, src/core/lights/
 * punctual.ts) on the punctual family (archetypes-punctual.ts). A delta light is reached
 * only by next-event estimation, so the BSDF-only comparison of consistency.ts cannot
 * see it. Three renders of K independent seeds each, NEE+MIS throughout:
 *   A = the scene, Sobol;
 *   C = the scene, independent samples;
 *   S = the scene with each point light replaced by a sphere of radius r at its
 *       position, radiance I·colour/(π r²) and black albedo, Sobol;
 * and Welch tests of A = C and A = S on the per-seed means of every image region and
 * channel, as consistency.ts does (2 pairs × 17 regions × 3 channels).
 *
 * The sphere's bias. Seen from a receiver at distance d, the sphere fills a cone of
 * half-angle θs = asin(r/d); over it ∫ L cosθ dω = π L sin²θs cosθc = I cosθc / d²
 * exactly while the cone is above the receiver's horizon and unoccluded, the point
 * light's irradiance (a Lambertian sphere is a point source outside it). What differs:
 * 1. the BSDF over the cone: the first-order term cancels by symmetry, the second is
 *    ≤ θs²·(2/α)² relative for a GGX lobe of α ≥ MIN_ROUGHNESS² = 0.04, whose value
 *    varies over ~α/2 in wi; with θs ≤ POINT_SPHERE_RADIUS / CLEARANCE = 2e-4 that is
 *    ≤ 1e-4 (the sheen lobe, ≥ 0.05 rad wide, and diffuse lobes less);
 * 2. penumbrae, of width w ≤ r·(receiver distance / occluder distance) ≤ 1e-4·20/0.5 =
 *    4e-3 in the unit frame: the soft profile minus the hard one integrates to 0 across
 *    a straight edge, but where a region's border cuts an edge a strip ≤ w/2 wide differs
 *    by at most half its light on average: ≤ 3e-3 of a 4×3-pixel block's light (≥ 0.37
 *    units wide at the cameras' ≥ 5 units and fovY ≥ 25°) in the worst case;
 * 3. the sphere shading the environment, the horizon crossing the cone: O(θs²), ≤ 1e-7.
 * The test resolves at best ~0.15 % of the whole image (`detectable`), where only the
 * O(θs²) terms act, and ~0.5 % of a block: the sphere stands in for the point light
 * within the test's power (docs/validation.md).
 */
import { compileScene, parseScene, type Scene } from '../../src/core/index.ts';
import { POINT_SPHERE_RADIUS } from './archetypes-punctual.ts';
import type { PunctualLightJson, SceneJson } from './builder.ts';
import type { ConsistencyOptions } from './consistency.ts';
import { loadGltfModels, type GeneratedScene } from './generate.ts';
import {
  imageRegions,
  pilotSegments,
  renderReplicas,
  replicaMean,
  type RenderConfig,
  type Replicas,
} from './replicas.ts';
import { normalQuantileTwoSided, welch } from './stats.ts';

export interface PunctualPairTest {
  pair: 'sobol-vs-independent' | 'point-vs-sphere';
  region: string;
  channel: number;
  meanA: number;
  meanB: number;
  t: number;
  nu: number;
  p: number;
}

export interface PunctualConsistency {
  tests: PunctualPairTest[];
  spp: Record<'A' | 'C' | 'S', number>;
  rejected: number;
  /** Smallest relative bias of A in the whole image each pair detects at `alpha` (brightest channel). */
  detectable: Record<PunctualPairTest['pair'], number>;
  /** Point lights the sphere render replaced. */
  spheres: number;
}

/** The scene file with each point light a sphere of radius `radius` (see the file comment). */
export function pointLightsAsSpheres(json: SceneJson, radius: number): SceneJson {
  const lights: PunctualLightJson[] = [];
  const materials = { ...json.materials };
  const shapes = [...json.shapes];
  (json.lights ?? []).forEach((l, i) => {
    if (l.type !== 'point') {
      lights.push(l);
      return;
    }
    const L = l.intensity / (Math.PI * radius * radius);
    const name = `point-light-${i}`;
    materials[name] = {
      type: 'diffuse',
      albedo: [0, 0, 0],
      emission: [L * l.color[0], L * l.color[1], L * l.color[2]],
    };
    shapes.push({ type: 'sphere', center: l.position!, radius, material: name });
  });
  const { lights: _old, ...rest } = json;
  return { ...rest, materials, shapes, ...(lights.length > 0 ? { lights } : {}) };
}

/** The sphere stand-in of a generated punctual scene, its glTF models loaded. */
export async function sphereVariant(g: GeneratedScene): Promise<Scene> {
  const json = pointLightsAsSpheres(g.json, POINT_SPHERE_RADIUS * g.scale);
  return loadGltfModels({ ...g, json, scene: parseScene(JSON.stringify(json)) });
}

function sppFor(budget: number, perPath: number, pixels: number, seeds: number, max: number) {
  const ideal = budget / (perPath * pixels * seeds);
  let spp = 1;
  while (spp * 2 <= Math.min(ideal, max)) spp *= 2;
  return spp;
}

const CONFIGS: Record<'A' | 'C' | 'S', Omit<RenderConfig, 'spp'>> = {
  A: { estimator: 'nee-mis', sampler: 'sobol' },
  C: { estimator: 'nee-mis', sampler: 'independent' },
  S: { estimator: 'nee-mis', sampler: 'sobol' },
};

/** Runs A, C and S and tests both pairs; `alpha` only sets `detectable`. */
export function checkPunctual(
  scene: Scene,
  spheres: Scene,
  options: ConsistencyOptions,
  seedBase: number,
  alpha: number,
): PunctualConsistency {
  const { width, height, seeds } = options;
  const regions = imageRegions(width, height);
  const reps = {} as Record<'A' | 'C' | 'S', Replicas>;
  const spp = {} as Record<'A' | 'C' | 'S', number>;
  let rejected = 0;
  for (const key of ['A', 'C', 'S'] as const) {
    const s = key === 'S' ? spheres : scene;
    const compiled = compileScene(s);
    const perPath = pilotSegments(s, compiled, CONFIGS[key], width, height) + 2;
    spp[key] = sppFor(options.budget, perPath, width * height, seeds, options.maxSpp);
    const seedList = Array.from(
      { length: seeds },
      (_, k) => seedBase + 7919 * k + key.charCodeAt(0),
    );
    reps[key] = renderReplicas(
      s,
      compiled,
      { ...CONFIGS[key], spp: spp[key] },
      seedList,
      width,
      height,
      regions,
    );
    rejected += reps[key].stats.rejected;
  }
  const z = normalQuantileTwoSided(alpha);
  const tests: PunctualPairTest[] = [];
  const detectable = { 'sobol-vs-independent': Infinity, 'point-vs-sphere': Infinity };
  for (const [pair, other] of [
    ['sobol-vs-independent', 'C'],
    ['point-vs-sphere', 'S'],
  ] as const) {
    for (let r = 0; r < regions.length; r++) {
      for (let c = 0; c < 3; c++) {
        const a = replicaMean(reps.A, r, c);
        const b = replicaMean(reps[other], r, c);
        const precision = 1e-12 * Math.max(Math.abs(a.mean), Math.abs(b.mean));
        const w = welch(
          a.mean,
          a.variance + precision * precision,
          seeds - 1,
          b.mean,
          b.variance,
          seeds - 1,
        );
        if (r === 0 && a.mean > 0)
          detectable[pair] = Math.min(
            detectable[pair],
            (z * Math.sqrt(a.variance + b.variance)) / a.mean,
          );
        tests.push({
          pair,
          region: regions[r].name,
          channel: c,
          meanA: a.mean,
          meanB: b.mean,
          ...w,
        });
      }
    }
  }
  const count = (scene.lights ?? []).filter((l) => l.type === 'point').length;
  return { tests, spp, rejected, detectable, spheres: count };
}
