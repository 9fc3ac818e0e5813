/**
 * Instancing (docs/gltf.md, Instancing): a mesh drawn several times is kept once, in
 * object space, with its own bottom-level BVH (BLAS); each drawing is an *instance* —
 * a transform and the BLAS — and the scene's one BVH (bvh.ts) holds the instances as
 * primitives of kind PRIM_INSTANCE beside the spheres, quads and world-space triangles:
 * it is the top-level BVH (TLAS). A ray reaching an instance in a TLAS leaf is carried
 * into object space and traverses the BLAS (traverse-instanced.ts, blas-traverse.ts).
 *
 * The instance record, 100 bytes:
 *   f64 ×12  instXform: the world-to-object affine 3×4, column-major (w00 w10 w20,
 *            w01 w11 w21, w02 w12 w22, wx wy wz). The ray is transformed by it; normals
 *            transform by its transpose ((M⁻¹)ᵀ, pbr-book 4e §3.10.1), so one matrix
 *            serves both. The object-to-world matrix is not stored: a hit needs it once
 *            (instance-surface.ts), and inverts this one.
 *   i32      instBlas: the BLAS's root node in blasNodes.
 * In f64 like every other coordinate: the triangle test's robustness (geometry/exact.ts)
 * is exact arithmetic on the doubles it is given, and an f32 transform would move the
 * object-space ray by far more than the boxes' one-ulp padding (bvh.ts f32Below).
 *
 * The BLASes are built with the scene's buildBvh over their triangles (references are
 * the global triangle numbers, so hits name triangles as without instancing) and
 * concatenated into one node array and one reference array, child and leaf indices
 * relocated, so a BLAS is its root node's number.
 */
import { BVH_NODE_WORDS, buildBvh, f32Above, f32Below } from './bvh.ts';
import { PRIM_KIND_BITS } from './primitives.ts';
import { SHAPE_TRIANGLE } from '../geometry/ray.ts';
import { checkCancel } from '../util/cancel.ts';

/** Kind tag of an instance in the TLAS's references (beside SHAPE_SPHERE, _QUAD, _TRIANGLE). */
export const PRIM_INSTANCE = 3;
/** Doubles per instance of instXform. */
export const INSTANCE_XFORM = 12;

export interface InstanceArrays {
  instXform: Float64Array;
  instBlas: Int32Array;
  blasNodes: Int32Array;
  blasRefs: Int32Array;
  /** [depth of the deepest BLAS] (its traversal stack needs depth + 1), or empty. */
  blasDepth: Int32Array;
}

export const NO_INSTANCES: InstanceArrays = {
  instXform: new Float64Array(0),
  instBlas: new Int32Array(0),
  blasNodes: new Int32Array(0),
  blasRefs: new Int32Array(0),
  blasDepth: new Int32Array(0),
};

/**
 * Builds the BLASes over triangles [blasTriangles[b], blasTriangles[b + 1]) of
 * (positions, indices), and the records of the instances (BLAS instanceBlas[k],
 * object-to-world 3×4 objectToWorld[12k, 12k + 12)). Returns the arrays and each
 * instance's world box (six numbers, exact; PrimitiveBoxes rounds them outwards).
 */
export function buildInstances(
  positions: Float64Array,
  indices: Int32Array,
  blasTriangles: ArrayLike<number>,
  instanceBlas: ArrayLike<number>,
  objectToWorld: Float64Array,
): { arrays: InstanceArrays; boxes: Float64Array } {
  const blasCount = blasTriangles.length - 1;
  const parts: { words: Int32Array; refs: Int32Array; depth: number }[] = [];
  let nodeTotal = 0;
  let refTotal = 0;
  let depth = 0;
  const root = new Int32Array(blasCount);
  const objectBox = new Float64Array(blasCount * 6);
  for (let b = 0; b < blasCount; b++) {
    const first = blasTriangles[b];
    const n = blasTriangles[b + 1] - first;
    // A mesh left without triangles (points and lines only) has no instances either.
    if (n === 0) continue;
    const boxes = new Float32Array(n * 6);
    const refs = new Int32Array(n);
    const box = objectBox.subarray(6 * b, 6 * b + 6);
    box.fill(Infinity, 0, 3);
    box.fill(-Infinity, 3, 6);
    for (let k = 0; k < n; k++) {
      if ((k & 65535) === 65535) checkCancel();
      const t = first + k;
      for (let a = 0; a < 3; a++) {
        const p0 = positions[indices[3 * t] * 3 + a],
          p1 = positions[indices[3 * t + 1] * 3 + a],
          p2 = positions[indices[3 * t + 2] * 3 + a];
        const lo = Math.min(p0, p1, p2);
        const hi = Math.max(p0, p1, p2);
        boxes[6 * k + a] = f32Below(lo);
        boxes[6 * k + 3 + a] = f32Above(hi);
        if (boxes[6 * k + a] < box[a]) box[a] = boxes[6 * k + a];
        if (boxes[6 * k + 3 + a] > box[3 + a]) box[3 + a] = boxes[6 * k + 3 + a];
      }
      refs[k] = (t << PRIM_KIND_BITS) | SHAPE_TRIANGLE;
    }
    // Node cost 2, as for the scene's meshes (compile.ts): fewer, fuller leaves.
    const bvh = buildBvh(boxes, refs, n, 2)!;
    root[b] = nodeTotal;
    parts.push({ words: bvh.words, refs: bvh.refs, depth: bvh.depth });
    nodeTotal += bvh.nodeCount;
    refTotal += bvh.refs.length;
    if (bvh.depth > depth) depth = bvh.depth;
  }
  const blasNodes = new Int32Array(nodeTotal * BVH_NODE_WORDS);
  const blasRefs = new Int32Array(refTotal);
  let nodeBase = 0;
  let refBase = 0;
  for (const part of parts) {
    const w = part.words;
    blasNodes.set(w, nodeBase * BVH_NODE_WORDS);
    for (
      let o = nodeBase * BVH_NODE_WORDS;
      o < nodeBase * BVH_NODE_WORDS + w.length;
      o += BVH_NODE_WORDS
    ) {
      for (let c = 12; c <= 13; c++) {
        const child = blasNodes[o + c];
        // An interior child moves by the nodes before; a leaf ~(first << 3 | count) by the refs.
        blasNodes[o + c] = child >= 0 ? child + nodeBase : ~(~child + (refBase << 3));
      }
    }
    blasRefs.set(part.refs, refBase);
    nodeBase += w.length / BVH_NODE_WORDS;
    refBase += part.refs.length;
  }
  const count = instanceBlas.length;
  const instXform = new Float64Array(count * INSTANCE_XFORM);
  const instBlas = new Int32Array(count);
  const boxes = new Float64Array(count * 6);
  for (let k = 0; k < count; k++) {
    const b = instanceBlas[k];
    instBlas[k] = root[b];
    invertAffine(objectToWorld, 12 * k, instXform, 12 * k);
    transformBox(objectToWorld, 12 * k, objectBox, 6 * b, boxes, 6 * k);
  }
  return {
    arrays: {
      instXform,
      instBlas,
      blasNodes,
      blasRefs,
      blasDepth: Int32Array.of(depth),
    },
    boxes,
  };
}

/**
 * The inverse of the affine 3×4 m[at, at + 12) (column-major) into out[o, o + 12): the
 * 3×3 by its adjugate over the determinant, the translation −A⁻¹t.
 */
export function invertAffine(m: Float64Array, at: number, out: Float64Array, o: number): void {
  const a = m[at],
    b = m[at + 3],
    c = m[at + 6];
  const d = m[at + 1],
    e = m[at + 4],
    f = m[at + 7];
  const g = m[at + 2],
    h = m[at + 5],
    i = m[at + 8];
  const c00 = e * i - f * h,
    c01 = f * g - d * i,
    c02 = d * h - e * g;
  const det = a * c00 + b * c01 + c * c02;
  const s = 1 / det;
  // Row-major inverse entries r_ij, stored column-major.
  const r00 = c00 * s,
    r01 = (c * h - b * i) * s,
    r02 = (b * f - c * e) * s;
  const r10 = c01 * s,
    r11 = (a * i - c * g) * s,
    r12 = (c * d - a * f) * s;
  const r20 = c02 * s,
    r21 = (b * g - a * h) * s,
    r22 = (a * e - b * d) * s;
  const tx = m[at + 9],
    ty = m[at + 10],
    tz = m[at + 11];
  out[o] = r00;
  out[o + 1] = r10;
  out[o + 2] = r20;
  out[o + 3] = r01;
  out[o + 4] = r11;
  out[o + 5] = r21;
  out[o + 6] = r02;
  out[o + 7] = r12;
  out[o + 8] = r22;
  out[o + 9] = -(r00 * tx + r01 * ty + r02 * tz);
  out[o + 10] = -(r10 * tx + r11 * ty + r12 * tz);
  out[o + 11] = -(r20 * tx + r21 * ty + r22 * tz);
}

/** The world box of the object box box[bo, bo + 6) under the affine m[at, at + 12). */
function transformBox(
  m: Float64Array,
  at: number,
  box: Float64Array,
  bo: number,
  out: Float64Array,
  o: number,
): void {
  for (let a = 0; a < 3; a++) {
    // Per axis, the extreme of each term is at one end of its interval (Arvo 1990).
    let lo = m[at + 9 + a];
    let hi = lo;
    let size = Math.abs(lo);
    for (let k = 0; k < 3; k++) {
      const e = m[at + 3 * k + a];
      const p = e * box[bo + k];
      const q = e * box[bo + 3 + k];
      lo += Math.min(p, q);
      hi += Math.max(p, q);
      size += Math.max(Math.abs(p), Math.abs(q));
    }
    // Four rounded products and sums: each off by at most half an ulp of `size`; where
    // the terms cancel, that is more than the Float32 padding of the result covers.
    const err = size * 2 ** -49;
    out[o + a] = lo - err;
    out[o + 3 + a] = hi + err;
  }
}
