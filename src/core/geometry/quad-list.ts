/**
 * The quads of a scene without a BVH (below BVH_THRESHOLD, e.g. the Cornell
 * box), regrouped for the plain loops of trace.ts: quads whose plane is
 * perpendicular to a coordinate axis get a short test, the rest keep the
 * general one of intersect.ts.
 *
 * Why: in a box-like scene most quads are axis-aligned (Cornell: 10 of 18,
 * walls, light, box tops and bottoms; the other 8, the box sides, are
 * vertical), and for them the general test spends
 * half its operations on exact zeros. With the normal n = ±e_a (its other two
 * components exactly ±0, which writeQuadRecord gives for edges in a
 * coordinate plane), the general test's
 *   t = (P − (n_x o_x + n_y o_y + n_z o_z)) / (n_x d_x + n_y d_y + n_z d_z)
 * is (P − n_a o_a) / (n_a d_a), and the a-components of the parallelogram
 * axes S = v × w and T = w × u are exactly ±0 too (each is a difference of
 * products with n's zero components), so s = q·S is q_b S_b + q_c S_c over
 * the two in-plane axes b < c. Dropping a term that is ±0 changes a sum at
 * most in the sign of a zero result, and every decision of the test (t > 0,
 * t < tMax, 0 ≤ s ≤ 1, 0 ≤ v ≤ 1) is the same for +0 and −0; where the
 * dropped zero meets an infinite t (a ray parallel to the plane), the t
 * tests reject in both forms (t = +∞ is never below tMax ≤ ∞). A dropped
 * product is ±0 and not NaN because its q component is finite whenever t is:
 * q_a = o_a + t d_a − c_a with t d_a = (P − n_a o_a)/n_a up to rounding, so
 * q_a is bounded by the scene's coordinates. So the short test accepts
 * exactly the hits of the general one, with the same t bit for bit (the
 * numerator and denominator of t are the same floating-point operations on
 * the same numbers whenever they are non-zero). Quads in a vertical plane
 * (VERTICAL_STRIDE) drop n_y o_y, n_y d_y and the zero components of S and
 * T in the same way; there a non-finite q_y or q_x, q_z makes the short s or
 * v infinite or NaN as well, so both forms reject.
 *
 * The groups change the order in which quads are tested, so ties in t are
 * resolved explicitly as the index-ordered loop resolved them: the quad with
 * the lowest index wins (tests/unit/core/quad-list.test.ts).
 *
 * The loops step through the records by literal strides (8, 9, 13: the
 * *_STRIDE constants below): in the bundle a module constant is a context
 * load, a Smi check and an overflow-checked multiply per quad, and the
 * literal steps made the Cornell rays' nearest-hit queries 8 % faster.
 */
import { Q_CORNER, Q_NORMAL, Q_PLANE, Q_SAXIS, Q_TAXIS, QUAD_STRIDE } from './shapes.ts';

/**
 * Record of an axis-aligned quad, a being its normal's axis and b < c the
 * other two: plane offset P, n_a, corner_b, corner_c, S_b, S_c, T_b, T_c.
 */
export const AXIS_STRIDE = 8;
/**
 * Record of a quad in a vertical plane (n_y exactly ±0, e.g. the sides of
 * the Cornell boxes) with one edge vertical: P, n_x, n_z, corner x, y, z,
 * then H_x, H_z of its horizontal parallelogram axis and V_y of its vertical
 * one (S and T, in either order: the test treats s and v alike).
 */
export const VERTICAL_STRIDE = 9;
/** Record of any other quad: corner, normal, P, S, T (the fields of the quad record it reads). */
export const GENERAL_STRIDE = 13;

export class QuadList {
  /** Axis-aligned quads' records, those of axis x, then y, then z. */
  readonly axis: Float64Array;
  /** Quad index of each axis record. */
  readonly axisIndex: Int32Array;
  /** axisStart[a] … axisStart[a + 1]: the records of axis a. */
  readonly axisStart: Int32Array;
  readonly vertical: Float64Array;
  readonly verticalIndex: Int32Array;
  readonly verticalCount: number;
  readonly general: Float64Array;
  readonly generalIndex: Int32Array;
  readonly generalCount: number;

  constructor(quads: Float64Array) {
    const n = quads.length / QUAD_STRIDE;
    const axisOf = new Int32Array(n);
    const count = [0, 0, 0, 0, 0];
    for (let i = 0; i < n; i++) {
      axisOf[i] = quadAxis(quads, i * QUAD_STRIDE);
      count[axisOf[i]]++;
    }
    this.axisStart = Int32Array.of(
      0,
      count[0],
      count[0] + count[1],
      count[0] + count[1] + count[2],
    );
    this.axis = new Float64Array(this.axisStart[3] * AXIS_STRIDE);
    this.axisIndex = new Int32Array(this.axisStart[3]);
    this.verticalCount = count[3];
    this.vertical = new Float64Array(count[3] * VERTICAL_STRIDE);
    this.verticalIndex = new Int32Array(count[3]);
    this.generalCount = count[4];
    this.general = new Float64Array(count[4] * GENERAL_STRIDE);
    this.generalIndex = new Int32Array(count[4]);
    const next = [this.axisStart[0], this.axisStart[1], this.axisStart[2], 0, 0];
    for (let i = 0; i < n; i++) {
      const o = i * QUAD_STRIDE;
      const a = axisOf[i];
      const k = next[a]++;
      if (a === 3) {
        // S horizontal and T vertical, or the other way round (quadAxis checked which).
        const sHorizontal = quads[o + Q_SAXIS + 1] === 0;
        const h = o + (sHorizontal ? Q_SAXIS : Q_TAXIS);
        const w = o + (sHorizontal ? Q_TAXIS : Q_SAXIS);
        const r = k * VERTICAL_STRIDE;
        this.vertical[r] = quads[o + Q_PLANE];
        this.vertical[r + 1] = quads[o + Q_NORMAL];
        this.vertical[r + 2] = quads[o + Q_NORMAL + 2];
        for (let j = 0; j < 3; j++) this.vertical[r + 3 + j] = quads[o + Q_CORNER + j];
        this.vertical[r + 6] = quads[h];
        this.vertical[r + 7] = quads[h + 2];
        this.vertical[r + 8] = quads[w + 1];
        this.verticalIndex[k] = i;
        continue;
      }
      if (a === 4) {
        const g = k * GENERAL_STRIDE;
        for (let j = 0; j < 3; j++) {
          this.general[g + j] = quads[o + Q_CORNER + j];
          this.general[g + 3 + j] = quads[o + Q_NORMAL + j];
          this.general[g + 7 + j] = quads[o + Q_SAXIS + j];
          this.general[g + 10 + j] = quads[o + Q_TAXIS + j];
        }
        this.general[g + 6] = quads[o + Q_PLANE];
        this.generalIndex[k] = i;
        continue;
      }
      const b = a === 0 ? 1 : 0;
      const c = a === 2 ? 1 : 2;
      const r = k * AXIS_STRIDE;
      this.axis[r] = quads[o + Q_PLANE];
      this.axis[r + 1] = quads[o + Q_NORMAL + a];
      this.axis[r + 2] = quads[o + Q_CORNER + b];
      this.axis[r + 3] = quads[o + Q_CORNER + c];
      this.axis[r + 4] = quads[o + Q_SAXIS + b];
      this.axis[r + 5] = quads[o + Q_SAXIS + c];
      this.axis[r + 6] = quads[o + Q_TAXIS + b];
      this.axis[r + 7] = quads[o + Q_TAXIS + c];
      this.axisIndex[k] = i;
    }
  }
}

/**
 * The axis (0, 1, 2) a quad's plane is perpendicular to, exactly; or 3 for
 * a vertical plane with a vertical edge (see VERTICAL_STRIDE); or 4.
 */
function quadAxis(quads: Float64Array, o: number): number {
  for (let a = 0; a < 3; a++) {
    const b = a === 0 ? 1 : 0;
    const c = a === 2 ? 1 : 2;
    if (
      quads[o + Q_NORMAL + b] === 0 &&
      quads[o + Q_NORMAL + c] === 0 &&
      quads[o + Q_SAXIS + a] === 0 &&
      quads[o + Q_TAXIS + a] === 0
    )
      return a;
  }
  const s = o + Q_SAXIS;
  const t = o + Q_TAXIS;
  if (
    quads[o + Q_NORMAL + 1] === 0 &&
    ((quads[s + 1] === 0 && quads[t] === 0 && quads[t + 2] === 0) ||
      (quads[t + 1] === 0 && quads[s] === 0 && quads[s + 2] === 0))
  )
    return 3;
  return 4;
}

/**
 * The nearest quad hit before r[6] (ray record of trace.ts): moves r[6] to it
 * and returns its index, or returns −1. A quad at exactly r[6] does not count
 * (the caller's earlier hit keeps a tie, as in the index-ordered loop). Each
 * quad costs one branch: all tests of a hit are combined as bits.
 */
export function nearestQuad(list: QuadList, r: Float64Array): number {
  const ox = r[0],
    oy = r[1],
    oz = r[2],
    dx = r[3],
    dy = r[4],
    dz = r[5];
  let tBest = r[6];
  let index = -1;
  const rec = list.axis;
  const ids = list.axisIndex;
  const start = list.axisStart;
  for (let a = 0; a < 3; a++) {
    // The ray along the normal's axis a and the in-plane axes b < c.
    const oa = a === 0 ? ox : a === 1 ? oy : oz;
    const da = a === 0 ? dx : a === 1 ? dy : dz;
    const ob = a === 0 ? oy : ox;
    const db = a === 0 ? dy : dx;
    const oc = a === 2 ? oy : oz;
    const dc = a === 2 ? dy : dz;
    for (let k = start[a], end = start[a + 1], o = k << 3; k < end; k++, o += 8) {
      const na = rec[o + 1];
      const t = (rec[o] - na * oa) / (na * da);
      const qb = ob + t * db - rec[o + 2];
      const qc = oc + t * dc - rec[o + 3];
      const s = qb * rec[o + 4] + qc * rec[o + 5];
      const v = qb * rec[o + 6] + qc * rec[o + 7];
      const i = ids[k];
      // A strictly closer hit, or a tie with a higher-indexed best. Written with
      // <= and < rather than ===, which V8 compiles with an extra branch for NaN
      // (3.5 % faster on the Cornell rays).
      if (
        (Number(t > 0) &
          Number(t <= tBest) &
          (Number(t < tBest) | Number(i < index)) &
          Number(s >= 0) &
          Number(s <= 1) &
          Number(v >= 0) &
          Number(v <= 1)) !==
        0
      ) {
        tBest = t;
        index = i;
      }
    }
  }
  const vert = list.vertical;
  const vids = list.verticalIndex;
  for (let k = 0, n = list.verticalCount, o = 0; k < n; k++, o += 9) {
    const nx = vert[o + 1];
    const nz = vert[o + 2];
    const t = (vert[o] - (nx * ox + nz * oz)) / (nx * dx + nz * dz);
    const qx = ox + t * dx - vert[o + 3];
    const qy = oy + t * dy - vert[o + 4];
    const qz = oz + t * dz - vert[o + 5];
    const s = qx * vert[o + 6] + qz * vert[o + 7];
    const v = qy * vert[o + 8];
    const i = vids[k];
    if (
      (Number(t > 0) &
        Number(t <= tBest) &
        (Number(t < tBest) | Number(i < index)) &
        Number(s >= 0) &
        Number(s <= 1) &
        Number(v >= 0) &
        Number(v <= 1)) !==
      0
    ) {
      tBest = t;
      index = i;
    }
  }
  const gen = list.general;
  const gids = list.generalIndex;
  for (let k = 0, n = list.generalCount, o = 0; k < n; k++, o += 13) {
    // intersectQuad (intersect.ts), the same operations.
    const nx = gen[o + 3];
    const ny = gen[o + 4];
    const nz = gen[o + 5];
    const t = (gen[o + 6] - (nx * ox + ny * oy + nz * oz)) / (nx * dx + ny * dy + nz * dz);
    const qx = ox + t * dx - gen[o];
    const qy = oy + t * dy - gen[o + 1];
    const qz = oz + t * dz - gen[o + 2];
    const s = qx * gen[o + 7] + qy * gen[o + 8] + qz * gen[o + 9];
    const v = qx * gen[o + 10] + qy * gen[o + 11] + qz * gen[o + 12];
    const i = gids[k];
    if (
      (Number(t > 0) &
        Number(t <= tBest) &
        (Number(t < tBest) | Number(i < index)) &
        Number(s >= 0) &
        Number(s <= 1) &
        Number(v >= 0) &
        Number(v <= 1)) !==
      0
    ) {
      tBest = t;
      index = i;
    }
  }
  r[6] = tBest;
  return index;
}
