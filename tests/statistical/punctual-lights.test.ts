/**
 * Punctual lights (lights/punctual.ts) against closed forms and against a tiny
 * emissive sphere of the same intensity:
 * 1. a point light over a Lambertian floor: L = ρ/π · I cosθ / d², the light straight
 *    above, 60° off and 85° off the normal, and at scales 1e-3 and 1e3;
 * 2. a spot's angular profile: the floor point seen from the spot at angles inside the
 *    inner cone, across the falloff and beyond the outer cone, against the extension's
 *    reference formula (written out here, not taken from the code under test);
 * 3. a directional light on a plane tilted 0°, 30°, 70° and 89°: L = ρ/π · E cosα;
 * 4. an emissive sphere of radius r and radiance I / (π r²) is, seen from outside and
 *    wholly above the horizon, exactly an isotropic source of intensity I (the
 *    sphere-to-element form factor): in direct light its render must match the point
 *    light's closed form, and in a room with several bounces (diffuse walls, a rough
 *    conductor) the two renders must agree region by region (Welch's test), and so
 *    over a glTF metallic–roughness model (its BSDF through bsdfEval, trace-path.ts);
 * 5. a mirror floor receives nothing from a point light (delta BSDF × delta light: no
 *    path), and its image is exactly black and finite.
 *
 * Each render uses K independent seeds (Sobol scrambling keyed by the seed); a case
 * fails when |estimate − exact| > t·se + δ, t the Student-t quantile for ALPHA / tests
 * (Bonferroni over every comparison of the file: the whole file false-alarms with
 * probability ≤ ALPHA = 1e-3), δ a deterministic bound on how much the answer varies
 * over the pinpoint camera's tiny footprint plus 1e-9 relative for rounding.
 */
import { Document } from '@gltf-transform/core';
import { describe, expect, it } from 'vitest';
import { compileScene, parseScene, type Scene } from '../../src/core/index.ts';
import { quadPrimitive, sceneWithFiles, toGlb } from '../helpers/gltf.ts';
import type { SceneJson, ShapeJson } from '../validation/builder.ts';
import { imageRegions, renderReplicas, replicaMean } from '../validation/replicas.ts';
import { studentTwoSided, welch } from '../validation/stats.ts';
import { add, mul, sub, type Vec3 } from '../validation/vec.ts';

const ALPHA = 1e-3;
const ALBEDO = 0.5;
const I = 7;

/** Student-t quantile for a two-sided p (bisection on the tail). */
function tQuantile(p: number, nu: number): number {
  let lo = 0;
  let hi = 1e3;
  for (let i = 0; i < 200; i++) {
    const mid = (lo + hi) / 2;
    if (studentTwoSided(mid, nu) > p) lo = mid;
    else hi = mid;
  }
  return hi;
}

type LightJson = Record<string, unknown>;

interface Case {
  name: string;
  scene: Omit<SceneJson, 'lights'> & { lights?: LightJson[] };
  exact: number;
  delta: number;
}

/** A camera at `eye` looking at `at` whose 4 × 3 image's half-diagonal at `at` is `footprint`. */
function pinpoint(eye: Vec3, at: Vec3, up: Vec3, footprint: number) {
  const dist = Math.hypot(...sub(at, eye));
  const fovY = ((2 * Math.atan(footprint / (dist * (5 / 3)))) / Math.PI) * 180;
  return { position: eye, target: at, up, fovY };
}

const floor = (S: number): Extract<ShapeJson, { type: 'quad' }> => ({
  type: 'quad',
  corner: [-S, 0, -S],
  u: [0, 0, 2 * S],
  v: [2 * S, 0, 0],
  material: 'floor',
});

function scene(
  camera: SceneJson['camera'],
  shapes: ShapeJson[],
  lights: LightJson[],
  maxBounces = 1,
  extra: SceneJson['materials'] = {},
): Case['scene'] {
  return {
    format: 'pathwise-scene/1',
    name: 'punctual',
    camera,
    settings: { width: 4, height: 3, maxBounces, spp: 4 },
    materials: { floor: { type: 'diffuse', albedo: [ALBEDO, ALBEDO, ALBEDO] }, ...extra },
    shapes,
    lights,
  };
}

/** The extension's reference falloff (KHR_lights_punctual, "Inner and Outer Cone Angles"). */
function referenceSpot(cd: number, innerRad: number, outerRad: number): number {
  const scale = 1 / Math.max(0.001, Math.cos(innerRad) - Math.cos(outerRad));
  const offset = -Math.cos(outerRad) * scale;
  const a = Math.min(1, Math.max(0, cd * scale + offset));
  return a * a;
}

const cases: Case[] = [];

// --- 1. Point light over a Lambertian floor ----------------------------------------

for (const [offAxisDeg, scale] of [
  [0, 1],
  [60, 1],
  [85, 1],
  [30, 1e-3],
  [30, 1e3],
]) {
  const d = 1.5 * scale;
  const th = (offAxisDeg * Math.PI) / 180;
  const light: Vec3 = [d * Math.sin(th), d * Math.cos(th), 0];
  const f = 1e-4 * d * Math.cos(th);
  // The camera halfway up the normal, below the light (no occluder: a point light).
  const camera = pinpoint([0, (d * Math.cos(th)) / 2, 0], [0, 0, 0], [0, 0, 1], f);
  const exact = (ALBEDO / Math.PI) * ((I * Math.cos(th)) / (d * d));
  cases.push({
    name: `point light ${offAxisDeg}° off the normal at distance ${d}`,
    scene: scene(camera, [floor(1e3 * d)], [{ type: 'point', position: light, intensity: I }]),
    exact,
    // E ∝ cosθ/d² varies at second order over the footprint: ≤ 10 (f / (d cosθ))².
    delta: (10 * (f / (d * Math.cos(th))) ** 2 + 1e-9) * exact,
  });
}

// --- 2. Spot profile -----------------------------------------------------------------

const INNER = 20;
const OUTER = 35;
for (const atDeg of [0, 10, 19, 22, 26, 30, 34, 36, 50]) {
  // The spot 2 above the origin, aimed so the origin is `atDeg` off its axis.
  const h = 2;
  const a = (atDeg * Math.PI) / 180;
  const axis: Vec3 = [Math.sin(a), -Math.cos(a), 0];
  const f = 1e-5 * h;
  const camera = pinpoint([0, h / 2, 0.3], [0, 0, 0], [0, 0, 1], f);
  const att = referenceSpot(Math.cos(a), (INNER * Math.PI) / 180, (OUTER * Math.PI) / 180);
  const exact = (ALBEDO / Math.PI) * ((I * att) / (h * h));
  const s = 1 / (Math.cos((INNER * Math.PI) / 180) - Math.cos((OUTER * Math.PI) / 180));
  cases.push({
    name: `spot (inner ${INNER}°, outer ${OUTER}°), floor point ${atDeg}° off its axis`,
    scene: scene(
      camera,
      [floor(1e3)],
      [
        {
          type: 'spot',
          position: [0, h, 0],
          direction: axis,
          intensity: I,
          innerConeAngle: INNER,
          outerConeAngle: OUTER,
        },
      ],
    ),
    exact,
    // Second order in the angular footprint f/h, times the falloff's curvature (~2s²).
    delta:
      ((10 + 2 * s * s) * (f / h) ** 2 + 1e-9) *
      Math.max(exact, (ALBEDO / Math.PI) * (I / (h * h))),
  });
}

// --- 3. Directional light on a tilted plane -----------------------------------------

const E_LUX = 3;
for (const tiltDeg of [0, 30, 70, 89]) {
  const t = (tiltDeg * Math.PI) / 180;
  // A plane through the origin, its normal tilted `t` from +y about the z axis.
  const n: Vec3 = [Math.sin(t), Math.cos(t), 0];
  const along: Vec3 = [Math.cos(t), -Math.sin(t), 0];
  const S = 100;
  const plane: ShapeJson = {
    type: 'quad',
    corner: add(mul(along, -S), [0, 0, -S]),
    u: [0, 0, 2 * S],
    v: mul(along, 2 * S),
    material: 'floor',
  };
  const camera = pinpoint(mul(n, 0.5), [0, 0, 0], [0, 0, 1], 1e-4);
  cases.push({
    name: `directional light on a plane tilted ${tiltDeg}°`,
    scene: scene(
      camera,
      [plane],
      [{ type: 'directional', direction: [0, -1, 0], intensity: E_LUX }],
    ),
    exact: (ALBEDO / Math.PI) * E_LUX * Math.cos(t),
    // E is constant over the plane: rounding only.
    delta: 1e-9 * E_LUX,
  });
}

// --- 4a. A tiny emissive sphere of the same intensity, direct light ------------------

for (const [offAxisDeg, r] of [
  [0, 1e-2],
  [50, 1e-3],
]) {
  const d = 1.5;
  const th = (offAxisDeg * Math.PI) / 180;
  const center: Vec3 = [d * Math.sin(th), d * Math.cos(th), 0];
  const L = I / (Math.PI * r * r);
  const f = 1e-4 * d * Math.cos(th);
  const camera = pinpoint([0, (d * Math.cos(th)) / 2, 0], [0, 0, 0], [0, 0, 1], f);
  cases.push({
    name: `emissive sphere r = ${r} of intensity ${I}, ${offAxisDeg}° off the normal, as the point light`,
    scene: scene(
      camera,
      [floor(1e3), { type: 'sphere', center, radius: r, material: 'lamp' }],
      [],
      1,
      {
        lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [L, L, L] },
      },
    ),
    exact: (ALBEDO / Math.PI) * ((I * Math.cos(th)) / (d * d)),
    delta: (10 * (f / (d * Math.cos(th))) ** 2 + 1e-9) * (ALBEDO / Math.PI) * (I / (d * d)),
  });
}

// --- 4b. The same, in a room with several bounces -----------------------------------

const ROOM_POINT: Vec3 = [0.2, 1.6, -0.3];
const ROOM_R = 1e-3;
function room(emitter: 'point' | 'sphere'): Case['scene'] {
  const L = I / (Math.PI * ROOM_R * ROOM_R);
  const shapes: ShapeJson[] = [
    floor(2),
    { type: 'quad', corner: [-2, 0, -2], u: [4, 0, 0], v: [0, 3, 0], material: 'wall' },
    { type: 'quad', corner: [-2, 0, 2], u: [0, 3, 0], v: [0, 0, -4], material: 'wall' },
    { type: 'sphere', center: [0.6, 0.5, 0.2], radius: 0.5, material: 'metal' },
  ];
  if (emitter === 'sphere')
    shapes.push({ type: 'sphere', center: ROOM_POINT, radius: ROOM_R, material: 'lamp' });
  return {
    ...scene(
      { position: [0, 1.2, 3.5], target: [0, 0.8, 0], up: [0, 1, 0], fovY: 60 },
      shapes,
      emitter === 'point'
        ? [{ type: 'point', position: ROOM_POINT, intensity: I, color: [1, 0.8, 0.6] }]
        : [],
      4,
      {
        wall: { type: 'diffuse', albedo: [0.7, 0.6, 0.5] },
        metal: { type: 'conductor', color: [0.9, 0.7, 0.4], roughness: 0.3 },
        lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [L, 0.8 * L, 0.6 * L] },
      },
    ),
    settings: { width: 16, height: 12, maxBounces: 4, spp: 32 },
  };
}
const ROOM_REGIONS = imageRegions(16, 12, 8);
const ROOM_TESTS = ROOM_REGIONS.length * 3;

/** Two unit quads of glTF metallic–roughness (one rough metal, one glossy plastic) on a floor. */
async function gltfRoom(emitter: 'point' | 'sphere'): Promise<Scene> {
  const doc = new Document();
  const metal = doc
    .createMaterial()
    .setBaseColorFactor([0.9, 0.6, 0.3, 1])
    .setMetallicFactor(1)
    .setRoughnessFactor(0.4);
  const plastic = doc
    .createMaterial()
    .setBaseColorFactor([0.2, 0.5, 0.8, 1])
    .setMetallicFactor(0)
    .setRoughnessFactor(0.2);
  const scene = doc.createScene();
  scene.addChild(
    doc
      .createNode()
      .setTranslation([-1.1, 0, 0])
      .setMesh(doc.createMesh().addPrimitive(quadPrimitive(doc).setMaterial(metal))),
  );
  scene.addChild(
    doc
      .createNode()
      .setTranslation([0.1, 0, 0.2])
      .setMesh(doc.createMesh().addPrimitive(quadPrimitive(doc).setMaterial(plastic))),
  );
  doc.getRoot().setDefaultScene(scene);
  const json = room(emitter);
  json.shapes = [floor(2), { type: 'gltf', file: 'quads.glb' } as unknown as ShapeJson];
  if (emitter === 'sphere')
    json.shapes.push({ type: 'sphere', center: ROOM_POINT, radius: ROOM_R, material: 'lamp' });
  json.camera = { position: [0, 0.8, 3], target: [0, 0.4, 0], up: [0, 1, 0], fovY: 50 };
  json.settings = { width: 16, height: 12, maxBounces: 3, spp: 32 };
  return sceneWithFiles(json, new Map([['quads.glb', await toGlb(doc)]]));
}

const TESTS = cases.length + 2 * ROOM_TESTS;
const T_CRIT_8 = tQuantile(ALPHA / TESTS, 7);

describe('punctual lights: known answers', () => {
  it.each(cases.map((c) => [c.name, c] as const))('%s', (_, c) => {
    const s = parseScene(JSON.stringify(c.scene));
    const seeds = Array.from({ length: 8 }, (_, k) => 4242 + 7919 * k);
    const regions = imageRegions(4, 3).slice(0, 1);
    const rep = renderReplicas(
      s,
      compileScene(s),
      { estimator: 'nee-mis', sampler: 'sobol', spp: 4 },
      seeds,
      4,
      3,
      regions,
    );
    expect(rep.stats.rejected).toBe(0);
    const { mean, variance } = replicaMean(rep, 0, 0);
    const se = Math.sqrt(variance);
    const allowed = T_CRIT_8 * se + c.delta;
    expect(
      Math.abs(mean - c.exact),
      `estimate ${mean.toPrecision(10)} ± ${se.toPrecision(2)}, exact ${c.exact.toPrecision(10)}, ` +
        `allowed ${allowed.toPrecision(3)}`,
    ).toBeLessThanOrEqual(allowed);
  });
});

/** Region by region and channel by channel, the point light's render equals the sphere's. */
function compareRenders(scenes: Scene[]): void {
  const seeds = Array.from({ length: 12 }, (_, k) => 77 + 104729 * k);
  const renders = scenes.map((s) => {
    return renderReplicas(
      s,
      compileScene(s),
      { estimator: 'nee-mis', sampler: 'sobol', spp: 32 },
      seeds,
      16,
      12,
      ROOM_REGIONS,
    );
  });
  for (const r of renders) expect(r.stats.rejected).toBe(0);
  const failures: string[] = [];
  for (let ri = 0; ri < ROOM_REGIONS.length; ri++) {
    for (let c = 0; c < 3; c++) {
      const a = replicaMean(renders[0], ri, c);
      const b = replicaMean(renders[1], ri, c);
      // The sphere's own size: its radiance pattern equals the point's up to (r/d)² ≈ 1e-6.
      const bias = 1e-5 * Math.max(a.mean, b.mean);
      const diff = Math.max(0, Math.abs(a.mean - b.mean) - bias);
      const w = welch(diff, a.variance, seeds.length - 1, 0, b.variance, seeds.length - 1);
      if (w.p < ALPHA / TESTS)
        failures.push(
          `${ROOM_REGIONS[ri].name} channel ${c}: point ${a.mean.toPrecision(6)} ± ` +
            `${Math.sqrt(a.variance).toPrecision(2)}, sphere ${b.mean.toPrecision(6)} ± ` +
            `${Math.sqrt(b.variance).toPrecision(2)} (p = ${w.p.toExponential(2)})`,
        );
    }
  }
  expect(failures).toEqual([]);
  // The light reaches the image: not a comparison of two black pictures.
  expect(replicaMean(renders[0], 0, 0).mean).toBeGreaterThan(0.01);
}

describe('punctual lights: a point light and a tiny sphere of its intensity in a room', () => {
  it('agree in every region and channel (4 bounces, diffuse walls, rough metal)', () => {
    compareRenders((['point', 'sphere'] as const).map((e) => parseScene(JSON.stringify(room(e)))));
  });

  it('agree over glTF metallic–roughness surfaces (3 bounces)', async () => {
    compareRenders(await Promise.all((['point', 'sphere'] as const).map(gltfRoom)));
  });
});

describe('punctual lights and delta BSDFs', () => {
  it('a mirror floor under a point light receives nothing: exactly black, no sample rejected', () => {
    const s = parseScene(
      JSON.stringify(
        scene(
          pinpoint([0, 1, 0.5], [0, 0, 0], [0, 0, 1], 0.05),
          [{ ...floor(10), material: 'mirror' }],
          [{ type: 'point', position: [0, 1, -0.5], intensity: I }],
          3,
          { mirror: { type: 'conductor', color: [1, 1, 1], roughness: 0 } },
        ),
      ),
    );
    const rep = renderReplicas(
      s,
      compileScene(s),
      { estimator: 'nee-mis', sampler: 'sobol', spp: 8 },
      [1, 2],
      4,
      3,
      imageRegions(4, 3).slice(0, 1),
    );
    expect(rep.stats.rejected).toBe(0);
    expect(rep.maxSample).toBe(0);
  });
});
