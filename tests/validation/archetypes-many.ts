/**
 * The generator's many-light family (issue 23): rooms lit by tens to hundreds of small
 * emitters, drawn with `generateScene(seed, { family: 'many' })`, for the light BVH
 * (src/core/lights/light-bvh.ts): NEE+MIS, whose choice of light now depends on the
 * shading point and its normal, must agree with BSDF-only sampling, which never
 * chooses a light (consistency-f.test.ts).
 *
 * Each scene: a room of quads (a wall sometimes missing, a constant environment then
 * seen through it) with diffuse or rough conductor walls, a few objects, and emitters
 * of three kinds in any mix:
 * - small spheres (radius 0.8–3 % of the room), strings of them along a wall, or
 *   scattered through the room;
 * - small quads facing every way (down, up, into a wall: each one-sided);
 * - an emissive grid mesh of 8 to 512 triangles, its vertices jittered so that the
 *   triangles face different ways, sometimes with cells left out.
 * Powers spread over two decades; radiance is capped at 100 so that BSDF-only
 * sampling, which must find every light by chance, still converges in the budget.
 */
import {
  bounces,
  environment,
  objects,
  pointIn,
  roomCamera,
  type Archetype,
  type Region,
  type Staged,
} from './archetypes.ts';
import type { SceneBuilder } from './builder.ts';
import { cross, length, normalize, sub, type Vec3 } from './vec.ts';

/**
 * A lamp's material: diffuse, of radiance L (at most 100) with a random tint. Never
 * glass or metal (b.emitter's now and then): each glass material multiplies the
 * BSDF-only sample bound by ior² (consistency.ts), and a few hundred lamps would make
 * the nee-vs-bsdf pair blind.
 */
function lamp(b: SceneBuilder, radiance: number): string {
  const L = Math.min(100, radiance);
  const tint = b.color(0.5, 1);
  return b.material('diffuse', [L * tint[0], L * tint[1], L * tint[2]]);
}

/** Small spheres: a string along a wall, or scattered in the region. */
function sphereLights(b: SceneBuilder, r: Region, size0: number, count: number, avoid: Vec3): void {
  const g = b.rng;
  const string = g.chance(0.4);
  const a = pointIn(b, r);
  const c = pointIn(b, r);
  for (let i = 0; i < count; i++) {
    const radius = size0 * g.logUniform(0.008, 0.03);
    const t = i / Math.max(1, count - 1);
    const p: Vec3 = string
      ? [
          a[0] + (c[0] - a[0]) * t,
          a[1] + (c[1] - a[1]) * t + 0.05 * size0 * Math.sin(20 * t),
          a[2] + (c[2] - a[2]) * t,
        ]
      : pointIn(b, r);
    if (length(sub(p, avoid)) < radius * 4) continue;
    // Power log-uniform over two decades; radiance = power / area.
    const power = g.logUniform(0.01, 1) * size0 * size0 * 0.02;
    b.sphere(p, radius, lamp(b, power / (4 * Math.PI * radius * radius)));
  }
  b.tag('sphere-light');
}

/** Small one-sided quads facing every way. */
function quadLights(b: SceneBuilder, r: Region, size0: number, count: number, avoid: Vec3): void {
  const g = b.rng;
  for (let i = 0; i < count; i++) {
    const s = size0 * g.logUniform(0.015, 0.06);
    const p = pointIn(b, r);
    if (length(sub(p, avoid)) < s * 4) continue;
    const n = b.rng.direction();
    const helper: Vec3 = Math.abs(n[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0];
    const eu = normalize(cross(helper, n));
    const ev = cross(n, eu);
    const u: Vec3 = [eu[0] * s, eu[1] * s, eu[2] * s];
    const v: Vec3 = [ev[0] * s, ev[1] * s, ev[2] * s];
    const corner: Vec3 = [
      p[0] - (u[0] + v[0]) / 2,
      p[1] - (u[1] + v[1]) / 2,
      p[2] - (u[2] + v[2]) / 2,
    ];
    const power = g.logUniform(0.01, 1) * size0 * size0 * 0.02;
    b.quad(corner, u, v, lamp(b, power / (s * s)));
  }
  b.tag('quad-light');
}

/** An emissive grid of k × k cells (two triangles each) facing down, jittered, some cells dropped. */
function gridLight(b: SceneBuilder, r: Region, size0: number): void {
  const g = b.rng;
  const k = g.int(2, 16);
  const side = size0 * g.uniform(0.1, 0.4);
  const c = pointIn(b, { lo: [r.lo[0], r.hi[1] * 0.7, r.lo[2]], hi: [r.hi[0], r.hi[1], r.hi[2]] });
  const jitter = (side / k) * g.uniform(0, 0.4);
  const positions: number[] = [];
  for (let i = 0; i <= k; i++) {
    for (let j = 0; j <= k; j++) {
      positions.push(
        c[0] - side / 2 + (side * i) / k,
        c[1] + g.uniform(-jitter, jitter),
        c[2] - side / 2 + (side * j) / k,
      );
    }
  }
  const drop = g.chance(0.5) ? g.uniform(0, 0.5) : 0;
  const indices: number[] = [];
  for (let i = 0; i < k; i++) {
    for (let j = 0; j < k; j++) {
      if (g.chance(drop)) continue;
      const v00 = i * (k + 1) + j;
      const v10 = v00 + k + 1;
      // Wound so that the normal points down (−y): cross(p10 − p00, p01 − p00) has −y.
      indices.push(v00, v10, v00 + 1, v10, v10 + 1, v00 + 1);
    }
  }
  if (indices.length === 0) indices.push(0, k + 1, 1);
  const power = g.logUniform(0.1, 1) * size0 * size0 * 0.2;
  b.mesh({ positions, indices }, lamp(b, power / (side * side)), side * side);
}

function buildManyRoom(b: SceneBuilder): Staged {
  const g = b.rng;
  const W = g.uniform(2, 6);
  const H = g.uniform(2, 4);
  const D = g.uniform(2, 6);
  const open = g.chance(0.3) ? [g.pick(['front', 'ceiling', 'left'])] : [];
  const wall = b.material(g.chance(0.85) ? 'diffuse' : 'conductor');
  b.box([0, 0, 0], [W, H, D], wall, false, open);
  environment(b, open.length > 0 ? 0.4 : 0.8);
  const eye: Vec3 = [g.uniform(0.2, 0.8) * W, g.uniform(0.2, 0.8) * H, g.uniform(0.05, 0.12) * D];
  const region: Region = { lo: [0.05 * W, 0.02 * H, 0.15 * D], hi: [0.95 * W, 0.95 * H, 0.95 * D] };
  const size0 = Math.hypot(W, H, D);
  const mix = g.weighted([
    ['spheres', 0.3],
    ['quads', 0.2],
    ['grid', 0.2],
    ['all', 0.3],
  ] as const);
  if (mix === 'spheres' || mix === 'all') sphereLights(b, region, size0, g.int(20, 300), eye);
  if (mix === 'quads' || mix === 'all') quadLights(b, region, size0, g.int(20, 200), eye);
  if (mix === 'grid' || mix === 'all') gridLight(b, region, size0);
  b.tag('multiple-lights');
  objects(b, { lo: [0.15 * W, 0, 0.25 * D], hi: [0.85 * W, 0.5 * H, 0.85 * D] }, g.int(1, 4), eye);
  return { camera: roomCamera(b, eye, W, H, D), maxBounces: bounces(b, 1, 6) };
}

export const MANY_ARCHETYPES: Archetype[] = [
  { name: 'many-room', weight: 1, build: buildManyRoom },
];
