/**
 * Closed-form answers for the known-answer tests (analytic.test.ts).
 *
 * - A uniform spherical emitter of radiance L whose whole body is above a
 *   receiver's tangent plane gives the irradiance E = π L (r/ℓ)² cosθ, ℓ
 *   the distance to its centre and θ the centre's angle off the normal
 *   (seen from outside, it acts as a point source of intensity π r² L at
 *   its centre: the classic sphere-to-tilted-element form factor). Over
 *   its normal (θ = 0) that is π L (r/d)²; a Lambertian receiver of albedo
 *   ρ then reflects ρ L (r/d)².
 * - A uniform polygonal emitter gives E = (L/2) Σᵢ γᵢ (n · ĉᵢ) with γᵢ the
 *   angle its edge i subtends and ĉᵢ the unit normal of the plane through
 *   the receiver and that edge (Lambert 1760; the "polygon" or
 *   contour-integral form factor: Baum, Rushmeier & Winget 1989; Arvo
 *   1995), exact when the whole polygon is above the horizon.
 */
import { cross, dot, length, sub, type Vec3 } from './vec.ts';

/** Irradiance at `p` (unit normal `n`) from a sphere light fully above p's horizon. */
export function sphereIrradiance(
  p: Vec3,
  n: Vec3,
  center: Vec3,
  radius: number,
  L: number,
): number {
  const w = sub(center, p);
  const l = length(w);
  const cosTheta = dot(w, n) / l;
  if (!(l > radius) || l * cosTheta < radius) {
    throw new Error('sphereIrradiance: the sphere must lie wholly above the horizon');
  }
  return Math.PI * L * (radius / l) ** 2 * cosTheta;
}

/**
 * Irradiance at `p` (unit normal `n`) from a convex polygon of radiance L
 * whose vertices are all on the side n points to. The angle of each edge
 * is atan2(|a × b|, a · b): accurate for the tiny angles of a polygon seen
 * edge-on, where acos(a · b) loses half the digits.
 */
export function polygonIrradiance(p: Vec3, n: Vec3, vertices: Vec3[], L: number): number {
  let sum = 0;
  for (let i = 0; i < vertices.length; i++) {
    const a = sub(vertices[i], p);
    const b = sub(vertices[(i + 1) % vertices.length], p);
    if (dot(a, n) < 0 || dot(b, n) < 0) {
      throw new Error('polygonIrradiance: the polygon must lie wholly above the horizon');
    }
    const c = cross(a, b);
    const s = length(c);
    if (s === 0) continue;
    const gamma = Math.atan2(s, dot(a, b));
    sum += (gamma * dot(c, n)) / s;
  }
  // The sign follows the winding as seen from p; the magnitude is the answer.
  return (L / 2) * Math.abs(sum);
}

/** The four corners of the quad corner + s·u + t·v in order around it. */
export function quadVertices(corner: Vec3, u: Vec3, v: Vec3): Vec3[] {
  const add = (x: Vec3, y: Vec3): Vec3 => [x[0] + y[0], x[1] + y[1], x[2] + y[2]];
  return [corner, add(corner, u), add(add(corner, u), v), add(corner, v)];
}

/** Area of a simple polygon in the plane (shoelace). */
export function polygonArea(points: [number, number][]): number {
  let a = 0;
  for (let i = 0; i < points.length; i++) {
    const [x0, y0] = points[i];
    const [x1, y1] = points[(i + 1) % points.length];
    a += x0 * y1 - x1 * y0;
  }
  return Math.abs(a) / 2;
}
