/**
 * Shapes compiled into flat Float64Arrays (flatbush-style), one record per
 * shape, so intersection loops read numbers, not objects.
 */
import type { QuadDesc, SphereDesc } from '../scene/types.ts';

/** Sphere record: center x, y, z and radius. */
export const SPHERE_STRIDE = 4;

/**
 * Quad record. With n the unit normal and w = n / |u × v|, a point p of the
 * plane has parallelogram coordinates s = (p − corner)·(v × w) and
 * t = (p − corner)·(w × u) (Shirley, "Ray Tracing: The Next Week" §6), so the
 * two cross products are stored ready-made.
 */
export const QUAD_STRIDE = 20;
export const Q_CORNER = 0;
export const Q_U = 3;
export const Q_V = 6;
export const Q_NORMAL = 9;
/** plane offset: n · corner */
export const Q_PLANE = 12;
/** v × w */
export const Q_SAXIS = 13;
/** w × u */
export const Q_TAXIS = 16;
export const Q_AREA = 19;

/**
 * Relative size of the offset that lifts a spawned ray off its surface:
 * 2^-36 of the magnitude of the coordinates involved. Doubles carry 2^-52
 * relative error, so this clears the rounding of a hit point by a factor of
 * ~65,000 while staying far below any visible scale — and, being relative,
 * it behaves the same for a scene scaled by 1e-4 or 1e4.
 */
export const OFFSET_SCALE = 2 ** -36;

/** Magnitude of a sphere's coordinates, for OFFSET_SCALE. */
export function sphereScale(spheres: Float64Array, i: number): number {
  const o = i * SPHERE_STRIDE;
  return (
    Math.max(Math.abs(spheres[o]), Math.abs(spheres[o + 1]), Math.abs(spheres[o + 2])) +
    spheres[o + 3]
  );
}

/** Magnitude of a quad's coordinates (corner plus both edges), for OFFSET_SCALE. */
export function quadScale(quads: Float64Array, i: number): number {
  const o = i * QUAD_STRIDE;
  return (
    Math.max(
      Math.abs(quads[o + Q_CORNER]),
      Math.abs(quads[o + Q_CORNER + 1]),
      Math.abs(quads[o + Q_CORNER + 2]),
    ) +
    Math.max(Math.abs(quads[o + Q_U]), Math.abs(quads[o + Q_U + 1]), Math.abs(quads[o + Q_U + 2])) +
    Math.max(Math.abs(quads[o + Q_V]), Math.abs(quads[o + Q_V + 1]), Math.abs(quads[o + Q_V + 2]))
  );
}

export function compileSpheres(shapes: SphereDesc[]): Float64Array {
  const out = new Float64Array(shapes.length * SPHERE_STRIDE);
  shapes.forEach((s, i) => {
    out.set([s.center[0], s.center[1], s.center[2], s.radius], i * SPHERE_STRIDE);
  });
  return out;
}

export function compileQuads(shapes: QuadDesc[]): Float64Array {
  const out = new Float64Array(shapes.length * QUAD_STRIDE);
  shapes.forEach((q, i) => {
    const [ux, uy, uz] = q.u;
    const [vx, vy, vz] = q.v;
    const cx = uy * vz - uz * vy;
    const cy = uz * vx - ux * vz;
    const cz = ux * vy - uy * vx;
    const area = Math.hypot(cx, cy, cz);
    const nx = cx / area;
    const ny = cy / area;
    const nz = cz / area;
    const wx = nx / area;
    const wy = ny / area;
    const wz = nz / area;
    const o = i * QUAD_STRIDE;
    out.set(q.corner, o + Q_CORNER);
    out.set(q.u, o + Q_U);
    out.set(q.v, o + Q_V);
    out[o + Q_NORMAL] = nx;
    out[o + Q_NORMAL + 1] = ny;
    out[o + Q_NORMAL + 2] = nz;
    out[o + Q_PLANE] = nx * q.corner[0] + ny * q.corner[1] + nz * q.corner[2];
    // v × w
    out[o + Q_SAXIS] = vy * wz - vz * wy;
    out[o + Q_SAXIS + 1] = vz * wx - vx * wz;
    out[o + Q_SAXIS + 2] = vx * wy - vy * wx;
    // w × u
    out[o + Q_TAXIS] = wy * uz - wz * uy;
    out[o + Q_TAXIS + 1] = wz * ux - wx * uz;
    out[o + Q_TAXIS + 2] = wx * uy - wy * ux;
    out[o + Q_AREA] = area;
  });
  return out;
}
