/**
 * Scene-level ray queries: the nearest hit (`intersectScene`) and any hit
 * before tMax (`occluded`, for shadow rays). Below the BVH threshold a plain
 * loop over the shapes is faster than any hierarchy; above it the BVH is
 * traversed front to back with a preallocated stack. The leaf loops
 * dispatch on each primitive's kind tag (accel/primitives.ts).
 */
import type { CompiledScene } from '../scene/compile.ts';
import { intersectQuad, intersectSphere } from './intersect.ts';
import { SHAPE_QUAD, SHAPE_SPHERE, SHAPE_TRIANGLE, type Hit, type Ray } from './ray.ts';
import { hitTriangle, intersectTriangleBary, setTriangleRay } from './triangle.ts';
import {
  BVH_LEAF_BITS,
  BVH_LEAF_MASK,
  BVH_NODE_WORDS,
  N_LEFT,
  N_RIGHT,
  N_RIGHT_BOX,
} from '../accel/bvh.ts';
import { PRIM_KIND_BITS, PRIM_KIND_MASK } from '../accel/primitives.ts';

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
  const triCount = scene.triCount;
  if (triCount > 0) {
    const tr = scene.triRay;
    setTriangleRay(ox, oy, oz, dx, dy, dz, tr);
    const pos = scene.triPositions;
    const idx = scene.triIndices;
    const best = scene.stackT;
    best[0] = tBest;
    for (let i = 0; i < triCount; i++) {
      if (hitTriangle(pos, idx, i, tr, best)) {
        kind = SHAPE_TRIANGLE;
        index = i;
      }
    }
    tBest = best[0];
  }
  if (kind < 0) return false;
  hit.t = tBest;
  hit.kind = kind;
  hit.index = index;
  if (kind === SHAPE_TRIANGLE) triangleBarycentrics(scene, hit);
  return true;
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

/**
 * Nearest hit through the BVH (layout in accel/bvh.ts). The loop visits
 * items: an interior node tests both children's boxes, enters the nearer
 * and pushes the other with its entry distance (skipped when popped if a
 * closer hit was found meanwhile); a leaf tests its primitives. Leaves are
 * handled in one place so V8 inlines every intersector exactly once: a call
 * that is not inlined would box its six double arguments on the heap.
 */
function intersectBvh(scene: CompiledScene, ray: Ray, hit: Hit): boolean {
  const bvh = scene.bvh!;
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  // The nearest distance so far lives in stackT[0] (the stack starts at 1):
  // kept in a local, V8 gave it a tagged representation here and boxed a
  // HeapNumber at every update (0.7 GB per 400k paths on the 10k-sphere
  // scene; bench/inproc.ts with the heap sampler).
  const tb = scene.stackT;
  tb[0] = ray.tMax;
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
  if (scene.triCount > 0) setTriangleRay(ox, oy, oz, dx, dy, dz, tr);
  const stack = scene.stack;
  const stackT = scene.stackT;
  // Slab test with the near/far planes chosen once per ray by the sign of
  // the direction (Williams et al., "An Efficient and Robust Ray–Box
  // Intersection Algorithm", JGT 2005). 1/0 = ±Infinity keeps axis-parallel
  // rays correct; a NaN from 0·∞ fails every comparison and so narrows
  // nothing: the box is kept.
  const ix = 1 / dx,
    iy = 1 / dy,
    iz = 1 / dz;
  const nearX = ix < 0 ? 3 : 0,
    nearY = iy < 0 ? 4 : 1,
    nearZ = iz < 0 ? 5 : 2;
  const farX = 3 - nearX,
    farY = 5 - nearY,
    farZ = 7 - nearZ;
  let sp = 1;
  let item = 0;
  for (;;) {
    if (item >= 0) {
      const b = item * BVH_NODE_WORDS;
      let l0 = 0;
      let l1 = tb[0];
      let v = (nodes[b + nearX] - ox) * ix;
      if (v > l0) l0 = v;
      v = (nodes[b + nearY] - oy) * iy;
      if (v > l0) l0 = v;
      v = (nodes[b + nearZ] - oz) * iz;
      if (v > l0) l0 = v;
      v = (nodes[b + farX] - ox) * ix;
      if (v < l1) l1 = v;
      v = (nodes[b + farY] - oy) * iy;
      if (v < l1) l1 = v;
      v = (nodes[b + farZ] - oz) * iz;
      if (v < l1) l1 = v;
      const c = b + N_RIGHT_BOX;
      let r0 = 0;
      let r1 = tb[0];
      v = (nodes[c + nearX] - ox) * ix;
      if (v > r0) r0 = v;
      v = (nodes[c + nearY] - oy) * iy;
      if (v > r0) r0 = v;
      v = (nodes[c + nearZ] - oz) * iz;
      if (v > r0) r0 = v;
      v = (nodes[c + farX] - ox) * ix;
      if (v < r1) r1 = v;
      v = (nodes[c + farY] - oy) * iy;
      if (v < r1) r1 = v;
      v = (nodes[c + farZ] - oz) * iz;
      if (v < r1) r1 = v;
      if (l0 <= l1) {
        if (r0 <= r1) {
          // Both: the nearer now, the other later.
          if (r0 < l0) {
            stack[sp] = words[b + N_LEFT];
            stackT[sp++] = l0;
            item = words[b + N_RIGHT];
          } else {
            stack[sp] = words[b + N_RIGHT];
            stackT[sp++] = r0;
            item = words[b + N_LEFT];
          }
        } else item = words[b + N_LEFT];
        continue;
      }
      if (r0 <= r1) {
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
            const t = intersectSphere(spheres, i, ox, oy, oz, dx, dy, dz, tb[0]);
            if (t < tb[0]) {
              tb[0] = t;
              kind = SHAPE_SPHERE;
              index = i;
            }
            break;
          }
          case SHAPE_QUAD: {
            const t = intersectQuad(quads, i, ox, oy, oz, dx, dy, dz, tb[0]);
            if (t < tb[0]) {
              tb[0] = t;
              kind = SHAPE_QUAD;
              index = i;
            }
            break;
          }
          case SHAPE_TRIANGLE:
            if (hitTriangle(triPositions, triIndices, i, tr, tb)) {
              kind = SHAPE_TRIANGLE;
              index = i;
            }
            break;
        }
      }
    }
    // Next: the latest pending item that may still hold a closer hit
    // (-1 is no item: a leaf's code is at most ~1).
    item = -1;
    while (sp > 1) {
      sp--;
      if (stackT[sp] < tb[0]) {
        item = stack[sp];
        break;
      }
    }
    if (item === -1) break;
  }
  if (kind < 0) return false;
  hit.t = tb[0];
  hit.kind = kind;
  hit.index = index;
  if (kind === SHAPE_TRIANGLE) triangleBarycentrics(scene, hit);
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
  const triCount = scene.triCount;
  if (triCount > 0) {
    const tr = scene.triRay;
    setTriangleRay(ox, oy, oz, dx, dy, dz, tr);
    const pos = scene.triPositions;
    const idx = scene.triIndices;
    const best = scene.stackT;
    for (let i = 0; i < triCount; i++) {
      best[0] = tMax;
      if (hitTriangle(pos, idx, i, tr, best)) return true;
    }
  }
  return false;
}

/** Any hit through the BVH: children in stored order, the first hit ends the search. */
function occludedBvh(scene: CompiledScene, ray: Ray): boolean {
  const bvh = scene.bvh!;
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz;
  const dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz;
  const tMax = ray.tMax;
  const nodes = bvh.nodes;
  const words = bvh.words;
  const refs = bvh.refs;
  const spheres = scene.spheres;
  const quads = scene.quads;
  const triPositions = scene.triPositions;
  const triIndices = scene.triIndices;
  const tr = scene.triRay;
  if (scene.triCount > 0) setTriangleRay(ox, oy, oz, dx, dy, dz, tr);
  const stack = scene.stack;
  // Scratch for the triangle test's distance (occlusion keeps no nearest hit).
  const stackT = scene.stackT;
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
  let item = 0;
  for (;;) {
    if (item >= 0) {
      const b = item * BVH_NODE_WORDS;
      let l0 = 0;
      let l1 = tMax;
      let v = (nodes[b + nearX] - ox) * ix;
      if (v > l0) l0 = v;
      v = (nodes[b + nearY] - oy) * iy;
      if (v > l0) l0 = v;
      v = (nodes[b + nearZ] - oz) * iz;
      if (v > l0) l0 = v;
      v = (nodes[b + farX] - ox) * ix;
      if (v < l1) l1 = v;
      v = (nodes[b + farY] - oy) * iy;
      if (v < l1) l1 = v;
      v = (nodes[b + farZ] - oz) * iz;
      if (v < l1) l1 = v;
      const c = b + N_RIGHT_BOX;
      let r0 = 0;
      let r1 = tMax;
      v = (nodes[c + nearX] - ox) * ix;
      if (v > r0) r0 = v;
      v = (nodes[c + nearY] - oy) * iy;
      if (v > r0) r0 = v;
      v = (nodes[c + nearZ] - oz) * iz;
      if (v > r0) r0 = v;
      v = (nodes[c + farX] - ox) * ix;
      if (v < r1) r1 = v;
      v = (nodes[c + farY] - oy) * iy;
      if (v < r1) r1 = v;
      v = (nodes[c + farZ] - oz) * iz;
      if (v < r1) r1 = v;
      if (l0 <= l1) {
        if (r0 <= r1) stack[sp++] = words[b + N_RIGHT];
        item = words[b + N_LEFT];
        continue;
      }
      if (r0 <= r1) {
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
            if (intersectSphere(spheres, i, ox, oy, oz, dx, dy, dz, tMax) < tMax) return true;
            break;
          case SHAPE_QUAD:
            if (intersectQuad(quads, i, ox, oy, oz, dx, dy, dz, tMax) < tMax) return true;
            break;
          case SHAPE_TRIANGLE:
            stackT[0] = tMax;
            if (hitTriangle(triPositions, triIndices, i, tr, stackT)) return true;
            break;
        }
      }
    }
    if (sp === 0) return false;
    item = stack[--sp];
  }
}
