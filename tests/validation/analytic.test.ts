/**
 * Known-answer tests (issue 8, deliverable 5), each with NEE+MIS and with
 * BSDF-only:
 * 1. sphere-light irradiance π L (r/d)² on a diffuse receiver straight
 *    below the light, d/r from 1000 down to 1.01, receivers a quad, a
 *    small sphere and huge spheres (radius 1e3, 1e5), and the issue's
 *    exact scene at scales 1e-4 and 1e4;
 * 2. the form factor of rectangle lights onto a point (Lambert's polygon
 *    formula), parallel, tilted, standing, near and large;
 * 3. a thin quad light seen edge-on: the issue's light, tilted 1e-4…0.1 rad
 *    off a floor, lighting a wall point 1e-4…0.2 below its plane (the
 *    issue's third case), and a quad light seen by the camera itself
 *    0.1…0.001 rad off its plane.
 *
 * Each case renders a tiny image whose every pixel sees (nearly) one
 * point, with K = 32 independent seeds; the estimate is the mean over
 * seeds and its standard error the spread across seeds (31 dof). A case
 * fails when |estimate − exact| > t·se + δ, with t the Student-t quantile
 * for p = ALPHA / CASES (Bonferroni: the whole file false-alarms with
 * probability ≤ ALPHA = 1e-3) and δ a deterministic bound on how much the
 * answer varies over the tiny pixel footprint (second order in
 * footprint / distance, computed per case) plus 1e-9 relative for rounding.
 */
import { describe, expect, it } from 'vitest';
import { compileScene, parseScene, type Estimator } from '../../src/core/index.ts';
import { polygonArea, polygonIrradiance, quadVertices, sphereIrradiance } from './analytic.ts';
import type { SceneJson, ShapeJson } from './builder.ts';
import { imageRegions, renderReplicas, replicaMean } from './replicas.ts';
import { studentTwoSided } from './stats.ts';
import { add, cross, dot, normalize, sub, type Vec3 } from './vec.ts';

const ALPHA = 1e-3;
const SEEDS = 32;

interface Case {
  name: string;
  scene: SceneJson;
  exact: number;
  /** Deterministic tolerance (footprint and rounding), absolute. */
  delta: number;
  estimator: Estimator;
  spp: number;
  width?: number;
  height?: number;
}

const cases: Case[] = [];

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

/**
 * A camera at `eye` looking at `at` with a field of view so narrow that
 * the image footprint's half-diagonal at `at` is `footprint`; returns it
 * with that half-diagonal.
 */
function pinpoint(eye: Vec3, at: Vec3, up: Vec3, footprint: number) {
  const dist = Math.hypot(...sub(at, eye));
  // Half-diagonal = dist · tan(fovY/2) · √(1 + aspect²), aspect 4/3 → × 5/3.
  const fovY = ((2 * Math.atan(footprint / (dist * (5 / 3)))) / Math.PI) * 180;
  return { position: eye, target: at, up, fovY };
}

function scene(
  name: string,
  camera: SceneJson['camera'],
  shapes: ShapeJson[],
  materials: SceneJson['materials'],
  maxBounces: number,
): SceneJson {
  return {
    format: 'pathwise-scene/1',
    name,
    camera,
    settings: { width: 4, height: 3, maxBounces, spp: 64 },
    materials,
    shapes,
  };
}

// --- 1. Sphere light over a receiver --------------------------------------

const R_LIGHT = 0.25;
const L_LIGHT = 10;
const ALBEDO = 0.5;

function sphereCase(receiver: 'quad' | 'small sphere' | number, dOverR: number, scale = 1) {
  const r = R_LIGHT * scale;
  const d = dOverR * r;
  const shapes: ShapeJson[] = [{ type: 'sphere', center: [0, d, 0], radius: r, material: 'lamp' }];
  let curvature = Infinity;
  if (receiver === 'quad') {
    const S = 1e3 * d;
    shapes.push({
      type: 'quad',
      corner: [-S, 0, -S],
      u: [0, 0, 2 * S],
      v: [2 * S, 0, 0],
      material: 'floor',
    });
  } else {
    const R = receiver === 'small sphere' ? 0.5 * d : receiver * scale;
    curvature = R;
    shapes.push({ type: 'sphere', center: [0, -R, 0], radius: R, material: 'floor' });
  }
  // The camera sits between light and receiver, looking straight down (it is no occluder).
  const gap = d - r;
  const footprint = 1e-4 * Math.min(gap, curvature);
  const camera = pinpoint([0, gap / 2, 0], [0, 0, 0], [0, 0, 1], footprint);
  const exact = (ALBEDO / Math.PI) * sphereIrradiance([0, 0, 0], [0, 1, 0], [0, d, 0], r, L_LIGHT);
  // E varies as 1 − (3/2)(x/d)² on a plane; curvature tilts the normal by x/R.
  const rel = 3 * (footprint / Math.min(d, curvature)) ** 2 + 1e-9;
  const label = typeof receiver === 'number' ? `sphere of radius ${receiver}` : `a ${receiver}`;
  return {
    name: `sphere light, d/r = ${dOverR}, over ${label}${scale !== 1 ? `, scale ${scale}` : ''}`,
    scene: scene(
      'sphere light over a receiver',
      camera,
      shapes,
      {
        floor: { type: 'diffuse', albedo: [ALBEDO, ALBEDO, ALBEDO] },
        lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [L_LIGHT, L_LIGHT, L_LIGHT] },
      },
      1,
    ),
    exact,
    delta: rel * exact,
  };
}

for (const receiver of ['quad', 'small sphere', 1e3, 1e5] as const) {
  for (const dOverR of [1000, 100, 20, 5, 2, 1.1, 1.01]) {
    cases.push({ ...sphereCase(receiver, dOverR), estimator: 'nee-mis', spp: 32 });
  }
  // BSDF-only finds the light with probability (r/d)²: 197k samples give ≥ 7,800 hits.
  for (const dOverR of [5, 2, 1.1, 1.01]) {
    cases.push({ ...sphereCase(receiver, dOverR), estimator: 'bsdf', spp: 512 });
  }
}
for (const scale of [1e-4, 1e4]) {
  cases.push({ ...sphereCase('quad', 20, scale), estimator: 'nee-mis', spp: 32 });
  cases.push({ ...sphereCase(1e5, 20, scale), estimator: 'nee-mis', spp: 32 });
}

// --- 2. Rectangle lights onto a point --------------------------------------

/** A quad light (corner, u, v; front side along cross(u, v)) lighting the origin of a floor. */
function rectangleCase(name: string, corner: Vec3, u: Vec3, v: Vec3) {
  const vertices = quadVertices(corner, u, v);
  const n = normalize(cross(u, v));
  if (dot(n, sub([0, 0, 0], corner)) <= 0) throw new Error(`${name}: light faces away`);
  // Distance scale: the nearer of the light's corners and the point where
  // the vertical through the receiver meets the light's plane.
  const hit = dot(corner, n) / n[1];
  const near = Math.min(
    ...vertices.map((p) => Math.hypot(...p)),
    Number.isFinite(hit) && hit > 0 ? hit : Infinity,
  );
  // The camera looks straight down from half that height: below the light.
  const eyeY = near / 2;
  const footprint = 1e-4 * near;
  const S = 1e3 * near;
  const exact = (ALBEDO / Math.PI) * polygonIrradiance([0, 0, 0], [0, 1, 0], vertices, L_LIGHT);
  return {
    name: `rectangle light: ${name}`,
    scene: scene(
      name,
      pinpoint([0, eyeY, 0], [0, 0, 0], [0, 0, 1], footprint),
      [
        {
          type: 'quad',
          corner: [-S, 0, -S],
          u: [0, 0, 2 * S],
          v: [2 * S, 0, 0],
          material: 'floor',
        },
        { type: 'quad', corner, u, v, material: 'lamp' },
      ],
      {
        floor: { type: 'diffuse', albedo: [ALBEDO, ALBEDO, ALBEDO] },
        lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [L_LIGHT, L_LIGHT, L_LIGHT] },
      },
      1,
    ),
    exact,
    delta: (3 * 1e-8 + 1e-9) * exact,
  };
}

const tilt = (a: number): Vec3 => [0, Math.sin(a), Math.cos(a)];
// cross(u, v) must point down, towards the floor point (checked).
const rectangles = [
  rectangleCase('1 × 1, parallel, centred, 1 above', [-0.5, 1, -0.5], [1, 0, 0], [0, 0, 1]),
  rectangleCase('2 × 0.5, parallel, off-centre', [0.3, 0.8, -0.2], [2, 0, 0], [0, 0, 0.5]),
  rectangleCase(
    '1 × 1, 0.01 above, 0.1 in from an edge (near)',
    [-0.1, 0.01, -0.5],
    [1, 0, 0],
    [0, 0, 1],
  ),
  rectangleCase('100 × 100, 1 above (large)', [-50, 1, -50], [100, 0, 0], [0, 0, 100]),
  rectangleCase('1 × 1, tilted 40°', [-0.5, 0.7, -0.3], [1, 0, 0], tilt(0.7)),
  rectangleCase('1 × 0.6, standing beside the point', [-0.5, 0, 0.4], [0, 0.6, 0], [1, 0, 0]),
];
for (const c of rectangles) {
  cases.push({ ...c, estimator: 'nee-mis', spp: 32 });
  cases.push({ ...c, estimator: 'bsdf', spp: 256 });
}

// --- 3. Thin quad light seen edge-on ----------------------------------------

/**
 * The issue's grazing light: 2 × 1, its near edge 0.3 above the floor at
 * z = 0.5, tilted `tiltAngle` off horizontal and facing down, towards a
 * wall at z = 2. The wall point (0, y, 2) sees its emitting side edge-on,
 * `below` under the light's plane. Only direct light (maxBounces 1).
 */
function grazingCase(tiltAngle: number, below: number) {
  const u: Vec3 = [2, 0, 0];
  const v: Vec3 = [0, Math.sin(tiltAngle), Math.cos(tiltAngle)];
  const corner: Vec3 = [-1, 0.3, 0.5];
  const planeAtWall = 0.3 + 1.5 * Math.tan(tiltAngle);
  const p: Vec3 = [0, planeAtWall - below, 2];
  const exact =
    (0.7 / Math.PI) * polygonIrradiance(p, [0, 0, -1], quadVertices(corner, u, v), L_LIGHT);
  const footprint = 1e-4 * below;
  return {
    name: `grazing quad light tilted ${tiltAngle} rad, wall point ${below} below its plane`,
    scene: scene(
      'grazing quad light on a wall',
      pinpoint(add(p, [0, 0, -0.05]), p, [0, 1, 0], footprint),
      [
        { type: 'quad', corner: [-5, 0, -5], u: [0, 0, 7], v: [10, 0, 0], material: 'floor' },
        { type: 'quad', corner: [-5, 0, 2], u: [10, 0, 0], v: [0, 5, 0], material: 'wall' },
        { type: 'quad', corner, u, v, material: 'lamp' },
      ],
      {
        floor: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] },
        wall: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
        lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [L_LIGHT, L_LIGHT, L_LIGHT] },
      },
      1,
    ),
    exact,
    // E is smooth across the footprint (symmetric about p): second order in footprint / below.
    delta: (10 * 1e-8 + 1e-9) * exact,
  };
}

// The wall point sees the light's emitting side at ~`below` rad: 1e-4 is
// beyond BSDF-only's reach (it finds the light with probability 6e-5), the
// others it hits with probability 6e-3 and 0.1.
for (const tiltAngle of [1e-4, 1e-3, 1e-2, 0.1]) {
  for (const below of [1e-4, 0.01, 0.2]) {
    const c = grazingCase(tiltAngle, below);
    cases.push({ ...c, estimator: 'nee-mis', spp: 32 });
    if (below >= 0.01) cases.push({ ...c, estimator: 'bsdf', spp: 512 });
  }
}

/**
 * A 0.5 × 0.6 quad light in the plane y = −1.5·tan(angle), from z = 1.2 to
 * 1.8, seen by a camera at the origin looking along +z: at grazing angles
 * near `angle`. No bounce, so the image mean is L times the fraction of the film
 * its projection covers (the spec's box filter): a shoelace area.
 */
function edgeOnCase(angle: number, front: boolean) {
  const fovY = 20;
  const W = 32;
  const H = 24;
  const y0 = -1.5 * Math.tan(angle);
  const corner: Vec3 = [-0.25, y0, 1.2];
  const across: Vec3 = [0.5, 0, 0];
  const along: Vec3 = [0, 0, 0.6];
  // cross(along, across) = (0, 0.6, 0): the emitting side faces up, towards the camera.
  const [u, v] = front ? [along, across] : [across, along];
  const tan = Math.tan((fovY / 2) * (Math.PI / 180));
  // Camera frame (spec): forward +z, right = cross(forward, up) = −x, upImage = +y.
  const film = quadVertices(corner, u, v).map((q): [number, number] => {
    const a = -q[0] / q[2] / (tan * (W / H));
    const b = q[1] / q[2] / tan;
    return [((a + 1) * W) / 2, ((1 - b) * H) / 2];
  });
  for (const [x, y] of film) {
    if (x < 0 || x > W || y < 0 || y > H) throw new Error('edge-on quad leaves the film');
  }
  const exact = front ? (L_LIGHT * polygonArea(film)) / (W * H) : 0;
  return {
    name: `quad light seen ${angle} rad off its plane, ${front ? 'front' : 'back'} side`,
    scene: scene(
      'quad light seen edge-on',
      { position: [0, 0, 0], target: [0, 0, 3], up: [0, 1, 0], fovY },
      [{ type: 'quad', corner, u, v, material: 'lamp' }],
      { lamp: { type: 'diffuse', albedo: [0.5, 0.5, 0.5], emission: [L_LIGHT, L_LIGHT, L_LIGHT] } },
      0,
    ),
    exact,
    delta: 1e-9 * L_LIGHT,
    width: W,
    height: H,
  };
}

for (const angle of [0.1, 0.01, 0.001]) {
  const c = edgeOnCase(angle, true);
  cases.push({ ...c, estimator: 'nee-mis', spp: 16 });
  cases.push({ ...c, estimator: 'bsdf', spp: 16 });
}
cases.push({ ...edgeOnCase(0.01, false), estimator: 'nee-mis', spp: 4 });

// --- The tests ---------------------------------------------------------------

const T_CRIT = tQuantile(ALPHA / cases.length, SEEDS - 1);

describe('the closed forms themselves', () => {
  it('agree with each other and with their limits', () => {
    // A far, small square: E → L·A·cos·cos/d².
    const far = polygonIrradiance(
      [0, 0, 0],
      [0, 1, 0],
      quadVertices([-0.005, 100, -0.005], [0, 0, 0.01], [0.01, 0, 0]),
      1,
    );
    expect(far / (1e-4 / 1e4) - 1).toBeLessThan(1e-6);
    // A huge parallel square: E → π L.
    const plane = polygonIrradiance(
      [0, 0, 0],
      [0, 1, 0],
      quadVertices([-1e6, 1, -1e6], [0, 0, 2e6], [2e6, 0, 0]),
      1,
    );
    expect(Math.abs(plane / Math.PI - 1)).toBeLessThan(1e-5);
    // A parallel a × b rectangle at height 1 over its corner: the closed form of
    // Siegel & Howell (differential element to parallel rectangle).
    for (const [a, b] of [
      [1, 1],
      [2, 0.5],
      [0.1, 30],
    ]) {
      const term = (x: number, y: number) =>
        (x / Math.sqrt(1 + x * x)) * Math.atan(y / Math.sqrt(1 + x * x));
      const formFactor = (term(a, b) + term(b, a)) / (2 * Math.PI);
      const polygon =
        polygonIrradiance([0, 0, 0], [0, 1, 0], quadVertices([0, 1, 0], [a, 0, 0], [0, 0, b]), 1) /
        Math.PI;
      expect(Math.abs(polygon / formFactor - 1)).toBeLessThan(1e-12);
    }
    expect(
      sphereIrradiance([0, 0, 0], [0, 1, 0], [0, 5, 0], 0.25, 10) * (0.5 / Math.PI),
    ).toBeCloseTo(0.0125, 12);
  });
});

describe('known answers (NEE+MIS and BSDF-only)', () => {
  it.each(cases.map((c) => [`${c.name} [${c.estimator}]`, c] as const))('%s', (_, c) => {
    const s = parseScene(JSON.stringify(c.scene));
    const width = c.width ?? 4;
    const height = c.height ?? 3;
    const regions = imageRegions(width, height).slice(0, 1);
    const seeds = Array.from({ length: SEEDS }, (_, k) => 9001 + 7919 * k);
    const rep = renderReplicas(
      s,
      compileScene(s),
      { estimator: c.estimator, sampler: 'sobol', spp: c.spp },
      seeds,
      width,
      height,
      regions,
    );
    expect(rep.stats.rejected).toBe(0);
    const { mean, variance } = replicaMean(rep, 0, 0);
    const se = Math.sqrt(variance);
    const allowed = T_CRIT * se + c.delta;
    expect(
      Math.abs(mean - c.exact),
      `estimate ${mean.toPrecision(8)} ± ${se.toPrecision(2)}, exact ${c.exact.toPrecision(8)} ` +
        `(${((mean / c.exact - 1) * 100).toFixed(3)} %), allowed ${allowed.toPrecision(3)}`,
    ).toBeLessThanOrEqual(allowed);
  });
});
