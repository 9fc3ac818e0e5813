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
  // Two small functions rather than one big one: V8 optimises (and inlines
  // the primitive tests into) each far better.
  return scene.bvh === null ? intersectList(scene, ray, hit) : intersectBvh(scene, ray, hit);
}

function intersectList(scene: CompiledScene, ray: Ray, hit: Hit): boolean {
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  let tBest = ray.tMax;
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
  const quads = scene.quads;
  for (let i = 0, n = scene.quadCount; i < n; i++) {
    const t = intersectQuad(quads, i, ox, oy, oz, dx, dy, dz, tBest);
    if (t < tBest) {
      tBest = t;
      kind = SHAPE_QUAD;
      index = i;
    }
  }
  if (kind < 0) return false;
  hit.t = tBest;
  hit.kind = kind;
  hit.index = index;
  return true;
}

function intersectBvh(scene: CompiledScene, ray: Ray, hit: Hit): boolean {
  const bvh = scene.bvh!;
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  let tBest = ray.tMax;
  let kind = -1;
  let index = -1;
  const bounds = bvh.bounds;
  const nodes = bvh.nodes;
  const primIds = bvh.primIds;
  const stack = bvh.stack;
  const sphereCount = scene.sphereCount;
  const spheres = scene.spheres;
  const quads = scene.quads;
  // Slab test with the near/far planes chosen once per ray by the sign of
  // the direction (Williams et al., "An Efficient and Robust Ray–Box
  // Intersection Algorithm", JGT 2005). 1/0 = ±Infinity keeps axis-parallel
  // rays correct; a NaN from 0·∞ compares false and so keeps the box.
  const ix = 1 / dx,
    iy = 1 / dy,
    iz = 1 / dz;
  const nearX = ix < 0 ? 3 : 0,
    nearY = iy < 0 ? 4 : 1,
    nearZ = iz < 0 ? 5 : 2;
  const farX = 3 - nearX,
    farY = 5 - nearY,
    farZ = 7 - nearZ;
  let sp = 0;
  let node = 0;
  for (;;) {
    const b = node * 6;
    let tNear = (bounds[b + nearX] - ox) * ix;
    let tFar = (bounds[b + farX] - ox) * ix;
    const ty0 = (bounds[b + nearY] - oy) * iy;
    const ty1 = (bounds[b + farY] - oy) * iy;
    const tz0 = (bounds[b + nearZ] - oz) * iz;
    const tz1 = (bounds[b + farZ] - oz) * iz;
    if (ty0 > tNear) tNear = ty0;
    if (tz0 > tNear) tNear = tz0;
    if (ty1 < tFar) tFar = ty1;
    if (tz1 < tFar) tFar = tz1;
    if (tNear < 0) tNear = 0;
    if (tFar > tBest) tFar = tBest;
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
        const neg = axis === 0 ? ix < 0 : axis === 1 ? iy < 0 : iz < 0;
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
  if (kind < 0) return false;
  hit.t = tBest;
  hit.kind = kind;
  hit.index = index;
  return true;
}

/** Whether anything lies on the ray in (0, ray.tMax). */
export function occluded(scene: CompiledScene, ray: Ray): boolean {
  return scene.bvh === null ? occludedList(scene, ray) : occludedBvh(scene, ray);
}

function occludedList(scene: CompiledScene, ray: Ray): boolean {
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  const tMax = ray.tMax;
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

function occludedBvh(scene: CompiledScene, ray: Ray): boolean {
  const bvh = scene.bvh!;
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  const tMax = ray.tMax;
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
  const nearX = ix < 0 ? 3 : 0,
    nearY = iy < 0 ? 4 : 1,
    nearZ = iz < 0 ? 5 : 2;
  const farX = 3 - nearX,
    farY = 5 - nearY,
    farZ = 7 - nearZ;
  let sp = 0;
  let node = 0;
  for (;;) {
    const b = node * 6;
    let tNear = (bounds[b + nearX] - ox) * ix;
    let tFar = (bounds[b + farX] - ox) * ix;
    const ty0 = (bounds[b + nearY] - oy) * iy;
    const ty1 = (bounds[b + farY] - oy) * iy;
    const tz0 = (bounds[b + nearZ] - oz) * iz;
    const tz1 = (bounds[b + farZ] - oz) * iz;
    if (ty0 > tNear) tNear = ty0;
    if (tz0 > tNear) tNear = tz0;
    if (ty1 < tFar) tFar = ty1;
    if (tz1 < tFar) tFar = tz1;
    if (tNear < 0) tNear = 0;
    if (tFar > tMax) tFar = tMax;
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
