/**
 * The emitters of a scene, for next-event estimation: every emissive sphere,
 * quad and mesh, and the environment map, chosen in proportion to power
 * (luminance of the emitted radiance times area; for the map, its integral of
 * luminance times the scene's radius squared, see compile.ts) from a CDF, and
 * then sampled:
 * - quads uniformly by area (pbr-book 4e §6.5.1), converted to solid angle;
 * - meshes uniformly by area over all their triangles (mesh-light.ts);
 * - the environment map by luminance times solid angle (environment-map.ts);
 * - spheres seen from outside uniformly in the cone of directions they
 *   subtend (pbr-book 3e §14.2.2, Sphere::Sample(ref)), which wastes no
 *   samples on the hidden back side; from inside, uniformly by area.
 * Emission leaves only the front side of a surface (outside of a sphere).
 * Point, spot and directional lights are delta lights (punctual.ts): chosen by
 * power like the rest, never hit by a ray, so lightPdf is never asked for them.
 *
 * The choice by power from a CDF is one of two: the light BVH (light-bvh.ts) chooses
 * by an estimate of each emitter's contribution at the reference point, and each
 * triangle of an emissive mesh on its own. The caller makes the choice and writes it
 * into the LightSample (`pick`, and `triangle` for a mesh), which `sampleLight` then
 * samples; `lightPdf` takes the BVH (or null for the CDF) to find the same `pick`.
 *
 * The shadow ray's far end is the sampled point lifted off the emitter, toward
 * the reference point, by a distance relative to the emitter's coordinates
 * (`OFFSET_SCALE`, the same rule the integrator uses to lift ray origins off
 * receivers). Aiming at the surface point itself with a tMax shortened by a
 * fixed fraction of the distance is not enough: the receiver's own lift can
 * exceed that fraction (a huge ground sphere lifts by ~1e-6 while a shadow
 * ray of length 5 keeps only ~5e-9 of slack), and then the emitter occludes
 * its own sample — which is why NEE once lost 3 % of a sphere light over a
 * floor and all of it over a ground sphere of radius 1000.
 */
import {
  OFFSET_SCALE,
  QUAD_STRIDE,
  Q_AREA,
  Q_CORNER,
  Q_NORMAL,
  Q_U,
  Q_V,
  SPHERE_STRIDE,
} from '../geometry/shapes.ts';
import { LIGHT_ENVIRONMENT, LIGHT_POINT, SHAPE_QUAD, SHAPE_TRIANGLE } from '../geometry/ray.ts';
import { Distribution1D } from '../sampling/distribution.ts';
import { EnvironmentSample, type EnvironmentMap } from './environment-map.ts';
import { MeshLightSample, type MeshLight } from './mesh-light.ts';
import { samplePunctual } from './punctual.ts';
import type { LightBvh } from './light-bvh.ts';

/**
 * In: the reference point and two random numbers (set by the caller; a
 * record rather than arguments keeps doubles unboxed across the call).
 * Out: what `sampleLight` writes — direction, distance, point and pdf.
 */
export class LightSample {
  refX = 0;
  refY = 0;
  refZ = 0;
  u0 = 0;
  u1 = 0;
  wx = 0;
  wy = 0;
  wz = 0;
  distance = 0;
  /**
   * The shadow ray's far end: the sampled point lifted off the emitter toward
   * the reference point (see the module comment).
   */
  px = 0;
  py = 0;
  pz = 0;
  /** Solid-angle density including the probability of choosing this light. */
  pdf = 0;
  /** In: the probability with which the light was chosen. */
  pick = 0;
  /** Index of the chosen light in the light list. */
  light = -1;
  /**
   * On a mesh light: the triangle and the point's barycentrics (weights of its
   * vertices 1 and 2), for emission that varies over the mesh (glTF textures).
   * In: the triangle the light BVH chose, or −1 to draw one by area over the mesh.
   */
  triangle = -1;
  b1 = 0;
  b2 = 0;
  /**
   * Radiance arriving from the environment map (`distance` is then Infinity), or the
   * irradiance from a punctual light (punctual.ts).
   */
  r = 0;
  g = 0;
  b = 0;
}

/** What a light list is made of, one entry per light. */
export interface LightListInput {
  /**
   * SHAPE_SPHERE, SHAPE_QUAD, SHAPE_TRIANGLE (a whole mesh), LIGHT_ENVIRONMENT, or a
   * punctual light (LIGHT_POINT, LIGHT_SPOT, LIGHT_DIRECTIONAL).
   */
  kind: number[];
  /** Index of the sphere, quad, mesh or punctual light (0 for the environment). */
  shape: number[];
  /** Selection weight (see the module comment). */
  power: number[];
  /** Coordinate magnitude, for the lift of sampled points (0 for the environment). */
  scale: number[];
  /** Material index of the emitter (−1 for the environment). */
  material: number[];
  /** The MeshLight of each mesh entry, by its `shape`: meshLights[shape]. */
  meshLights?: (MeshLight | null)[];
  environment?: EnvironmentMap | null;
  /** The punctual lights' records (punctual.ts), indexed by `shape`. */
  punctual?: Float64Array;
}

export class LightList {
  readonly count: number;
  readonly kind: Int32Array;
  readonly shape: Int32Array;
  readonly material: Int32Array;
  /** Probability of choosing each light. */
  readonly prob: Float64Array;
  /** The choice: a CDF over the lights (stratified numbers stay stratified). */
  readonly distribution: Distribution1D;
  /** Distance by which a sampled point is lifted off each light (OFFSET_SCALE × its scale). */
  readonly offset: Float64Array;
  readonly meshLights: (MeshLight | null)[];
  readonly environment: EnvironmentMap | null;
  readonly punctual: Float64Array;
  /** Index of the environment map in the list, or −1. */
  readonly environmentLight: number;
  /**
   * The light BVH over these lights, once built (CompiledScene.lightBvh); sampleLight
   * reads its triangle areas.
   */
  bvh: LightBvh | null = null;
  /** Scratch records of sampleLight (one list per thread, so never shared). */
  readonly meshSample = new MeshLightSample();
  readonly envSample = new EnvironmentSample();

  constructor(input: LightListInput) {
    this.count = input.kind.length;
    this.kind = Int32Array.from(input.kind);
    this.shape = Int32Array.from(input.shape);
    this.material = Int32Array.from(input.material);
    this.offset = Float64Array.from(input.scale, (s) => s * OFFSET_SCALE);
    this.distribution = new Distribution1D(input.power);
    this.prob = Float64Array.from({ length: this.count }, (_, i) => this.distribution.prob(i));
    this.meshLights = input.meshLights ?? [];
    this.environment = input.environment ?? null;
    this.punctual = input.punctual ?? new Float64Array(0);
    this.environmentLight = input.kind.indexOf(LIGHT_ENVIRONMENT);
  }

  /** Index of the light whose CDF interval contains u (binary search). */
  choose(u: number): number {
    return this.distribution.find(u);
  }
}

/**
 * Samples a point on light `l` as seen from (out.refX, refY, refZ) with the
 * numbers out.u0, out.u1. Writes `out` and returns false when the sample
 * cannot contribute (back side, degenerate).
 */
export function sampleLight(
  lights: LightList,
  spheres: Float64Array,
  quads: Float64Array,
  l: number,
  out: LightSample,
): boolean {
  const x = out.refX,
    y = out.refY,
    z = out.refZ;
  const u0 = out.u0,
    u1 = out.u1;
  const s = lights.shape[l];
  const choose = out.pick;
  const lift = lights.offset[l];
  out.light = l;
  const kind = lights.kind[l];
  if (kind === SHAPE_TRIANGLE) {
    const mesh = lights.meshLights[s]!;
    const ms = lights.meshSample;
    let area = mesh.area;
    if (out.triangle >= 0) {
      // Chosen by the light BVH: this triangle alone, uniformly by its area.
      const bvh = lights.bvh!;
      area = bvh.primArea[bvh.primOf(l, out.triangle)];
      mesh.sampleTriangle(out.triangle, u0, u1, ms);
    } else mesh.sample(u0, u1, ms);
    out.triangle = ms.triangle;
    out.b1 = ms.b1;
    out.b2 = ms.b2;
    return finishAreaSample(
      x,
      y,
      z,
      ms.px,
      ms.py,
      ms.pz,
      ms.nx,
      ms.ny,
      ms.nz,
      area,
      choose,
      lift,
      out,
    );
  }
  if (kind === LIGHT_ENVIRONMENT) {
    const es = lights.envSample;
    if (!lights.environment!.sample(u0, u1, es)) return false;
    out.wx = es.wx;
    out.wy = es.wy;
    out.wz = es.wz;
    out.distance = Infinity;
    out.pdf = choose * es.pdf;
    out.r = es.r;
    out.g = es.g;
    out.b = es.b;
    return true;
  }
  if (kind === SHAPE_QUAD) {
    const o = s * QUAD_STRIDE;
    const px = quads[o + Q_CORNER] + u0 * quads[o + Q_U] + u1 * quads[o + Q_V];
    const py = quads[o + Q_CORNER + 1] + u0 * quads[o + Q_U + 1] + u1 * quads[o + Q_V + 1];
    const pz = quads[o + Q_CORNER + 2] + u0 * quads[o + Q_U + 2] + u1 * quads[o + Q_V + 2];
    return finishAreaSample(
      x,
      y,
      z,
      px,
      py,
      pz,
      quads[o + Q_NORMAL],
      quads[o + Q_NORMAL + 1],
      quads[o + Q_NORMAL + 2],
      quads[o + Q_AREA],
      choose,
      lift,
      out,
    );
  }
  if (kind >= LIGHT_POINT) return samplePunctual(lights.punctual, s, kind, choose, out);
  const o = s * SPHERE_STRIDE;
  const cx = spheres[o];
  const cy = spheres[o + 1];
  const cz = spheres[o + 2];
  const r = spheres[o + 3];
  let wcx = cx - x;
  let wcy = cy - y;
  let wcz = cz - z;
  const dc2 = wcx * wcx + wcy * wcy + wcz * wcz;
  // Points on the sphere itself (which rounding may put just outside) count
  // as inside: the tangent plane hides the whole emitting side from them.
  if (dc2 <= r * r * (1 + 1e-9)) {
    // Inside: uniform by area. The emitting side faces away from every
    // interior point, so finishAreaSample finds cosθ ≤ 0 and returns false.
    const zz = 1 - 2 * u0;
    const rr = Math.sqrt(Math.max(0, 1 - zz * zz));
    const phi = 2 * Math.PI * u1;
    const nx = rr * Math.cos(phi);
    const ny = rr * Math.sin(phi);
    return finishAreaSample(
      x,
      y,
      z,
      cx + r * nx,
      cy + r * ny,
      cz + r * zz,
      nx,
      ny,
      zz,
      4 * Math.PI * r * r,
      choose,
      lift,
      out,
    );
  }
  // Outside: uniform in the cone of directions the sphere subtends, then the
  // point on the sphere seen along that direction (pbr-book 4e §6.2.4).
  const dc = Math.sqrt(dc2);
  const inv = 1 / dc;
  wcx *= inv;
  wcy *= inv;
  wcz *= inv;
  const sin2Max = (r * r) / dc2;
  const sinMax = r / dc;
  const cosMax = Math.sqrt(Math.max(0, 1 - sin2Max));
  // 1 − cosθmax without cancellation for small, distant spheres.
  const oneMinusCosMax = sin2Max / (1 + cosMax);
  // Uniform in solid angle means 1 − cosθ uniform in [0, 1 − cosθmax]; keep
  // 1 − cosθ itself so sin²θ = (1 − cosθ)(1 + cosθ) stays exact for tiny
  // cones (where cosθ rounds to 1). Exact at every size, so sampling and
  // pdf agree to rounding.
  const oneMinusCos = u0 * oneMinusCosMax;
  const cosT = 1 - oneMinusCos;
  const sin2 = oneMinusCos * (2 - oneMinusCos);
  // Angle α at the sphere's center between the reference direction and the
  // sampled point, in the form that does not cancel (pbr-book 4e eq. 6.8,
  // instead of the law of cosines, which loses digits when r ≪ distance).
  const cosAlpha = Math.min(1, sin2 / sinMax + cosT * Math.sqrt(Math.max(0, 1 - sin2 / sin2Max)));
  const sinAlpha = Math.sqrt(Math.max(0, 1 - cosAlpha * cosAlpha));
  const phi = 2 * Math.PI * u1;
  // Frame around −wc (from the center toward the reference point).
  const ax = -wcx;
  const ay = -wcy;
  const az = -wcz;
  const sign = az >= 0 ? 1 : -1;
  const a = -1 / (sign + az);
  const b = ax * ay * a;
  const s1x = 1 + sign * ax * ax * a;
  const s1y = sign * b;
  const s1z = -sign * ax;
  const t1x = b;
  const t1y = sign + ay * ay * a;
  const t1z = -ay;
  const cp = Math.cos(phi) * sinAlpha;
  const sp = Math.sin(phi) * sinAlpha;
  let nx = cp * s1x + sp * t1x + cosAlpha * ax;
  let ny = cp * s1y + sp * t1y + cosAlpha * ay;
  let nz = cp * s1z + sp * t1z + cosAlpha * az;
  const nInv = 1 / Math.sqrt(nx * nx + ny * ny + nz * nz);
  nx *= nInv;
  ny *= nInv;
  nz *= nInv;
  const px = cx + r * nx;
  const py = cy + r * ny;
  const pz = cz + r * nz;
  let wx = px - x;
  let wy = py - y;
  let wz = pz - z;
  const dist = Math.sqrt(wx * wx + wy * wy + wz * wz);
  if (!(dist > 0)) return false;
  wx /= dist;
  wy /= dist;
  wz /= dist;
  // From outside the cone only reaches the emitting front side; guard the
  // silhouette against rounding.
  if (nx * wx + ny * wy + nz * wz >= 0) return false;
  out.wx = wx;
  out.wy = wy;
  out.wz = wz;
  out.distance = dist;
  out.px = px + lift * nx;
  out.py = py + lift * ny;
  out.pz = pz + lift * nz;
  out.pdf = choose / (2 * Math.PI * oneMinusCosMax);
  return true;
}

function finishAreaSample(
  x: number,
  y: number,
  z: number,
  px: number,
  py: number,
  pz: number,
  nx: number,
  ny: number,
  nz: number,
  area: number,
  choose: number,
  lift: number,
  out: LightSample,
): boolean {
  let wx = px - x;
  let wy = py - y;
  let wz = pz - z;
  const d2 = wx * wx + wy * wy + wz * wz;
  if (!(d2 > 0)) return false;
  const dist = Math.sqrt(d2);
  wx /= dist;
  wy /= dist;
  wz /= dist;
  const cosLight = -(nx * wx + ny * wy + nz * wz);
  if (cosLight <= 0) return false;
  out.wx = wx;
  out.wy = wy;
  out.wz = wz;
  out.distance = dist;
  // The reference point is on the front side (cosLight > 0): lift toward it.
  out.px = px + lift * nx;
  out.py = py + lift * ny;
  out.pz = pz + lift * nz;
  const pdf = (choose * d2) / (area * cosLight);
  // A light of tiny area (a quad of area 1e-320, say: valid, but area·cos underflows) has
  // a pdf that overflows; its sample's contribution, proportional to 1/pdf, is 0. Without
  // this, Inf/Inf turns it into a NaN sample (then rejected by the film, but lost).
  if (!(pdf < Infinity)) return false;
  out.pdf = pdf;
  return true;
}
