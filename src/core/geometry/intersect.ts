/**
 * Ray–shape intersection without any fixed absolute epsilon.
 *
 * Spheres use the numerically robust quadratic of Haines et al. ("Precision
 * Improvements for Ray/Sphere Intersection", Ray Tracing Gems 2019, ch. 7):
 * the discriminant is r² − |f − (f·d)d|², which does not cancel
 * catastrophically for huge spheres or distant origins, and the two roots
 * come from the stable pair c/q, q. Quads intersect their plane and test
 * the parallelogram coordinates. A ray parallel to a quad (n·d = 0) misses
 * it outright rather than producing ±Inf or NaN.
 *
 * Self-intersection is avoided where rays are *spawned* (see spawn.ts), by
 * an offset relative to the magnitude of the hit point, so `tMin` is 0.
 */
import {
  QUAD_STRIDE,
  Q_CORNER,
  Q_NORMAL,
  Q_PLANE,
  Q_SAXIS,
  Q_TAXIS,
  SPHERE_STRIDE,
} from './shapes.ts';
import { mulPow2 } from './exact.ts';

/** Distance to the nearest hit of sphere i in (0, tMax), or Infinity. */
export function intersectSphere(
  spheres: Float64Array,
  i: number,
  ox: number,
  oy: number,
  oz: number,
  dx: number,
  dy: number,
  dz: number,
  tMax: number,
): number {
  const o = i * SPHERE_STRIDE;
  const r = spheres[o + 3];
  if (!(r < SPHERE_HUGE && r > SPHERE_TINY)) {
    return intersectSphereScaled(spheres, i, ox, oy, oz, dx, dy, dz, tMax);
  }
  const fx = ox - spheres[o];
  const fy = oy - spheres[o + 1];
  const fz = oz - spheres[o + 2];
  const b = fx * dx + fy * dy + fz * dz;
  const lx = fx - b * dx;
  const ly = fy - b * dy;
  const lz = fz - b * dz;
  const disc = r * r - (lx * lx + ly * ly + lz * lz);
  if (disc < 0) return Infinity;
  const c = fx * fx + fy * fy + fz * fz - r * r;
  const q = b > 0 ? -b - Math.sqrt(disc) : -b + Math.sqrt(disc);
  let t0 = c / q;
  let t1 = q;
  if (t0 > t1) {
    const tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  if (t0 > 0 && t0 < tMax) return t0;
  if (t1 > 0 && t1 < tMax) return t1;
  return Infinity;
}

/**
 * Radii outside [2^-400, 2^400] take intersectSphereScaled: r² and |f|² would over- or
 * underflow (a sphere of radius 2^1000 was missed by every ray, one of 2^-600 hit by
 * every ray that came near).
 */
export const SPHERE_HUGE = 2 ** 400;
export const SPHERE_TINY = 2 ** -400;

/**
 * intersectSphere for a radius beyond 2^±400: the same quadratic on the origin offset
 * and radius scaled by a power of two (exact) to a largest magnitude near 1, and the
 * roots scaled back. A tiny sphere far from the origin is left unscaled: it is below
 * the offset's rounding, and misses as it should.
 */
export function intersectSphereScaled(
  spheres: Float64Array,
  i: number,
  ox: number,
  oy: number,
  oz: number,
  dx: number,
  dy: number,
  dz: number,
  tMax: number,
): number {
  const o = i * SPHERE_STRIDE;
  let r = spheres[o + 3];
  let fx = ox - spheres[o];
  let fy = oy - spheres[o + 1];
  let fz = oz - spheres[o + 2];
  const m = Math.max(r, Math.abs(fx), Math.abs(fy), Math.abs(fz));
  const e = m > SPHERE_HUGE || m < SPHERE_TINY ? Math.floor(Math.log2(m)) : 0;
  r = mulPow2(r, -e);
  fx = mulPow2(fx, -e);
  fy = mulPow2(fy, -e);
  fz = mulPow2(fz, -e);
  const b = fx * dx + fy * dy + fz * dz;
  const lx = fx - b * dx;
  const ly = fy - b * dy;
  const lz = fz - b * dz;
  const disc = r * r - (lx * lx + ly * ly + lz * lz);
  if (disc < 0) return Infinity;
  const c = fx * fx + fy * fy + fz * fz - r * r;
  const q = b > 0 ? -b - Math.sqrt(disc) : -b + Math.sqrt(disc);
  let t0 = mulPow2(c / q, e);
  let t1 = mulPow2(q, e);
  if (t0 > t1) {
    const tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  if (t0 > 0 && t0 < tMax) return t0;
  if (t1 > 0 && t1 < tMax) return t1;
  return Infinity;
}

/** Distance to quad i in (0, tMax), or Infinity (also for rays parallel to it). */
export function intersectQuad(
  quads: Float64Array,
  i: number,
  ox: number,
  oy: number,
  oz: number,
  dx: number,
  dy: number,
  dz: number,
  tMax: number,
): number {
  const o = i * QUAD_STRIDE;
  const nx = quads[o + Q_NORMAL];
  const ny = quads[o + Q_NORMAL + 1];
  const nz = quads[o + Q_NORMAL + 2];
  const t = (quads[o + Q_PLANE] - (nx * ox + ny * oy + nz * oz)) / (nx * dx + ny * dy + nz * dz);
  if (!(t > 0 && t < tMax)) return Infinity;
  const qx = ox + t * dx - quads[o + Q_CORNER];
  const qy = oy + t * dy - quads[o + Q_CORNER + 1];
  const qz = oz + t * dz - quads[o + Q_CORNER + 2];
  const s = qx * quads[o + Q_SAXIS] + qy * quads[o + Q_SAXIS + 1] + qz * quads[o + Q_SAXIS + 2];
  const v = qx * quads[o + Q_TAXIS] + qy * quads[o + Q_TAXIS + 1] + qz * quads[o + Q_TAXIS + 2];
  // One branch instead of six: the comparisons are combined as bits.
  const ok = Number(s >= 0) & Number(s <= 1) & Number(v >= 0) & Number(v <= 1);
  return ok !== 0 ? t : Infinity;
}

/** If sphere i lies on the ray before r[R_T], moves r[R_T] to the hit and returns true. */
export function hitSphere(spheres: Float64Array, i: number, r: Float64Array): boolean {
  const t = intersectSphere(spheres, i, r[0], r[1], r[2], r[3], r[4], r[5], r[6]);
  if (t < r[6]) {
    r[6] = t;
    return true;
  }
  return false;
}

/** If quad i lies on the ray before r[R_T], moves r[R_T] to the hit and returns true. */
export function hitQuad(quads: Float64Array, i: number, r: Float64Array): boolean {
  const t = intersectQuad(quads, i, r[0], r[1], r[2], r[3], r[4], r[5], r[6]);
  if (t < r[6]) {
    r[6] = t;
    return true;
  }
  return false;
}
