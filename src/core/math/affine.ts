/**
 * Affine transforms of meshes: a row-major 4×4 matrix whose last row is 0 0 0 1
 * (docs/scene-format.md, Meshes). Points map by the matrix, normals by its inverse
 * transpose (pbr-book 4e §3.10.3), which for the upper 3×3 block A is cof(A) / det(A);
 * normals are renormalised afterwards, so only the cofactor matrix and the sign of the
 * determinant are needed, and no division by a tiny determinant can overflow.
 */

/**
 * The cofactor matrix C of the 3×3 matrix with rows (a b c), (d e f), (g h i), row by
 * row: Cᵀ / det is its inverse, so C / det is its inverse transpose. Both normal
 * matrices (this file's, row-major scene transforms; gltf/transforms.ts, column-major
 * node matrices) take it from here.
 */
export function cofactors3(
  a: number,
  b: number,
  c: number,
  d: number,
  e: number,
  f: number,
  g: number,
  h: number,
  i: number,
): Float64Array {
  return Float64Array.of(
    e * i - f * h,
    -(d * i - f * g),
    d * h - e * g,
    -(b * i - c * h),
    a * i - c * g,
    -(a * h - b * g),
    b * f - c * e,
    -(a * f - c * d),
    a * e - b * d,
  );
}

/** Why `m` is not an acceptable transform, or undefined if it is. */
export function transformProblem(m: ArrayLike<number>): string | undefined {
  if (m[12] !== 0 || m[13] !== 0 || m[14] !== 0 || m[15] !== 1) {
    return `its last row must be 0 0 0 1, got ${m[12]} ${m[13]} ${m[14]} ${m[15]}`;
  }
  // Invertibility, independent of scale: scale each row of the 3×3 block to a largest
  // entry of 1 (which keeps the rank) and ask for a determinant clearly above rounding.
  const rows: number[] = [];
  for (let r = 0; r < 3; r++) {
    const a = m[r * 4],
      b = m[r * 4 + 1],
      c = m[r * 4 + 2];
    const s = Math.max(Math.abs(a), Math.abs(b), Math.abs(c));
    if (s === 0) return `it is not invertible (row ${r + 1} of its 3×3 part is zero)`;
    rows.push(a / s, b / s, c / s);
  }
  const det = det3(rows, 0);
  if (!(Math.abs(det) > 1e-12)) {
    return 'it is not invertible (its 3×3 part is singular)';
  }
  return undefined;
}

function det3(m: ArrayLike<number>, o: number): number {
  return (
    m[o] * (m[o + 4] * m[o + 8] - m[o + 5] * m[o + 7]) -
    m[o + 1] * (m[o + 3] * m[o + 8] - m[o + 5] * m[o + 6]) +
    m[o + 2] * (m[o + 3] * m[o + 7] - m[o + 4] * m[o + 6])
  );
}

/** Applies the affine transform `m` to every point of `xyz` in place. */
export function transformPoints(m: ArrayLike<number>, xyz: Float64Array): void {
  const m00 = m[0],
    m01 = m[1],
    m02 = m[2],
    m03 = m[3];
  const m10 = m[4],
    m11 = m[5],
    m12 = m[6],
    m13 = m[7];
  const m20 = m[8],
    m21 = m[9],
    m22 = m[10],
    m23 = m[11];
  for (let i = 0, n = xyz.length; i < n; i += 3) {
    const x = xyz[i],
      y = xyz[i + 1],
      z = xyz[i + 2];
    xyz[i] = m00 * x + m01 * y + m02 * z + m03;
    xyz[i + 1] = m10 * x + m11 * y + m12 * z + m13;
    xyz[i + 2] = m20 * x + m21 * y + m22 * z + m23;
  }
}

/**
 * The matrix that maps normals (up to a positive factor): the cofactor matrix of the
 * 3×3 block times the sign of its determinant, i.e. the inverse transpose times |det|.
 * Returned row-major, 9 numbers.
 */
export function normalMatrix(m: ArrayLike<number>): Float64Array {
  // A uniform scale changes neither the direction of normals nor the sign of the
  // determinant; scaling to a largest entry of 1 keeps the cofactors' products in range.
  let s0 = 0;
  for (const k of [0, 1, 2, 4, 5, 6, 8, 9, 10]) s0 = Math.max(s0, Math.abs(m[k]));
  const a = m[0] / s0,
    b = m[1] / s0,
    c = m[2] / s0;
  const d = m[4] / s0,
    e = m[5] / s0,
    f = m[6] / s0;
  const g = m[8] / s0,
    h = m[9] / s0,
    i = m[10] / s0;
  // Cofactors C[r][c] of A; (A⁻¹)ᵀ = C / det.
  const cof = cofactors3(a, b, c, d, e, f, g, h, i);
  const det = a * cof[0] + b * cof[1] + c * cof[2];
  if (det < 0) for (let k = 0; k < 9; k++) cof[k] = -cof[k];
  // Normals are renormalised; a largest entry of 1 keeps them away from underflow.
  let s = 0;
  for (let k = 0; k < 9; k++) s = Math.max(s, Math.abs(cof[k]));
  if (s > 0) for (let k = 0; k < 9; k++) cof[k] /= s;
  return cof;
}
