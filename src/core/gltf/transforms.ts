/**
 * The 4×4 affine transforms of the node hierarchy, column-major as glTF
 * stores them (glTF 2.0 §3.5.3): a node's local matrix is its `matrix`, or
 * T · R · S from `translation`, `rotation` (a unit quaternion x, y, z, w)
 * and `scale`; a world matrix is the product of the local matrices from the
 * root down. Read from the JSON itself so that a matrix is used exactly as
 * written.
 */
import { cofactors3 } from '../math/affine.ts';

export type Mat4 = Float64Array;

export function identity(): Mat4 {
  const m = new Float64Array(16);
  m[0] = m[5] = m[10] = m[15] = 1;
  return m;
}

/** a · b (column-major). */
export function multiply(a: Mat4, b: Mat4): Mat4 {
  const out = new Float64Array(16);
  for (let c = 0; c < 4; c++) {
    for (let r = 0; r < 4; r++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
      out[c * 4 + r] = s;
    }
  }
  return out;
}

/** The local matrix of a node of the (validated) JSON. */
export function nodeMatrix(node: Record<string, unknown>): Mat4 {
  if (Array.isArray(node.matrix)) return Float64Array.from(node.matrix as number[]);
  const [tx, ty, tz] = (node.translation as number[] | undefined) ?? [0, 0, 0];
  let [x, y, z, w] = (node.rotation as number[] | undefined) ?? [0, 0, 0, 1];
  const [sx, sy, sz] = (node.scale as number[] | undefined) ?? [1, 1, 1];
  // Quaternions must be unit; normalise what rounding (or a sloppy writer) left.
  const l = Math.hypot(x, y, z, w);
  if (l > 0) {
    x /= l;
    y /= l;
    z /= l;
    w /= l;
  } else w = 1;
  const m = new Float64Array(16);
  m[0] = (1 - 2 * (y * y + z * z)) * sx;
  m[1] = 2 * (x * y + z * w) * sx;
  m[2] = 2 * (x * z - y * w) * sx;
  m[4] = 2 * (x * y - z * w) * sy;
  m[5] = (1 - 2 * (x * x + z * z)) * sy;
  m[6] = 2 * (y * z + x * w) * sy;
  m[8] = 2 * (x * z + y * w) * sz;
  m[9] = 2 * (y * z - x * w) * sz;
  m[10] = (1 - 2 * (x * x + y * y)) * sz;
  m[12] = tx;
  m[13] = ty;
  m[14] = tz;
  m[15] = 1;
  return m;
}

/** A row-major 4×4 of the scene format (16 numbers) as a column-major Mat4. */
export function fromRowMajor(rows: number[]): Mat4 {
  const m = new Float64Array(16);
  for (let r = 0; r < 4; r++) for (let c = 0; c < 4; c++) m[c * 4 + r] = rows[r * 4 + c];
  return m;
}

/** Determinant of the upper 3×3 (its sign tells whether the transform mirrors). */
export function det3(m: Mat4): number {
  return (
    m[0] * (m[5] * m[10] - m[9] * m[6]) -
    m[4] * (m[1] * m[10] - m[9] * m[2]) +
    m[8] * (m[1] * m[6] - m[5] * m[2])
  );
}

/**
 * The normal matrix: the inverse transpose of the upper 3×3, as 9 numbers,
 * column-major (pbr-book 4e §3.10.1). Its scale is irrelevant (normals are
 * renormalised), so the cofactor matrix (det · inverse transpose) is used,
 * times the sign of det, and no division can fail.
 */
export function normalMatrix(m: Mat4): Float64Array {
  // A uniform scale changes neither the direction of normals nor the sign of the
  // determinant; a largest entry of 1 keeps the cofactors' products in range (a matrix
  // of diag(1e308) has cofactors of 1e616 otherwise, and every normal would be Infinity).
  let s0 = 0;
  for (const k of [0, 1, 2, 4, 5, 6, 8, 9, 10]) s0 = Math.max(s0, Math.abs(m[k]));
  if (!(s0 > 0)) s0 = 1;
  const a = m[0] / s0,
    b = m[4] / s0,
    c = m[8] / s0;
  const d = m[1] / s0,
    e = m[5] / s0,
    f = m[9] / s0;
  const g = m[2] / s0,
    h = m[6] / s0,
    i = m[10] / s0;
  const s = det3(m) < 0 ? -1 : 1;
  // Cofactor matrix of the 3×3 (= det · inverse transpose). cofactors3 gives it row by
  // row; the callers read it column-major (out[3 * col + row]), so it is transposed here.
  // (It was not until the instancing work compared copies with instances: a rotated node
  // turned its normals by the inverse rotation.)
  const c3 = cofactors3(a, b, c, d, e, f, g, h, i);
  const out = new Float64Array(9);
  for (let r = 0; r < 3; r++) for (let k = 0; k < 3; k++) out[3 * k + r] = c3[3 * r + k] * s;
  return out;
}
