/**
 * Scene-level ray queries: the nearest hit (`intersectScene`) and any hit
 * before tMax (`occluded`, for shadow rays). Below the BVH threshold a plain
 * loop over the shapes; above it the BVH (accel/bvh.ts), whose leaves
 * dispatch on each primitive's kind tag (accel/primitives.ts).
 *
 * The queries copy the ray into the scene's ray record (a Float64Array:
 * origin, direction and the current far bound R_T), and the primitive tests
 * `hitSphere`/`hitQuad` read it and move R_T to a closer hit. They take and
 * return no double: when V8 does not inline a call (it declines for a kind
 * that is rare in the scene), a double argument or result would be boxed on
 * the heap at every call.
 */
import {
  BVH_LEAF_BITS,
  BVH_LEAF_MASK,
  BVH_NODE_WORDS,
  N_LEFT,
  N_RIGHT,
  N_RIGHT_BOX,
} from '../accel/bvh.ts';
import { PRIM_KIND_BITS, PRIM_KIND_MASK } from '../accel/primitives.ts';
import type { CompiledScene } from '../scene/compile.ts';
import { intersectQuad, intersectSphere } from './intersect.ts';
import { SHAPE_QUAD, SHAPE_SPHERE, SHAPE_TRIANGLE, type Hit, type Ray } from './ray.ts';
import {
  QUAD_STRIDE,
  Q_CORNER,
  Q_NORMAL,
  Q_PLANE,
  Q_SAXIS,
  Q_TAXIS,
  SPHERE_STRIDE,
} from './shapes.ts';
import { anyQuad, nearestQuad } from './quad-list.ts';
import { hitTriangle, intersectTriangleBary, setTriangleRay } from './triangle.ts';

/** Ray record layout: origin, direction, far bound. */
export const R_OX = 0;
export const R_DX = 3;
export const R_T = 6;
export const RAY_RECORD_WORDS = 8;

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

function loadRay(r: Float64Array, ray: Ray): void {
  r[0] = ray.ox;
  r[1] = ray.oy;
  r[2] = ray.oz;
  r[3] = ray.dx;
  r[4] = ray.dy;
  r[5] = ray.dz;
  r[6] = ray.tMax;
}

export function intersectScene(scene: CompiledScene, ray: Ray, hit: Hit): boolean {
  const r = scene.ray;
  loadRay(r, ray);
  // Two small functions rather than one big one: V8 optimises (and inlines
  // the primitive tests into) each far better.
  if (scene.triCount > 0) setTriangleRay(r[0], r[1], r[2], r[3], r[4], r[5], scene.triRay);
  const found = scene.bvh === null ? intersectList(scene, r, hit) : intersectBvh(scene, r, hit);
  if (found) {
    hit.t = r[6];
    if (hit.kind === SHAPE_TRIANGLE) triangleBarycentrics(scene, hit);
  }
  return found;
}

/** Barycentrics of the kept triangle hit, recomputed once with the same ray constants. */
function triangleBarycentrics(scene: CompiledScene, hit: Hit): void {
  const th = scene.triHit;
  intersectTriangleBary(
    scene.triPositions,
    scene.triIndices,
    hit.index,
    scene.triRay,
    Infinity,
    th,
  );
  hit.b0 = th.b0;
  hit.b1 = th.b1;
  hit.b2 = th.b2;
}

/** Whether anything lies on the ray in (0, ray.tMax). */
export function occluded(scene: CompiledScene, ray: Ray): boolean {
  const r = scene.ray;
  loadRay(r, ray);
  if (scene.triCount > 0) setTriangleRay(r[0], r[1], r[2], r[3], r[4], r[5], scene.triRay);
  return scene.bvh === null ? occludedList(scene, r) : occludedBvh(scene, r);
}

// The plain loops call the primitive tests with the ray in locals: each
// call runs once per shape and query, so V8 always inlines it.
function intersectList(scene: CompiledScene, r: Float64Array, hit: Hit): boolean {
  const ox = r[0],
    oy = r[1],
    oz = r[2],
    dx = r[3],
    dy = r[4],
    dz = r[5];
  let tBest = r[6];
  let kind = -1;
  let index = -1;
  const spheres = scene.spheres;
  for (let i = 0, n = scene.sphereCount; i < n; i++) {
    const t = intersectSphere(spheres, i, ox, oy, oz, dx, dy, dz, tBest);
    if (t < tBest) {
      tBest = t;
      kind = SHAPE_SPHERE;
      index = i;
    }
  }
  r[6] = tBest;
  if (scene.quadCount > 0) {
    const q = nearestQuad(scene.quadList, r);
    if (q >= 0) {
      kind = SHAPE_QUAD;
      index = q;
    }
  }
  const triCount = scene.triCount;
  if (triCount > 0) {
    const pos = scene.triPositions;
    const idx = scene.triIndices;
    const tr = scene.triRay;
    for (let i = 0; i < triCount; i++) {
      if (hitTriangle(pos, idx, i, tr, r)) {
        kind = SHAPE_TRIANGLE;
        index = i;
      }
    }
  }
  if (kind < 0) return false;
  hit.kind = kind;
  hit.index = index;
  return true;
}

function occludedList(scene: CompiledScene, r: Float64Array): boolean {
  const ox = r[0],
    oy = r[1],
    oz = r[2],
    dx = r[3],
    dy = r[4],
    dz = r[5],
    tMax = r[6];
  const spheres = scene.spheres;
  for (let i = 0, n = scene.sphereCount; i < n; i++) {
    if (intersectSphere(spheres, i, ox, oy, oz, dx, dy, dz, tMax) < tMax) return true;
  }
  if (scene.quadCount > 0 && anyQuad(scene.quadList, r)) return true;
  const triCount = scene.triCount;
  if (triCount > 0) {
    const pos = scene.triPositions;
    const idx = scene.triIndices;
    const tr = scene.triRay;
    for (let i = 0; i < triCount; i++) if (hitTriangle(pos, idx, i, tr, r)) return true;
  }
  return false;
}

/**
 * Nearest hit through the BVH (layout in accel/bvh.ts). The loop visits
 * items: an interior node tests both children's boxes and, when both are
 * hit, enters the nearer first and pushes the other with its entry
 * distance (skipped when popped if a closer hit was found meanwhile); a
 * leaf tests its primitives. Leaves are handled in one place so that each
 * kind's test is inlined once.
 *
 * Leaf tests by hand: the sphere and quad tests are written out here (the
 * same arithmetic as intersectSphere/intersectQuad, so the same hits bit for
 * bit; tests/unit/bvh.test.ts compares with the plain loop) rather than
 * called. V8 inlines a call only if, when it optimises this function, the
 * call has run on at least 15 % of its invocations so far
 * (--min-inlining-frequency). A render starts at the top rows, whose rays
 * often reach no leaf (sky): V8 then optimises this function early, sees
 * the leaf calls as rare and keeps them out of line for the whole render
 * (10k spheres: 0 leaf calls in the first 1,000 queries, 0.87 per query
 * over the render; forcing the inlining with the flag, or these written-out
 * tests, gave +2–5 % paths/s; docs/performance.md). The triangle test stays
 * a call: it exceeds V8's inlining size limit anyway.
 *
 * Boxes are tested in the pairwise form of the slab test (Williams et al.,
 * "An Efficient and Robust Ray–Box Intersection Algorithm", JGT 2005, for
 * the near/far planes chosen by the direction's signs): the interval
 * [0, t] meets every slab iff each slab's entry lies before every other
 * exit. The twelve comparisons are combined as bits, so a box costs one
 * branch instead of twelve hard-to-predict ones (17 % faster on the Cornell
 * box's rays; bench/inproc.ts). A comparison with NaN (0·∞ for a ray in
 * the plane of a face) is false and skips the box, which is right because
 * boxes are padded: such a ray cannot reach what is inside.
 */
function intersectBvh(scene: CompiledScene, r: Float64Array, hit: Hit): boolean {
  const bvh = scene.bvh!;
  const ox = r[0],
    oy = r[1],
    oz = r[2];
  const ix = 1 / r[3],
    iy = 1 / r[4],
    iz = 1 / r[5];
  let kind = -1;
  let index = -1;
  const nodes = bvh.nodes;
  const words = bvh.words;
  const refs = bvh.refs;
  const spheres = scene.spheres;
  const quads = scene.quads;
  const triPositions = scene.triPositions;
  const triIndices = scene.triIndices;
  const tr = scene.triRay;
  const stack = scene.stack;
  const stackT = scene.stackT;
  const nearX = ix < 0 ? 3 : 0,
    nearY = iy < 0 ? 4 : 1,
    nearZ = iz < 0 ? 5 : 2;
  const farX = 3 - nearX,
    farY = 5 - nearY,
    farZ = 7 - nearZ;
  let sp = 0;
  let item = 0;
  traversal: for (;;) {
    if (item >= 0) {
      const b = item * BVH_NODE_WORDS;
      const t = r[6];
      let nx = (nodes[b + nearX] - ox) * ix;
      let ny = (nodes[b + nearY] - oy) * iy;
      let nz = (nodes[b + nearZ] - oz) * iz;
      let fx = (nodes[b + farX] - ox) * ix;
      let fy = (nodes[b + farY] - oy) * iy;
      let fz = (nodes[b + farZ] - oz) * iz;
      const hitL =
        Number(nx <= fy) &
        Number(nx <= fz) &
        Number(ny <= fx) &
        Number(ny <= fz) &
        Number(nz <= fx) &
        Number(nz <= fy) &
        Number(nx <= t) &
        Number(ny <= t) &
        Number(nz <= t) &
        Number(fx >= 0) &
        Number(fy >= 0) &
        Number(fz >= 0);
      const lx = nx,
        ly = ny,
        lz = nz;
      const c = b + N_RIGHT_BOX;
      nx = (nodes[c + nearX] - ox) * ix;
      ny = (nodes[c + nearY] - oy) * iy;
      nz = (nodes[c + nearZ] - oz) * iz;
      fx = (nodes[c + farX] - ox) * ix;
      fy = (nodes[c + farY] - oy) * iy;
      fz = (nodes[c + farZ] - oz) * iz;
      const hitR =
        Number(nx <= fy) &
        Number(nx <= fz) &
        Number(ny <= fx) &
        Number(ny <= fz) &
        Number(nz <= fx) &
        Number(nz <= fy) &
        Number(nx <= t) &
        Number(ny <= t) &
        Number(nz <= t) &
        Number(fx >= 0) &
        Number(fy >= 0) &
        Number(fz >= 0);
      if ((hitL & hitR) !== 0) {
        // Both: the nearer first; the other is pushed with its entry
        // distance, to be skipped if a closer hit is found meanwhile.
        let eL = lx;
        if (ly > eL) eL = ly;
        if (lz > eL) eL = lz;
        let eR = nx;
        if (ny > eR) eR = ny;
        if (nz > eR) eR = nz;
        if (eR < eL) {
          stack[sp] = words[b + N_LEFT];
          stackT[sp++] = eL;
          item = words[b + N_RIGHT];
        } else {
          stack[sp] = words[b + N_RIGHT];
          stackT[sp++] = eR;
          item = words[b + N_LEFT];
        }
        continue;
      }
      if (hitL !== 0) {
        item = words[b + N_LEFT];
        continue;
      }
      if (hitR !== 0) {
        item = words[b + N_RIGHT];
        continue;
      }
    } else {
      // A leaf: ~(first << BVH_LEAF_BITS | count).
      const leaf = ~item;
      const first = leaf >> BVH_LEAF_BITS;
      for (let k = first, end = first + (leaf & BVH_LEAF_MASK); k < end; k++) {
        const ref = refs[k];
        const i = ref >> PRIM_KIND_BITS;
        switch (ref & PRIM_KIND_MASK) {
          case SHAPE_SPHERE: {
            // intersectSphere (intersect.ts) written out: see "Leaf tests by hand" above.
            const o = i * SPHERE_STRIDE;
            const rad = spheres[o + 3];
            const dx = r[3],
              dy = r[4],
              dz = r[5];
            const fx = ox - spheres[o];
            const fy = oy - spheres[o + 1];
            const fz = oz - spheres[o + 2];
            const bb = fx * dx + fy * dy + fz * dz;
            const lx = fx - bb * dx;
            const ly = fy - bb * dy;
            const lz = fz - bb * dz;
            const disc = rad * rad - (lx * lx + ly * ly + lz * lz);
            if (disc < 0) break;
            const cc = fx * fx + fy * fy + fz * fz - rad * rad;
            const q = bb > 0 ? -bb - Math.sqrt(disc) : -bb + Math.sqrt(disc);
            let t0 = cc / q;
            let t1 = q;
            if (t0 > t1) {
              const tmp = t0;
              t0 = t1;
              t1 = tmp;
            }
            const tMax = r[6];
            if (t0 > 0 && t0 < tMax) r[6] = t0;
            else if (t1 > 0 && t1 < tMax) r[6] = t1;
            else break;
            kind = SHAPE_SPHERE;
            index = i;
            break;
          }
          case SHAPE_QUAD: {
            // intersectQuad (intersect.ts) written out.
            const o = i * QUAD_STRIDE;
            const dx = r[3],
              dy = r[4],
              dz = r[5];
            const nx = quads[o + Q_NORMAL];
            const ny = quads[o + Q_NORMAL + 1];
            const nz = quads[o + Q_NORMAL + 2];
            const t =
              (quads[o + Q_PLANE] - (nx * ox + ny * oy + nz * oz)) / (nx * dx + ny * dy + nz * dz);
            if (!(t > 0 && t < r[6])) break;
            const qx = ox + t * dx - quads[o + Q_CORNER];
            const qy = oy + t * dy - quads[o + Q_CORNER + 1];
            const qz = oz + t * dz - quads[o + Q_CORNER + 2];
            const qs =
              qx * quads[o + Q_SAXIS] + qy * quads[o + Q_SAXIS + 1] + qz * quads[o + Q_SAXIS + 2];
            const qv =
              qx * quads[o + Q_TAXIS] + qy * quads[o + Q_TAXIS + 1] + qz * quads[o + Q_TAXIS + 2];
            if ((Number(qs >= 0) & Number(qs <= 1) & Number(qv >= 0) & Number(qv <= 1)) === 0)
              break;
            r[6] = t;
            kind = SHAPE_QUAD;
            index = i;
            break;
          }
          case SHAPE_TRIANGLE:
            if (hitTriangle(triPositions, triIndices, i, tr, r)) {
              kind = SHAPE_TRIANGLE;
              index = i;
            }
            break;
        }
      }
    }
    // The latest pending child that may still hold a closer hit.
    do {
      if (sp === 0) break traversal;
      sp--;
    } while (!(stackT[sp] < r[6]));
    item = stack[sp];
  }
  if (kind < 0) return false;
  hit.kind = kind;
  hit.index = index;
  return true;
}

/** Any hit through the BVH: the box test of intersectBvh; the first hit ends the search. */
function occludedBvh(scene: CompiledScene, r: Float64Array): boolean {
  const bvh = scene.bvh!;
  const ox = r[0],
    oy = r[1],
    oz = r[2];
  const ix = 1 / r[3],
    iy = 1 / r[4],
    iz = 1 / r[5];
  const tMax = r[6];
  const nodes = bvh.nodes;
  const words = bvh.words;
  const refs = bvh.refs;
  const spheres = scene.spheres;
  const quads = scene.quads;
  const triPositions = scene.triPositions;
  const triIndices = scene.triIndices;
  const tr = scene.triRay;
  const stack = scene.stack;
  const nearX = ix < 0 ? 3 : 0,
    nearY = iy < 0 ? 4 : 1,
    nearZ = iz < 0 ? 5 : 2;
  const farX = 3 - nearX,
    farY = 5 - nearY,
    farZ = 7 - nearZ;
  let sp = 0;
  let item = 0;
  for (;;) {
    if (item >= 0) {
      const b = item * BVH_NODE_WORDS;
      let nx = (nodes[b + nearX] - ox) * ix;
      let ny = (nodes[b + nearY] - oy) * iy;
      let nz = (nodes[b + nearZ] - oz) * iz;
      let fx = (nodes[b + farX] - ox) * ix;
      let fy = (nodes[b + farY] - oy) * iy;
      let fz = (nodes[b + farZ] - oz) * iz;
      const hitL =
        Number(nx <= fy) &
        Number(nx <= fz) &
        Number(ny <= fx) &
        Number(ny <= fz) &
        Number(nz <= fx) &
        Number(nz <= fy) &
        Number(nx <= tMax) &
        Number(ny <= tMax) &
        Number(nz <= tMax) &
        Number(fx >= 0) &
        Number(fy >= 0) &
        Number(fz >= 0);
      const c = b + N_RIGHT_BOX;
      nx = (nodes[c + nearX] - ox) * ix;
      ny = (nodes[c + nearY] - oy) * iy;
      nz = (nodes[c + nearZ] - oz) * iz;
      fx = (nodes[c + farX] - ox) * ix;
      fy = (nodes[c + farY] - oy) * iy;
      fz = (nodes[c + farZ] - oz) * iz;
      const hitR =
        Number(nx <= fy) &
        Number(nx <= fz) &
        Number(ny <= fx) &
        Number(ny <= fz) &
        Number(nz <= fx) &
        Number(nz <= fy) &
        Number(nx <= tMax) &
        Number(ny <= tMax) &
        Number(nz <= tMax) &
        Number(fx >= 0) &
        Number(fy >= 0) &
        Number(fz >= 0);
      if (hitL !== 0) {
        if (hitR !== 0) stack[sp++] = words[b + N_RIGHT];
        item = words[b + N_LEFT];
        continue;
      }
      if (hitR !== 0) {
        item = words[b + N_RIGHT];
        continue;
      }
    } else {
      const leaf = ~item;
      const first = leaf >> BVH_LEAF_BITS;
      for (let k = first, end = first + (leaf & BVH_LEAF_MASK); k < end; k++) {
        const ref = refs[k];
        const i = ref >> PRIM_KIND_BITS;
        switch (ref & PRIM_KIND_MASK) {
          case SHAPE_SPHERE:
            if (hitSphere(spheres, i, r)) return true;
            break;
          case SHAPE_QUAD:
            if (hitQuad(quads, i, r)) return true;
            break;
          case SHAPE_TRIANGLE:
            if (hitTriangle(triPositions, triIndices, i, tr, r)) return true;
            break;
        }
      }
    }
    if (sp === 0) return false;
    item = stack[--sp];
  }
}
