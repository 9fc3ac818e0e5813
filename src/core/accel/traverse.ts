/**
 * Ray queries through the BVH (layout in bvh.ts): the nearest hit
 * (`intersectBvh`) and any hit (`occludedBvh`), called by accel/trace.ts
 * with the ray in the scene's ray record (geometry/ray.ts: origin,
 * direction, far bound r[6]).
 *
 * Offsets are written as literals (node words 16 per node, right box at 6,
 * children at 12 and 13; leaf codes ~(first << 3 | count); references
 * index << 2 | kind; spheres 4 and quads 20 numbers per record, the quad
 * fields of geometry/shapes.ts): in the bundle an imported constant is a
 * context load and a Smi check at each use, and an overflow-checked
 * multiply for a stride. tests/unit/core/bvh.test.ts checks that the literals
 * match the named layout.
 */
import type { SceneGeometry } from './scene-geometry.ts';
import {
  hitQuad,
  hitSphere,
  intersectSphereScaled,
  SPHERE_HUGE,
  SPHERE_TINY,
} from '../geometry/intersect.ts';
import {
  loadRay,
  SHAPE_QUAD,
  SHAPE_SPHERE,
  SHAPE_TRIANGLE,
  type Hit,
  type Ray,
} from '../geometry/ray.ts';
import { hitTriangle, setTriangleRay } from '../geometry/triangle.ts';
import { occludedInstanced } from './traverse-instanced.ts';

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
 * bit; tests/unit/core/bvh.test.ts compares with the plain loop) rather than
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
export function intersectBvh(scene: SceneGeometry, r: Float64Array, hit: Hit): boolean {
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
      const b = item << 4;
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
      const c = b + 6;
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
          stack[sp] = words[b + 12];
          stackT[sp++] = eL;
          item = words[b + 13];
        } else {
          stack[sp] = words[b + 13];
          stackT[sp++] = eR;
          item = words[b + 12];
        }
        continue;
      }
      if (hitL !== 0) {
        item = words[b + 12];
        continue;
      }
      if (hitR !== 0) {
        item = words[b + 13];
        continue;
      }
    } else {
      // A leaf: ~(first << BVH_LEAF_BITS | count).
      const leaf = ~item;
      const first = leaf >> 3;
      for (let k = first, end = first + (leaf & 7); k < end; k++) {
        const ref = refs[k];
        const i = ref >> 2;
        switch (ref & 3) {
          case 0: {
            // SHAPE_SPHERE
            // intersectSphere (intersect.ts) written out: see "Leaf tests by hand" above.
            const o = i << 2;
            const rad = spheres[o + 3];
            const dx = r[3],
              dy = r[4],
              dz = r[5];
            if (!(rad < SPHERE_HUGE && rad > SPHERE_TINY)) {
              // Radii beyond 2^±400, out of line (intersect.ts).
              const t = intersectSphereScaled(spheres, i, ox, oy, oz, dx, dy, dz, r[6]);
              if (!(t < r[6])) break;
              r[6] = t;
              kind = SHAPE_SPHERE;
              index = i;
              break;
            }
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
          case 1: {
            // SHAPE_QUAD
            // intersectQuad (intersect.ts) written out.
            const o = i * 20;
            const dx = r[3],
              dy = r[4],
              dz = r[5];
            const nx = quads[o + 9];
            const ny = quads[o + 10];
            const nz = quads[o + 11];
            const t =
              (quads[o + 12] - (nx * ox + ny * oy + nz * oz)) / (nx * dx + ny * dy + nz * dz);
            if (!(t > 0 && t < r[6])) break;
            const qx = ox + t * dx - quads[o];
            const qy = oy + t * dy - quads[o + 1];
            const qz = oz + t * dz - quads[o + 2];
            const qs = qx * quads[o + 13] + qy * quads[o + 14] + qz * quads[o + 15];
            const qv = qx * quads[o + 16] + qy * quads[o + 17] + qz * quads[o + 18];
            if ((Number(qs >= 0) & Number(qs <= 1) & Number(qv >= 0) & Number(qv <= 1)) === 0)
              break;
            r[6] = t;
            kind = SHAPE_QUAD;
            index = i;
            break;
          }
          case 2: // SHAPE_TRIANGLE
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

/**
 * Any hit through the BVH: the box test of intersectBvh; the first hit ends
 * the search. It loads the ray record itself (rather than trace.ts's
 * `occluded`, which stays small enough to be inlined; see there).
 */
export function occludedBvh(scene: SceneGeometry, ray: Ray): boolean {
  // Instances: the same loop with one more leaf case (traverse-instanced.ts).
  if (scene.instanceCount !== 0) return occludedInstanced(scene, ray);
  const bvh = scene.bvh!;
  const r = scene.ray;
  loadRay(r, ray);
  if (scene.triCount > 0) setTriangleRay(r[0], r[1], r[2], r[3], r[4], r[5], scene.triRay);
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
      const b = item << 4;
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
      const c = b + 6;
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
        if (hitR !== 0) stack[sp++] = words[b + 13];
        item = words[b + 12];
        continue;
      }
      if (hitR !== 0) {
        item = words[b + 13];
        continue;
      }
    } else {
      const leaf = ~item;
      const first = leaf >> 3;
      for (let k = first, end = first + (leaf & 7); k < end; k++) {
        const ref = refs[k];
        const i = ref >> 2;
        switch (ref & 3) {
          case 0: // SHAPE_SPHERE
            if (hitSphere(spheres, i, r)) return true;
            break;
          case 1: // SHAPE_QUAD
            if (hitQuad(quads, i, r)) return true;
            break;
          case 2: // SHAPE_TRIANGLE
            if (hitTriangle(triPositions, triIndices, i, tr, r)) return true;
            break;
        }
      }
    }
    if (sp === 0) return false;
    item = stack[--sp];
  }
}
