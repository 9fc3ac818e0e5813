/**
 * Scene-level ray queries: the nearest hit (`intersectScene`) and any hit
 * before tMax (`occluded`, for shadow rays). Below the BVH threshold a plain
 * loop over the shapes is faster than any hierarchy; above it the BVH is
 * traversed front to back with a preallocated stack.
 */
import type { CompiledScene } from '../scene/compile.ts';
import { intersectQuad, intersectSphere } from './intersect.ts';
import { SHAPE_QUAD, SHAPE_SPHERE, type Hit, type Ray } from './ray.ts';

export function intersectScene(scene: CompiledScene, ray: Ray, hit: Hit): boolean {
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  let tBest = ray.tMax;
  let kind = -1;
  let index = -1;
  const bvh = scene.bvh;
  if (bvh === null) {
    const spheres = scene.spheres;
    for (let i = 0, n = scene.sphereCount; i < n; i++) {
      const t = intersectSphere(spheres, i, ox, oy, oz, dx, dy, dz, tBest);
      if (t < tBest) {
        tBest = t;
        kind = SHAPE_SPHERE;
        index = i;
      }
    }
    const quads = scene.quads;
    for (let i = 0, n = scene.quadCount; i < n; i++) {
      const t = intersectQuad(quads, i, ox, oy, oz, dx, dy, dz, tBest);
      if (t < tBest) {
        tBest = t;
        kind = SHAPE_QUAD;
        index = i;
      }
    }
  } else {
    const bounds = bvh.bounds;
    const nodes = bvh.nodes;
    const primIds = bvh.primIds;
    const stack = bvh.stack;
    const sphereCount = scene.sphereCount;
    const spheres = scene.spheres;
    const quads = scene.quads;
    // 1/0 = ±Infinity keeps the slab test correct for axis-parallel rays.
    const ix = 1 / dx,
      iy = 1 / dy,
      iz = 1 / dz;
    const negX = ix < 0,
      negY = iy < 0,
      negZ = iz < 0;
    let sp = 0;
    let node = 0;
    for (;;) {
      const b = node * 6;
      const tx0 = ((negX ? bounds[b + 3] : bounds[b]) - ox) * ix;
      const tx1 = ((negX ? bounds[b] : bounds[b + 3]) - ox) * ix;
      const ty0 = ((negY ? bounds[b + 4] : bounds[b + 1]) - oy) * iy;
      const ty1 = ((negY ? bounds[b + 1] : bounds[b + 4]) - oy) * iy;
      const tz0 = ((negZ ? bounds[b + 5] : bounds[b + 2]) - oz) * iz;
      const tz1 = ((negZ ? bounds[b + 2] : bounds[b + 5]) - oz) * iz;
      // NaN (0·∞ for an origin on a slab plane) must not reject the box.
      const tNear = Math.max(tx0 > ty0 ? tx0 : ty0, tz0, 0);
      const tFar = Math.min(tx1 < ty1 ? tx1 : ty1, tz1, tBest);
      if (!(tNear > tFar)) {
        const count = nodes[node * 3 + 1];
        if (count > 0) {
          const first = nodes[node * 3];
          for (let k = first, end = first + count; k < end; k++) {
            const p = primIds[k];
            if (p < sphereCount) {
              const t = intersectSphere(spheres, p, ox, oy, oz, dx, dy, dz, tBest);
              if (t < tBest) {
                tBest = t;
                kind = SHAPE_SPHERE;
                index = p;
              }
            } else {
              const q = p - sphereCount;
              const t = intersectQuad(quads, q, ox, oy, oz, dx, dy, dz, tBest);
              if (t < tBest) {
                tBest = t;
                kind = SHAPE_QUAD;
                index = q;
              }
            }
          }
        } else {
          // Visit the child on the ray's near side first.
          const axis = nodes[node * 3 + 2];
          const neg = axis === 0 ? negX : axis === 1 ? negY : negZ;
          const right = nodes[node * 3];
          if (neg) {
            stack[sp++] = node + 1;
            node = right;
          } else {
            stack[sp++] = right;
            node = node + 1;
          }
          continue;
        }
      }
      if (sp === 0) break;
      node = stack[--sp];
    }
  }
  if (kind < 0) return false;
  hit.t = tBest;
  hit.kind = kind;
  hit.index = index;
  return true;
}

/** Whether anything lies on the ray in (0, ray.tMax). */
export function occluded(scene: CompiledScene, ray: Ray): boolean {
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  const tMax = ray.tMax;
  const bvh = scene.bvh;
  if (bvh === null) {
    const spheres = scene.spheres;
    for (let i = 0, n = scene.sphereCount; i < n; i++) {
      if (intersectSphere(spheres, i, ox, oy, oz, dx, dy, dz, tMax) < tMax) return true;
    }
    const quads = scene.quads;
    for (let i = 0, n = scene.quadCount; i < n; i++) {
      if (intersectQuad(quads, i, ox, oy, oz, dx, dy, dz, tMax) < tMax) return true;
    }
    return false;
  }
  const bounds = bvh.bounds;
  const nodes = bvh.nodes;
  const primIds = bvh.primIds;
  const stack = bvh.stack;
  const sphereCount = scene.sphereCount;
  const spheres = scene.spheres;
  const quads = scene.quads;
  const ix = 1 / dx,
    iy = 1 / dy,
    iz = 1 / dz;
  const negX = ix < 0,
    negY = iy < 0,
    negZ = iz < 0;
  let sp = 0;
  let node = 0;
  for (;;) {
    const b = node * 6;
    const tx0 = ((negX ? bounds[b + 3] : bounds[b]) - ox) * ix;
    const tx1 = ((negX ? bounds[b] : bounds[b + 3]) - ox) * ix;
    const ty0 = ((negY ? bounds[b + 4] : bounds[b + 1]) - oy) * iy;
    const ty1 = ((negY ? bounds[b + 1] : bounds[b + 4]) - oy) * iy;
    const tz0 = ((negZ ? bounds[b + 5] : bounds[b + 2]) - oz) * iz;
    const tz1 = ((negZ ? bounds[b + 2] : bounds[b + 5]) - oz) * iz;
    const tNear = Math.max(tx0 > ty0 ? tx0 : ty0, tz0, 0);
    const tFar = Math.min(tx1 < ty1 ? tx1 : ty1, tz1, tMax);
    if (!(tNear > tFar)) {
      const count = nodes[node * 3 + 1];
      if (count > 0) {
        const first = nodes[node * 3];
        for (let k = first, end = first + count; k < end; k++) {
          const p = primIds[k];
          const t =
            p < sphereCount
              ? intersectSphere(spheres, p, ox, oy, oz, dx, dy, dz, tMax)
              : intersectQuad(quads, p - sphereCount, ox, oy, oz, dx, dy, dz, tMax);
          if (t < tMax) return true;
        }
      } else {
        stack[sp++] = nodes[node * 3];
        node = node + 1;
        continue;
      }
    }
    if (sp === 0) return false;
    node = stack[--sp];
  }
}
