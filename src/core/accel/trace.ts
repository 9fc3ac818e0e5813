/**
 * Scene-level ray queries: the nearest hit (`intersectScene`) and any hit
 * before tMax (`occluded`, for shadow rays). Below the BVH threshold a plain
 * loop over the shapes (the quads regrouped by quad-list.ts); above it the
 * BVH (accel/bvh.ts, traversed in accel/traverse.ts), whose leaves dispatch
 * on each primitive's kind tag (accel/primitives.ts).
 *
 * The queries copy the ray into the scene's ray record (ray.ts: origin,
 * direction and the current far bound R_T; `occluded` leaves that to the
 * loop it calls, which does so only where a primitive test reads the
 * record), and the primitive tests
 * (`hitSphere`/`hitQuad` of intersect.ts, `hitTriangle`) read it and move R_T
 * to a closer hit. They take and
 * return no double: when V8 does not inline a call (it declines for a kind
 * that is rare in the scene), a double argument or result would be boxed on
 * the heap at every call.
 */
import { intersectBvh, occludedBvh } from './traverse.ts';
import { intersectInstanced } from './traverse-instanced.ts';
import type { SceneGeometry } from './scene-geometry.ts';
import { intersectSphere } from '../geometry/intersect.ts';
import {
  loadRay,
  SHAPE_QUAD,
  SHAPE_SPHERE,
  SHAPE_TRIANGLE,
  type Hit,
  type Ray,
} from '../geometry/ray.ts';
import { nearestQuad } from '../geometry/quad-list.ts';
import { hitTriangle, intersectTriangleBary, setTriangleRay } from '../geometry/triangle.ts';

export { RAY_RECORD_WORDS, R_DX, R_OX, R_T } from '../geometry/ray.ts';

export function intersectScene(scene: SceneGeometry, ray: Ray, hit: Hit): boolean {
  const r = scene.ray;
  loadRay(r, ray);
  // Two small functions rather than one big one: V8 optimises (and inlines
  // the primitive tests into) each far better.
  if (scene.triCount > 0) setTriangleRay(r[0], r[1], r[2], r[3], r[4], r[5], scene.triRay);
  const found =
    scene.bvh === null
      ? intersectList(scene, r, hit)
      : scene.instanceCount === 0
        ? intersectBvh(scene, r, hit)
        : intersectInstanced(scene, r, hit);
  if (found) {
    hit.t = r[6];
    if (hit.kind === SHAPE_TRIANGLE) triangleBarycentrics(scene, hit);
  }
  return found;
}

/**
 * Barycentrics of the kept triangle hit, recomputed once with the same ray constants
 * (an instance's object-space ones, which intersectInstanced left for its hit).
 */
function triangleBarycentrics(scene: SceneGeometry, hit: Hit): void {
  const th = scene.triHit;
  intersectTriangleBary(
    scene.triPositions,
    scene.triIndices,
    hit.index,
    hit.instance < 0 ? scene.triRay : scene.objTriRay,
    Infinity,
    th,
  );
  hit.b0 = th.b0;
  hit.b1 = th.b1;
  hit.b2 = th.b2;
}

/**
 * Whether anything lies on the ray in (0, ray.tMax). A dispatcher to one
 * function per structure, each loading the ray itself: 29 bytecode bytes, so
 * that V8 inlines it into the integrator's loop, whose inlining budget is
 * mostly spent by then (the former `occluded`, with the loading of the ray
 * record and the plain loops in it, was 300), and a shadow ray costs one
 * call, to the loop that does the work.
 */
export function occluded(scene: SceneGeometry, ray: Ray): boolean {
  return scene.bvh === null ? occludedList(scene, ray) : occludedBvh(scene, ray);
}

// The plain loops call the primitive tests with the ray in locals: each
// call runs once per shape and query, so V8 always inlines it.
function intersectList(scene: SceneGeometry, r: Float64Array, hit: Hit): boolean {
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

/**
 * Any hit among the plain loops' shapes. Unlike intersectList, the regrouped
 * quad loops (quad-list.ts) are written out here rather than called: they
 * exceed V8's inlining size limit, so a call would be a second one per
 * shadow ray in quad scenes.
 */
function occludedList(scene: SceneGeometry, ray: Ray): boolean {
  const ox = ray.ox,
    oy = ray.oy,
    oz = ray.oz,
    dx = ray.dx,
    dy = ray.dy,
    dz = ray.dz,
    tMax = ray.tMax;
  const spheres = scene.spheres;
  for (let i = 0, n = scene.sphereCount; i < n; i++) {
    if (intersectSphere(spheres, i, ox, oy, oz, dx, dy, dz, tMax) < tMax) return true;
  }
  const list = scene.quadList;
  const rec = list.axis;
  const start = list.axisStart;
  for (let a = 0; a < 3; a++) {
    const oa = a === 0 ? ox : a === 1 ? oy : oz;
    const da = a === 0 ? dx : a === 1 ? dy : dz;
    const ob = a === 0 ? oy : ox;
    const db = a === 0 ? dy : dx;
    const oc = a === 2 ? oy : oz;
    const dc = a === 2 ? dy : dz;
    for (let k = start[a], end = start[a + 1], o = k << 3; k < end; k++, o += 8) {
      const na = rec[o + 1];
      const t = (rec[o] - na * oa) / (na * da);
      if (!(t > 0 && t < tMax)) continue;
      const qb = ob + t * db - rec[o + 2];
      const qc = oc + t * dc - rec[o + 3];
      const s = qb * rec[o + 4] + qc * rec[o + 5];
      const v = qb * rec[o + 6] + qc * rec[o + 7];
      if ((Number(s >= 0) & Number(s <= 1) & Number(v >= 0) & Number(v <= 1)) !== 0) return true;
    }
  }
  const vert = list.vertical;
  for (let k = 0, n = list.verticalCount, o = 0; k < n; k++, o += 9) {
    const nx = vert[o + 1];
    const nz = vert[o + 2];
    const t = (vert[o] - (nx * ox + nz * oz)) / (nx * dx + nz * dz);
    if (!(t > 0 && t < tMax)) continue;
    const qx = ox + t * dx - vert[o + 3];
    const qy = oy + t * dy - vert[o + 4];
    const qz = oz + t * dz - vert[o + 5];
    const s = qx * vert[o + 6] + qz * vert[o + 7];
    const v = qy * vert[o + 8];
    if ((Number(s >= 0) & Number(s <= 1) & Number(v >= 0) & Number(v <= 1)) !== 0) return true;
  }
  const gen = list.general;
  for (let k = 0, n = list.generalCount, o = 0; k < n; k++, o += 13) {
    const nx = gen[o + 3];
    const ny = gen[o + 4];
    const nz = gen[o + 5];
    const t = (gen[o + 6] - (nx * ox + ny * oy + nz * oz)) / (nx * dx + ny * dy + nz * dz);
    if (!(t > 0 && t < tMax)) continue;
    const qx = ox + t * dx - gen[o];
    const qy = oy + t * dy - gen[o + 1];
    const qz = oz + t * dz - gen[o + 2];
    const s = qx * gen[o + 7] + qy * gen[o + 8] + qz * gen[o + 9];
    const v = qx * gen[o + 10] + qy * gen[o + 11] + qz * gen[o + 12];
    if ((Number(s >= 0) & Number(s <= 1) & Number(v >= 0) & Number(v <= 1)) !== 0) return true;
  }
  const triCount = scene.triCount;
  if (triCount > 0) {
    const r = scene.ray;
    loadRay(r, ray);
    const pos = scene.triPositions;
    const idx = scene.triIndices;
    const tr = scene.triRay;
    setTriangleRay(ox, oy, oz, dx, dy, dz, tr);
    for (let i = 0; i < triCount; i++) if (hitTriangle(pos, idx, i, tr, r)) return true;
  }
  return false;
}
