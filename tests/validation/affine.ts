/**
 * Row-major 4×4 affine matrices (last row 0 0 0 1), as the scene format's mesh
 * `transform` has them, for the generator's meshes: x' = A x + t.
 */
import { rotate, type Similarity, type Vec3 } from './vec.ts';

export type Matrix = number[];

export const IDENTITY: Matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];

/** A · B. */
export function compose(a: Matrix, b: Matrix): Matrix {
  const out = new Array<number>(16).fill(0);
  for (let i = 0; i < 4; i++) {
    for (let j = 0; j < 4; j++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += a[4 * i + k] * b[4 * k + j];
      out[4 * i + j] = s;
    }
  }
  // Exact last row whatever the rounding.
  out[12] = out[13] = out[14] = 0;
  out[15] = 1;
  return out;
}

/** x ↦ R(axis, angle) · diag(scale) · x + translation. */
export function trs(translation: Vec3, axis: Vec3, angle: number, scale: Vec3): Matrix {
  const cols = [0, 1, 2].map((k) => {
    const e: Vec3 = [0, 0, 0];
    e[k] = scale[k];
    return rotate(e, axis, angle);
  });
  return [
    cols[0][0],
    cols[1][0],
    cols[2][0],
    translation[0],
    cols[0][1],
    cols[1][1],
    cols[2][1],
    translation[1],
    cols[0][2],
    cols[1][2],
    cols[2][2],
    translation[2],
    0,
    0,
    0,
    1,
  ];
}

/** The similarity as a matrix. */
export function similarityMatrix(sim: Similarity): Matrix {
  return trs(sim.offset, sim.axis, sim.angle, [sim.scale, sim.scale, sim.scale]);
}

export function applyPoint(m: Matrix, p: Vec3): Vec3 {
  return [0, 1, 2].map(
    (i) => m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3],
  ) as Vec3;
}

/** Determinant of the linear part (negative: the transform mirrors). */
export function determinant(m: Matrix): number {
  return (
    m[0] * (m[5] * m[10] - m[6] * m[9]) -
    m[1] * (m[4] * m[10] - m[6] * m[8]) +
    m[2] * (m[4] * m[9] - m[5] * m[8])
  );
}

/** Every position of a flat array mapped by m (a fresh array). */
export function transformPositions(m: Matrix, positions: readonly number[]): number[] {
  const out = new Array<number>(positions.length);
  for (let i = 0; i < positions.length; i += 3) {
    const p = applyPoint(m, [positions[i], positions[i + 1], positions[i + 2]]);
    out[i] = p[0];
    out[i + 1] = p[1];
    out[i + 2] = p[2];
  }
  return out;
}

/** The inverse transpose of the linear part, row-major 3×3: maps normals. */
export function normalMatrix(m: Matrix): number[] {
  const [a, b, c, , d, e, f, , g, h, i] = m;
  const det = determinant(m);
  // inverse = adjugate / det; its transpose is the cofactor matrix / det.
  return [
    (e * i - f * h) / det,
    (f * g - d * i) / det,
    (d * h - e * g) / det,
    (c * h - b * i) / det,
    (a * i - c * g) / det,
    (b * g - a * h) / det,
    (b * f - c * e) / det,
    (c * d - a * f) / det,
    (a * e - b * d) / det,
  ];
}

/** Normals mapped by the normal matrix and normalised (a fresh array). */
export function transformNormals(m: Matrix, normals: readonly number[]): number[] {
  const n = normalMatrix(m);
  const out = new Array<number>(normals.length);
  for (let k = 0; k < normals.length; k += 3) {
    const [x, y, z] = [normals[k], normals[k + 1], normals[k + 2]];
    const tx = n[0] * x + n[1] * y + n[2] * z;
    const ty = n[3] * x + n[4] * y + n[5] * z;
    const tz = n[6] * x + n[7] * y + n[8] * z;
    const l = Math.hypot(tx, ty, tz);
    out[k] = tx / l;
    out[k + 1] = ty / l;
    out[k + 2] = tz / l;
  }
  return out;
}
