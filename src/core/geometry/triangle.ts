/**
 * Watertight ray–triangle intersection (Woop, Benthin and Wald, "Watertight Ray/Triangle
 * Intersection", JCGT 2(1), 2013; pbr-book 4e §6.5.3). The vertices are translated to
 * the ray origin and sheared so the ray runs along +z; the 2D edge functions U, V, W
 * then decide the hit. Every vertex is transformed the same way for every triangle that
 * uses it, so two triangles sharing an edge see it through bit-identical (negated)
 * values: a ray cannot slip between them.
 *
 * Two refinements for double precision and exact edges:
 * - an edge function too close to zero for its sign to be trusted is recomputed exactly
 *   (exact.ts), the double-precision analogue of the paper's float→double fallback, so
 *   the signs around a shared vertex are consistent too;
 * - a point exactly on an edge or vertex belongs to one triangle only, by a tie rule
 *   equivalent to moving the point an infinitesimal step along (1, −δ) in the sheared
 *   plane (the "top-left" rule of rasterisers), so there are no double hits either.
 *
 * The distance is a cubic in the coordinates relative to the ray origin, so beyond about
 * 2^±340 it would over- or underflow: the careful path then scales the triangle's nine
 * coordinates by a power of two (exact: the same signs, the same hits) and the distance
 * back, so triangles at any finite magnitude are hit.
 */
import { DIFF_OF_PRODUCTS_ERROR, exactDiffOfProducts, mulPow2 } from './exact.ts';

/**
 * Per-ray constants: the permutation that makes the largest direction component z (kx,
 * ky swapped when it is negative, to keep the winding), and the shear. Compute once per
 * ray with `setTriangleRay`, then test any number of triangles.
 */
export class TriangleRay {
  kx = 0;
  ky = 1;
  kz = 2;
  sx = 0;
  sy = 0;
  sz = 1;
  /** The origin, permuted: its kx, ky and kz components. */
  o0 = 0;
  o1 = 0;
  o2 = 0;
}

export function setTriangleRay(
  ox: number,
  oy: number,
  oz: number,
  dx: number,
  dy: number,
  dz: number,
  out: TriangleRay,
): void {
  const ax = Math.abs(dx),
    ay = Math.abs(dy),
    az = Math.abs(dz);
  const kz = ax > ay ? (ax > az ? 0 : 2) : ay > az ? 1 : 2;
  let kx = kz === 2 ? 0 : kz + 1;
  let ky = kx === 2 ? 0 : kx + 1;
  const dkz = kz === 0 ? dx : kz === 1 ? dy : dz;
  if (dkz < 0) {
    const tmp = kx;
    kx = ky;
    ky = tmp;
  }
  const dkx = kx === 0 ? dx : kx === 1 ? dy : dz;
  const dky = ky === 0 ? dx : ky === 1 ? dy : dz;
  out.kx = kx;
  out.ky = ky;
  out.kz = kz;
  out.sx = dkx / dkz;
  out.sy = dky / dkz;
  out.sz = 1 / dkz;
  out.o0 = kx === 0 ? ox : kx === 1 ? oy : oz;
  out.o1 = ky === 0 ? ox : ky === 1 ? oy : oz;
  out.o2 = kz === 0 ? ox : kz === 1 ? oy : oz;
}

/** Barycentrics (of p0, p1, p2) of the last hit found by `intersectTriangleBary`. */
export class TriangleHit {
  b0 = 0;
  b1 = 0;
  b2 = 0;
}

/** Index of the far bound in the scene's ray record (R_T of geometry/ray.ts). */
const R_T = 6;

/**
 * Whether the ray hits triangle `tri` closer than r[R_T], the far bound of the scene's
 * ray record (tMax, or the nearest hit so far); if so, moves r[R_T] to the hit. `positions` holds x, y, z
 * per vertex and `indices` three vertex indices per triangle. The ray enters only
 * through `r` (setTriangleRay); its direction need not be unit length.
 *
 * The distance travels through the ray record rather than as a number argument and
 * result: where V8 does not inline a call, a double passed or returned is boxed on the
 * heap, one allocation per test.
 *
 * This is the common case: every edge function's sign certain. Anything closer to an
 * edge takes the careful path out of line (exact signs, the tie rule), which gives the
 * same answer wherever both apply. (The function is still a call from the BVH loops: at
 * 679 bytes of bytecode it exceeds V8's inlining limit of 460; a version split to 448
 * bytes was not inlined either, the loops' inlining budget being spent, and forcing the
 * inlining with V8 flags gained nothing on the 1M-triangle mesh: docs/performance.md.)
 *
 * Certainty of a sign, without Math.abs (each call is ~14 bytes of bytecode): Shewchuk's
 * bound for u = u1 − u2 is |u| > C·fl(|u1| + |u2|), and fl(|u1| + |u2|) = max(|u|, |s|)
 * with s = fl(u1 + u2) (one of the two is the same rounded operation on the same
 * magnitudes, the other is smaller), so the test is |u| > |C·s| for a finite u, i.e.
 * u + C·s and u − C·s of one sign: their product positive (a product that underflows to
 * 0 sends the triangle to the careful path, which is always right). The sign of a rounded
 * sum is exact.
 */
export function hitTriangle(
  positions: Float64Array,
  indices: Uint32Array | Int32Array,
  tri: number,
  tr: TriangleRay,
  record: Float64Array,
): boolean {
  const kx = tr.kx,
    ky = tr.ky,
    kz = tr.kz;
  const ia = indices[3 * tri] * 3,
    ib = indices[3 * tri + 1] * 3,
    ic = indices[3 * tri + 2] * 3;
  const o0 = tr.o0,
    o1 = tr.o1,
    o2 = tr.o2;
  const az = positions[ia + kz] - o2,
    bz = positions[ib + kz] - o2,
    cz = positions[ic + kz] - o2;
  const sx = tr.sx,
    sy = tr.sy;
  const ax = positions[ia + kx] - o0 - sx * az,
    ay = positions[ia + ky] - o1 - sy * az;
  const bx = positions[ib + kx] - o0 - sx * bz,
    by = positions[ib + ky] - o1 - sy * bz;
  const cx = positions[ic + kx] - o0 - sx * cz,
    cy = positions[ic + ky] - o1 - sy * cz;
  const u1 = cx * by,
    u2 = cy * bx;
  const v1 = ax * cy,
    v2 = ay * cx;
  const u = u1 - u2,
    v = v1 - v2;
  const cu = DIFF_OF_PRODUCTS_ERROR * (u1 + u2),
    cv = DIFF_OF_PRODUCTS_ERROR * (v1 + v2);
  if (!((u + cu) * (u - cu) > 0 && (v + cv) * (v - cv) > 0)) {
    return hitTriangleCareful(positions, indices, tri, tr, record);
  }
  // Signs that are certain and differ: a miss (the usual exit, before W is computed).
  if (u < 0 !== v < 0) return false;
  const w1 = bx * ay,
    w2 = by * ax;
  const w = w1 - w2;
  const cw = DIFF_OF_PRODUCTS_ERROR * (w1 + w2);
  if (!((w + cw) * (w - cw) > 0)) return hitTriangleCareful(positions, indices, tri, tr, record);
  if (u < 0 !== w < 0) return false;
  const det = u + v + w;
  const tScaled = tr.sz * (u * az + v * bz + w * cz);
  const tMax = record[R_T];
  if (det > 0 ? tScaled <= 0 || tScaled >= tMax * det : tScaled >= 0 || tScaled <= tMax * det) {
    // The distance is a cubic in the coordinates: one that overflowed (coordinates
    // beyond ~2^340 from the origin) or vanished is no miss; the careful path rescales.
    if (tScaled === 0 || tScaled - tScaled !== 0) {
      return hitTriangleCareful(positions, indices, tri, tr, record);
    }
    return false;
  }
  const t = tScaled / det;
  if (!(t > 0 && t < tMax)) return false;
  record[R_T] = t;
  return true;
}

/** hitTriangle by the careful path (intersectTriangleBary), out of line. */
function hitTriangleCareful(
  positions: Float64Array,
  indices: Uint32Array | Int32Array,
  tri: number,
  tr: TriangleRay,
  record: Float64Array,
): boolean {
  const tMax = record[R_T];
  const t = intersectTriangleBary(positions, indices, tri, tr, tMax, null);
  if (!(t < tMax)) return false;
  record[R_T] = t;
  return true;
}

/**
 * Distance to triangle `tri` in (0, tMax), or Infinity, by the careful path alone (exact
 * edge signs where rounding could decide them, the tie rule on edges); on a hit writes
 * the barycentrics into `hit` (if given). `hitTriangle` answers the same, faster.
 */
export function intersectTriangleBary(
  positions: Float64Array,
  indices: Uint32Array | Int32Array,
  tri: number,
  r: TriangleRay,
  tMax: number,
  hit: TriangleHit | null,
): number {
  const kx = r.kx,
    ky = r.ky,
    kz = r.kz;
  const ia = indices[3 * tri] * 3,
    ib = indices[3 * tri + 1] * 3,
    ic = indices[3 * tri + 2] * 3;
  const o0 = r.o0,
    o1 = r.o1,
    o2 = r.o2;
  // Vertices relative to the origin, permuted so the ray runs along the third axis.
  let az = positions[ia + kz] - o2,
    bz = positions[ib + kz] - o2,
    cz = positions[ic + kz] - o2;
  const sx = r.sx,
    sy = r.sy;
  let ax = positions[ia + kx] - o0 - sx * az,
    ay = positions[ia + ky] - o1 - sy * az;
  let bx = positions[ib + kx] - o0 - sx * bz,
    by = positions[ib + ky] - o1 - sy * bz;
  let cx = positions[ic + kx] - o0 - sx * cz,
    cy = positions[ic + ky] - o1 - sy * cz;
  // Beyond 2^±300 from the ray origin the cubic of the distance would over- or
  // underflow: scale the nine coordinates by a power of two (exact, so every sign below
  // is the same as unscaled, and shared edges stay watertight) and the distance back.
  const m = Math.max(
    Math.abs(ax),
    Math.abs(ay),
    Math.abs(az),
    Math.abs(bx),
    Math.abs(by),
    Math.abs(bz),
    Math.abs(cx),
    Math.abs(cy),
    Math.abs(cz),
  );
  let exp = 0;
  if (m > SCALE_ABOVE || (m < SCALE_BELOW && m > 0)) {
    exp = Math.floor(Math.log2(m));
    ax = mulPow2(ax, -exp);
    ay = mulPow2(ay, -exp);
    az = mulPow2(az, -exp);
    bx = mulPow2(bx, -exp);
    by = mulPow2(by, -exp);
    bz = mulPow2(bz, -exp);
    cx = mulPow2(cx, -exp);
    cy = mulPow2(cy, -exp);
    cz = mulPow2(cz, -exp);
  }

  let u = cx * by - cy * bx;
  let v = ax * cy - ay * cx;
  let w = bx * ay - by * ax;
  // Recompute exactly any edge function whose sign rounding might have decided.
  if (Math.abs(u) <= DIFF_OF_PRODUCTS_ERROR * (Math.abs(cx * by) + Math.abs(cy * bx))) {
    u = exactDiffOfProducts(cx, by, cy, bx);
  }
  if (Math.abs(v) <= DIFF_OF_PRODUCTS_ERROR * (Math.abs(ax * cy) + Math.abs(ay * cx))) {
    v = exactDiffOfProducts(ax, cy, ay, cx);
  }
  if (Math.abs(w) <= DIFF_OF_PRODUCTS_ERROR * (Math.abs(bx * ay) + Math.abs(by * ax))) {
    w = exactDiffOfProducts(bx, ay, by, ax);
  }
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return Infinity;
  const det = u + v + w;
  if (det === 0) return Infinity; // edge-on: the ray lies in the triangle's plane
  // A point exactly on an edge belongs to the triangle only if the edge, oriented as
  // the triangle's boundary with positive orientation, points to +y (or along +x).
  if (u === 0 || v === 0 || w === 0) {
    const s = det > 0 ? 1 : -1;
    if (u === 0 && !ownsEdge((cx - bx) * s, (cy - by) * s)) return Infinity;
    if (v === 0 && !ownsEdge((ax - cx) * s, (ay - cy) * s)) return Infinity;
    if (w === 0 && !ownsEdge((bx - ax) * s, (by - ay) * s)) return Infinity;
  }
  const szz = r.sz;
  const tScaled = szz * (u * az + v * bz + w * cz);
  let t: number;
  if (exp === 0) {
    // 0 < t = tScaled / det < tMax, without dividing on the way.
    if (det > 0 ? tScaled <= 0 || tScaled >= tMax * det : tScaled >= 0 || tScaled <= tMax * det) {
      return Infinity;
    }
    t = tScaled / det;
  } else {
    if (det > 0 ? tScaled <= 0 : tScaled >= 0) return Infinity;
    t = mulPow2(tScaled / det, exp);
  }
  if (!(t > 0 && t < tMax)) return Infinity; // underflow of a vanishing distance
  if (hit !== null) {
    const inv = 1 / det;
    hit.b0 = u * inv;
    hit.b1 = v * inv;
    hit.b2 = w * inv;
  }
  return t;
}

/** Coordinates relative to the ray origin outside [2^-300, 2^300] are rescaled (see above). */
const SCALE_ABOVE = 2 ** 300;
const SCALE_BELOW = 2 ** -300;

function ownsEdge(ex: number, ey: number): boolean {
  return ey > 0 || (ey === 0 && ex > 0);
}
