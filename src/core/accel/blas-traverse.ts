/**
 * An instance's side of the two-level traversal (traverse-instanced.ts): the ray carried
 * into the instance's object space by its world-to-object matrix (accel/instances.ts),
 * its direction not renormalised so that distances are the same in both spaces, and the
 * instance's BLAS traversed with it — triangles only, the box tests of intersectBvh
 * (traverse.ts), its own stack (scene.blasStack), the far bound shared with the world
 * ray so that the nearest hit over everything is kept.
 */
import type { SceneGeometry } from './scene-geometry.ts';
import { hitTriangle, setTriangleRay } from '../geometry/triangle.ts';

/**
 * Loads instance k's object-space ray into scene.objRay (far bound r[R_T] unchanged:
 * the distance is the same in both spaces) and its triangle constants.
 */
export function objectRay(
  scene: SceneGeometry,
  k: number,
  ox: number,
  oy: number,
  oz: number,
  dx: number,
  dy: number,
  dz: number,
): void {
  const m = scene.instXform;
  const o = k * 12;
  const q = scene.objRay;
  q[0] = m[o] * ox + m[o + 3] * oy + m[o + 6] * oz + m[o + 9];
  q[1] = m[o + 1] * ox + m[o + 4] * oy + m[o + 7] * oz + m[o + 10];
  q[2] = m[o + 2] * ox + m[o + 5] * oy + m[o + 8] * oz + m[o + 11];
  q[3] = m[o] * dx + m[o + 3] * dy + m[o + 6] * dz;
  q[4] = m[o + 1] * dx + m[o + 4] * dy + m[o + 7] * dz;
  q[5] = m[o + 2] * dx + m[o + 5] * dy + m[o + 8] * dz;
  setTriangleRay(q[0], q[1], q[2], q[3], q[4], q[5], scene.objTriRay);
}

/**
 * The nearest triangle of instance k closer than r[R_T] (which it then moves), or −1.
 * Returns an integer (no boxing where V8 does not inline the call).
 */
export function intersectInstance(scene: SceneGeometry, k: number, r: Float64Array): number {
  objectRay(scene, k, r[0], r[1], r[2], r[3], r[4], r[5]);
  const q = scene.objRay;
  q[6] = r[6];
  const tri = traverseBlas(scene, scene.instBlas[k], q, false);
  if (tri >= 0) r[6] = q[6];
  return tri;
}

/** Whether instance k has a triangle before r[R_T]. */
export function occludedInstance(scene: SceneGeometry, k: number, r: Float64Array): boolean {
  objectRay(scene, k, r[0], r[1], r[2], r[3], r[4], r[5]);
  const q = scene.objRay;
  q[6] = r[6];
  return traverseBlas(scene, scene.instBlas[k], q, true) >= 0;
}

/**
 * A BLAS (triangles only) from its root node, with the object-space ray q: the nearest
 * hit's triangle (q[R_T] moved to it), or with `any`, the first hit found; −1 for none.
 * The box tests are intersectBvh's.
 */
function traverseBlas(scene: SceneGeometry, root: number, q: Float64Array, any: boolean): number {
  const nodes = scene.blasBoxes;
  const words = scene.blasNodes;
  const refs = scene.blasRefs;
  const triPositions = scene.triPositions;
  const triIndices = scene.triIndices;
  const tr = scene.objTriRay;
  const stack = scene.blasStack;
  const stackT = scene.blasStackT;
  const ox = q[0],
    oy = q[1],
    oz = q[2];
  const ix = 1 / q[3],
    iy = 1 / q[4],
    iz = 1 / q[5];
  const nearX = ix < 0 ? 3 : 0,
    nearY = iy < 0 ? 4 : 1,
    nearZ = iz < 0 ? 5 : 2;
  const farX = 3 - nearX,
    farY = 5 - nearY,
    farZ = 7 - nearZ;
  let found = -1;
  let sp = 0;
  let item = root;
  traversal: for (;;) {
    if (item >= 0) {
      const b = item << 4;
      const t = q[6];
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
      const leaf = ~item;
      const first = leaf >> 3;
      for (let k = first, end = first + (leaf & 7); k < end; k++) {
        const i = refs[k] >> 2;
        if (hitTriangle(triPositions, triIndices, i, tr, q)) {
          if (any) return i;
          found = i;
        }
      }
    }
    do {
      if (sp === 0) break traversal;
      sp--;
    } while (!(stackT[sp] < q[6]));
    item = stack[sp];
  }
  return found;
}
