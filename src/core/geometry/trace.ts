/**
 * Scene-level ray queries: the nearest hit (`intersectScene`) and any hit
 * before tMax (`occluded`, for shadow rays). Below the BVH threshold a plain
 * loop over the shapes (the quads regrouped by quad-list.ts); above it the
 * BVH (accel/bvh.ts, traversed in accel/traverse.ts), whose leaves dispatch
 * on each primitive's kind tag (accel/primitives.ts).
 *
 * The queries copy the ray into the scene's ray record (ray.ts: origin,
 * direction and the current far bound R_T), and the primitive tests
 * (`hitSphere`/`hitQuad` of intersect.ts, `hitTriangle`) read it and move R_T
 * to a closer hit. They take and
 * return no double: when V8 does not inline a call (it declines for a kind
 * that is rare in the scene), a double argument or result would be boxed on
 * the heap at every call.
 */
import { intersectBvh, occludedBvh } from '../accel/traverse.ts';
import type { CompiledScene } from '../scene/compile.ts';
import { intersectSphere } from './intersect.ts';
import { SHAPE_QUAD, SHAPE_SPHERE, SHAPE_TRIANGLE, type Hit, type Ray } from './ray.ts';
import { anyQuad, nearestQuad } from './quad-list.ts';
import { hitTriangle, intersectTriangleBary, setTriangleRay } from './triangle.ts';

export { RAY_RECORD_WORDS, R_DX, R_OX, R_T } from './ray.ts';

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
