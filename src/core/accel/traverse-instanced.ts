/**
 * Ray queries through a two-level hierarchy (accel/instances.ts): the scene's BVH with
 * instances among its primitives (the TLAS), each instance a transform and a BLAS.
 * `intersectInstanced` and `occludedInstanced` are intersectBvh and occludedBvh
 * (traverse.ts) with one more leaf case, PRIM_INSTANCE, written out separately so that
 * scenes without instances run traverse.ts's loops unchanged (the same code, so the
 * same speed: the leaf switch is the hot loop).
 *
 * At an instance, the ray goes into object space by the instance's world-to-object
 * matrix, its direction *not* renormalised: o' = W·o + w, d' = W·d, so a point
 * o + t·d maps to o' + t·d' and the distance t is the same in both spaces (pbr-book 4e
 * §6.1.3, "Transformed primitives"). The BLAS's triangles then move the shared far
 * bound r[R_T] as any other primitive does, and the nearest hit over world primitives
 * and every instance is kept. The object-space ray and its triangle constants are
 * per-scene scratch (objRay, objTriRay); the BLAS has its own stack.
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
  SHAPE_SPHERE,
  SHAPE_QUAD,
  SHAPE_TRIANGLE,
  type Hit,
  type Ray,
} from '../geometry/ray.ts';
import { hitTriangle, setTriangleRay } from '../geometry/triangle.ts';
import { intersectInstance, objectRay, occludedInstance } from './blas-traverse.ts';

/**
 * Nearest hit through the TLAS and the instances' BLASes; as intersectBvh, and sets
 * hit.instance (−1 for a world-space primitive).
 */
export function intersectInstanced(scene: SceneGeometry, r: Float64Array, hit: Hit): boolean {
  const bvh = scene.bvh!;
  const ox = r[0],
    oy = r[1],
    oz = r[2];
  const ix = 1 / r[3],
    iy = 1 / r[4],
    iz = 1 / r[5];
  let kind = -1;
  let index = -1;
  let instance = -1;
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
              instance = -1;
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
            instance = -1;
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
            instance = -1;
            index = i;
            break;
          }
          case 2: // SHAPE_TRIANGLE
            if (hitTriangle(triPositions, triIndices, i, tr, r)) {
              kind = SHAPE_TRIANGLE;
              index = i;
              instance = -1;
            }
            break;
          case 3: {
            // PRIM_INSTANCE: its BLAS, in object space.
            const tri = intersectInstance(scene, i, r);
            if (tri >= 0) {
              kind = SHAPE_TRIANGLE;
              index = tri;
              instance = i;
            }
            break;
          }
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
  hit.instance = instance;
  if (kind < 0) return false;
  hit.kind = kind;
  hit.index = index;
  // The barycentrics (trace.ts) are recomputed with the object-space ray of the hit.
  if (instance >= 0) objectRay(scene, instance, r[0], r[1], r[2], r[3], r[4], r[5]);
  return true;
}

/**
 * Any hit through the TLAS and the instances' BLASes (occludedBvh with instances).
 */
export function occludedInstanced(scene: SceneGeometry, ray: Ray): boolean {
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
          case 3: // PRIM_INSTANCE
            if (occludedInstance(scene, i, r)) return true;
            break;
        }
      }
    }
    if (sp === 0) return false;
    item = stack[--sp];
  }
}
