/**
 * Shapes compiled into flat Float64Arrays (flatbush-style), one record per
 * shape, so intersection loops read numbers, not objects.
 */
import type { QuadDesc, SphereDesc } from '../scene/format/types.ts';

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
  shapes.forEach((q, i) => writeQuadRecord(q.corner, q.u, q.v, out, i * QUAD_STRIDE));
  return out;
}

/**
 * Writes the record of the quad (corner, u, v) at `out[o…o+QUAD_STRIDE)` and returns its
 * area |u × v|. The loader calls it too, and rejects a quad whose record is not finite or
 * whose area is 0 (docs/scene-format.md: "non-zero area when computed in double
 * precision, with a finite unit normal").
 *
 * Computed robustly: u and v are first divided by their largest component, so the cross
 * product of the scaled edges neither underflows (u = [1e-200, 0, 0]) nor overflows; the
 * scale comes back only in the area, and in the two axes as
 *   v × w = (v' × n) / (|u' × v'| · max|u|),   w × u = (n × u') / (|u' × v'| · max|v|),
 * with u' = u / max|u|, v' = v / max|v| and w = n / |u × v|.
 */
export function writeQuadRecord(
  corner: readonly number[],
  u: readonly number[],
  v: readonly number[],
  out: Float64Array,
  o: number,
): number {
  const su = Math.max(Math.abs(u[0]), Math.abs(u[1]), Math.abs(u[2]));
  const sv = Math.max(Math.abs(v[0]), Math.abs(v[1]), Math.abs(v[2]));
  const ux = u[0] / su;
  const uy = u[1] / su;
  const uz = u[2] / su;
  const vx = v[0] / sv;
  const vy = v[1] / sv;
  const vz = v[2] / sv;
  const cx = uy * vz - uz * vy;
  const cy = uz * vx - ux * vz;
  const cz = ux * vy - uy * vx;
  // |u' × v'| <= 2, so hypot of the scaled product is exact enough and never overflows.
  const len = Math.hypot(cx, cy, cz);
  const area = len * su * sv;
  const nx = cx / len;
  const ny = cy / len;
  const nz = cz / len;
  out[o + Q_CORNER] = corner[0];
  out[o + Q_CORNER + 1] = corner[1];
  out[o + Q_CORNER + 2] = corner[2];
  out[o + Q_U] = u[0];
  out[o + Q_U + 1] = u[1];
  out[o + Q_U + 2] = u[2];
  out[o + Q_V] = v[0];
  out[o + Q_V + 1] = v[1];
  out[o + Q_V + 2] = v[2];
  out[o + Q_NORMAL] = nx;
  out[o + Q_NORMAL + 1] = ny;
  out[o + Q_NORMAL + 2] = nz;
  out[o + Q_PLANE] = nx * corner[0] + ny * corner[1] + nz * corner[2];
  // v × w
  const ks = 1 / (len * su);
  out[o + Q_SAXIS] = (vy * nz - vz * ny) * ks;
  out[o + Q_SAXIS + 1] = (vz * nx - vx * nz) * ks;
  out[o + Q_SAXIS + 2] = (vx * ny - vy * nx) * ks;
  // w × u
  const kt = 1 / (len * sv);
  out[o + Q_TAXIS] = (ny * uz - nz * uy) * kt;
  out[o + Q_TAXIS + 1] = (nz * ux - nx * uz) * kt;
  out[o + Q_TAXIS + 2] = (nx * uy - ny * ux) * kt;
  out[o + Q_AREA] = area;
  return area;
}
