/**
 * The regrouped quad loops (src/core/geometry/quad-list.ts) give exactly the
 * answers of the index-ordered loop over intersectQuad: the same nearest quad
 * (lowest index on ties), the same distance bit for bit, the same occlusion
 * (trace.ts's occluded, whose list loop writes the quad groups out).
 */
import { describe, expect, it } from 'vitest';
import { intersectQuad } from '../../../src/core/geometry/intersect.ts';
import { QuadList, nearestQuad } from '../../../src/core/geometry/quad-list.ts';
import { Ray } from '../../../src/core/geometry/ray.ts';
import { occluded } from '../../../src/core/accel/trace.ts';
import type { CompiledScene } from '../../../src/core/scene/compile/compile.ts';
import { QUAD_STRIDE, writeQuadRecord } from '../../../src/core/geometry/shapes.ts';
import { pcgHash } from '../../../src/core/rng/pcg.ts';

let state = 1;
const rand = (): number => (state = pcgHash(state + 1)) / 4294967296;
const pick = <T>(xs: T[]): T => xs[Math.floor(rand() * xs.length)];

/** Quads of every group: axis-aligned (edges on axes or rotated in the plane), vertical, general. */
function makeQuads(): number[][][] {
  const out: number[][][] = [];
  const c = (): number[] => [pick([0, 1, -2, 3.5]), pick([0, 2, -1]), pick([0, -3, 1.25])];
  for (let k = 0; k < 40; k++) {
    const a = rand() * Math.PI * 2;
    const w = 1 + 3 * rand();
    const h = 1 + 3 * rand();
    const horiz = [Math.cos(a) * w, 0, Math.sin(a) * w];
    const horiz2 = [-Math.sin(a) * h, 0, Math.cos(a) * h];
    switch (k % 6) {
      case 0: // y plane, axis edges (a floor), either orientation
        out.push(rand() < 0.5 ? [c(), [0, 0, w], [h, 0, 0]] : [c(), [h, 0, 0], [0, 0, w]]);
        break;
      case 1: // x or z plane
        out.push(rand() < 0.5 ? [c(), [0, h, 0], [0, 0, w]] : [c(), [w, 0, 0], [0, h, 0]]);
        break;
      case 2: // y plane, rotated edges (a box top)
        out.push([c(), horiz, horiz2]);
        break;
      case 3: // vertical plane with a vertical edge (a box side), either edge order
        out.push(rand() < 0.5 ? [c(), horiz, [0, h, 0]] : [c(), [0, h, 0], horiz]);
        break;
      case 4: // general
        out.push([c(), [w, 0.3 * h, 0.1], [0.2, -0.5, h]]);
        break;
      default: // a copy of an earlier quad: exact ties in t
        out.push(out[Math.floor(rand() * out.length)]);
    }
  }
  return out;
}

describe('QuadList', () => {
  it('sorts quads into the axis, vertical and general groups', () => {
    const quads = new Float64Array(4 * QUAD_STRIDE);
    writeQuadRecord([0, 0, 0], [1, 0, 0], [0, 1, 0], quads, 0); // z plane
    writeQuadRecord([0, 0, 0], [0, 0, 1], [1, 0, 0], quads, QUAD_STRIDE); // y plane
    writeQuadRecord([0, 0, 0], [0.6, 0, 0.8], [0, 2, 0], quads, 2 * QUAD_STRIDE); // vertical
    writeQuadRecord([0, 0, 0], [1, 1, 0], [0, 1, 1], quads, 3 * QUAD_STRIDE); // general
    const list = new QuadList(quads);
    expect(Array.from(list.axisStart)).toEqual([0, 0, 1, 2]);
    expect(Array.from(list.axisIndex)).toEqual([1, 0]);
    expect(Array.from(list.verticalIndex)).toEqual([2]);
    expect(Array.from(list.generalIndex)).toEqual([3]);
  });

  // At the scale of the scenes and far from it (tiny and huge coordinates: other roundings,
  // subnormal products), where a dropped ±0 term could show if the argument were wrong.
  it.each([1, 1e-150, 3e-7, 7e5, 1e150])(
    'finds the nearest quad and occlusion exactly as the index-ordered loop (scale %s)',
    (scale) => {
      const descs = makeQuads().map((q) => q.map((v) => v.map((c) => c * scale)));
      const quads = new Float64Array(descs.length * QUAD_STRIDE);
      descs.forEach((q, i) => writeQuadRecord(q[0], q[1], q[2], quads, i * QUAD_STRIDE));
      const list = new QuadList(quads);
      // The fields of a quads-only scene without a BVH that the shadow query reads.
      const scene = {
        bvh: null,
        spheres: new Float64Array(0),
        sphereCount: 0,
        quadList: list,
        triCount: 0,
      } as unknown as CompiledScene;
      expect(list.axisStart[3]).toBeGreaterThan(0);
      expect(list.verticalCount).toBeGreaterThan(0);
      expect(list.generalCount).toBeGreaterThan(0);
      const r = new Float64Array(8);
      let hits = 0;
      let ties = 0;
      for (let k = 0; k < 20000; k++) {
        const ox = (10 * rand() - 5) * scale,
          oy = (10 * rand() - 5) * scale,
          oz = (10 * rand() - 5) * scale;
        // Directions along an axis or in a coordinate plane now and then: rays parallel to
        // quads, and exact zeros in the products the short tests leave out.
        let dx = pick([0, 2 * rand() - 1, 2 * rand() - 1]);
        let dy = pick([0, 2 * rand() - 1, 2 * rand() - 1]);
        let dz = pick([0, 2 * rand() - 1, 2 * rand() - 1]);
        if (dx === 0 && dy === 0 && dz === 0) dy = 1;
        const l = Math.hypot(dx, dy, dz);
        dx /= l;
        dy /= l;
        dz /= l;
        const tMax = pick([Infinity, 4 * rand() * scale, 8 * rand() * scale]);
        // Reference: intersectQuad in index order, a strictly closer hit replaces.
        let tBest = tMax;
        let best = -1;
        let sameT = 0;
        for (let i = 0; i < descs.length; i++) {
          const t = intersectQuad(quads, i, ox, oy, oz, dx, dy, dz, tMax);
          if (t < tBest) {
            tBest = t;
            best = i;
          }
        }
        for (let i = 0; i < descs.length; i++)
          if (best >= 0 && intersectQuad(quads, i, ox, oy, oz, dx, dy, dz, tMax) === tBest) sameT++;
        r.set([ox, oy, oz, dx, dy, dz, tMax]);
        const got = nearestQuad(list, r);
        expect(got).toBe(best);
        expect(Object.is(r[6], tBest)).toBe(true);
        r[6] = tMax;
        const ray = new Ray();
        [ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tMax] = [ox, oy, oz, dx, dy, dz, tMax];
        expect(occluded(scene, ray)).toBe(best >= 0);
        if (best >= 0) hits++;
        if (sameT > 1) ties++;
      }
      // The rays met quads, and ties (the copies) among them.
      expect(hits).toBeGreaterThan(2000);
      expect(ties).toBeGreaterThan(100);
    },
  );
});
