/**
 * The BVH finds the same nearest hits as the plain loop over shapes, and
 * the scene compiler builds only what a scene has.
 */
import { describe, expect, it } from 'vitest';
import { BVH_THRESHOLD, compileScene } from '../../../src/core/index.ts';
import { randomSpheresScene } from '../../../src/core/scene/load/random-spheres.ts';
import { loadScene, renderSampled } from '../../helpers/render.ts';
import {
  Hit,
  Ray,
  SHAPE_QUAD,
  SHAPE_SPHERE,
  SHAPE_TRIANGLE,
} from '../../../src/core/geometry/ray.ts';
import {
  QUAD_STRIDE,
  Q_CORNER,
  Q_NORMAL,
  Q_PLANE,
  Q_SAXIS,
  Q_TAXIS,
  SPHERE_STRIDE,
} from '../../../src/core/geometry/shapes.ts';
import {
  AXIS_STRIDE,
  GENERAL_STRIDE,
  VERTICAL_STRIDE,
} from '../../../src/core/geometry/quad-list.ts';
import { intersectScene, occluded } from '../../../src/core/accel/trace.ts';
import { pcgHash } from '../../../src/core/rng/pcg.ts';
import {
  BVH_LEAF_BITS,
  BVH_LEAF_MASK,
  BVH_MAX_LEAF,
  BVH_NODE_WORDS,
  N_LEFT,
  N_RIGHT,
  N_RIGHT_BOX,
  buildBvh,
  f32Above,
  f32Below,
  type Bvh,
} from '../../../src/core/accel/bvh.ts';
import {
  PRIM_KIND_BITS,
  PRIM_KIND_MASK,
  PrimitiveBoxes,
} from '../../../src/core/accel/primitives.ts';

/**
 * Walks the tree from the root: every reference must sit in exactly one
 * leaf, and every primitive's box inside the box its parent stores for that
 * leaf and for each node above it.
 */
function checkTree(bvh: Bvh, boxes: Float32Array, refs: Int32Array, n: number): void {
  const seen = new Int32Array(n);
  const byRef = new Map<number, number>();
  for (let i = 0; i < n; i++) byRef.set(refs[i], i);
  const walk = (code: number, box: number[]): void => {
    if (code >= 0) {
      expect(code).toBeLessThan(bvh.nodeCount);
      for (let side = 0; side < 2; side++) {
        const b = code * BVH_NODE_WORDS + side * 6;
        const child = Array.from(bvh.nodes.subarray(b, b + 6));
        // A child box lies inside its parent's box.
        for (let a = 0; a < 3; a++) {
          if (child[a] > child[a + 3]) continue; // the empty box of a one-primitive tree
          expect(child[a]).toBeGreaterThanOrEqual(box[a]);
          expect(child[a + 3]).toBeLessThanOrEqual(box[a + 3]);
        }
        walk(bvh.words[code * BVH_NODE_WORDS + N_LEFT + side], child);
      }
      return;
    }
    const leaf = ~code;
    const first = leaf >> BVH_LEAF_BITS;
    const count = leaf & BVH_LEAF_MASK;
    if (box[0] > box[3]) return; // the empty sibling
    expect(count).toBeGreaterThan(0);
    expect(count).toBeLessThanOrEqual(BVH_MAX_LEAF);
    for (let k = first; k < first + count; k++) {
      const p = byRef.get(bvh.refs[k])!;
      seen[p]++;
      for (let a = 0; a < 3; a++) {
        expect(boxes[p * 6 + a]).toBeGreaterThanOrEqual(box[a]);
        expect(boxes[p * 6 + 3 + a]).toBeLessThanOrEqual(box[a + 3]);
      }
    }
  };
  walk(0, [-Infinity, -Infinity, -Infinity, Infinity, Infinity, Infinity]);
  expect(Array.from(seen)).toEqual(new Array(n).fill(1));
}

function boxesOf(list: number[][]): { boxes: Float32Array; refs: Int32Array } {
  const prims = new PrimitiveBoxes(list.length);
  list.forEach((b, i) => prims.add(0, i, b[0], b[1], b[2], b[3], b[4], b[5]));
  return { boxes: prims.boxes, refs: prims.refs };
}

describe('BVH', () => {
  it('answers nearest-hit and occlusion queries exactly like the plain loop', () => {
    const scene = randomSpheresScene(300, 4);
    const list = compileScene(scene, { bvh: false });
    const bvh = compileScene(scene, { bvh: true });
    expect(list.bvh).toBeNull();
    expect(bvh.bvh).not.toBeNull();
    const ray = new Ray();
    const a = new Hit();
    const b = new Hit();
    let state = 7;
    const rand = (): number => (state = pcgHash(state + 1)) / 4294967296;
    let hits = 0;
    for (let i = 0; i < 20000; i++) {
      ray.ox = (rand() - 0.5) * 30;
      ray.oy = rand() * 4;
      ray.oz = (rand() - 0.5) * 30;
      // Include axis-parallel directions, where 1/d is infinite.
      let dx = i % 7 === 0 ? 0 : rand() - 0.5;
      let dy = i % 11 === 0 ? 0 : rand() - 0.5;
      let dz = rand() - 0.5;
      const l = Math.hypot(dx, dy, dz);
      [dx, dy, dz] = [dx / l, dy / l, dz / l];
      [ray.dx, ray.dy, ray.dz] = [dx, dy, dz];
      ray.tMax = i % 3 === 0 ? 5 : Infinity;
      const hitList = intersectScene(list, ray, a);
      const hitBvh = intersectScene(bvh, ray, b);
      expect(hitBvh).toBe(hitList);
      if (hitList) {
        hits++;
        expect(b.t).toBe(a.t);
        expect([b.kind, b.index]).toEqual([a.kind, a.index]);
      }
      expect(occluded(bvh, ray)).toBe(occluded(list, ray));
    }
    expect(hits).toBeGreaterThan(1000);
  });

  it('renders the same image with and without the BVH', () => {
    const scene = loadScene('spheres');
    const a = renderSampled(scene, { width: 40, height: 24, spp: 2, bvh: false });
    const b = renderSampled(scene, { width: 40, height: 24, spp: 2, bvh: true });
    expect(Array.from(b.mean)).toEqual(Array.from(a.mean));
  });

  it('places every primitive in exactly one leaf, inside the boxes above it', () => {
    const scene = compileScene(randomSpheresScene(1000, 9), { bvh: true });
    let state = 3;
    const rand = (): number => (state = pcgHash(state + 1)) / 4294967296;
    const cases: number[][][] = [
      // One primitive; two; a pile of coincident ones (no plane separates them).
      [[0, 0, 0, 1, 1, 1]],
      [
        [0, 0, 0, 1, 1, 1],
        [5, 0, 0, 6, 1, 1],
      ],
      Array.from({ length: 13 }, () => [0, 0, 0, 1, 1, 1]),
      // Flat boxes (axis-aligned quads) and random ones.
      Array.from({ length: 50 }, (_, i) => [i, 0, 0, i + 1, 0, 2]),
      Array.from({ length: 500 }, () => {
        const x = rand() * 100,
          y = rand() * 100,
          z = rand() * 100;
        return [x, y, z, x + rand() * 5, y + rand(), z + rand() * 20];
      }),
    ];
    for (const list of cases) {
      const { boxes, refs } = boxesOf(list);
      const bvh = buildBvh(boxes, refs, list.length)!;
      expect(bvh.nodeCount).toBeLessThanOrEqual(Math.max(1, list.length - 1));
      checkTree(bvh, boxes, refs, list.length);
    }
    expect(scene.bvh).not.toBeNull();
    expect(buildBvh(new Float32Array(0), new Int32Array(0), 0)).toBeNull();
    // References carry the kind in their low bits.
    expect(scene.bvh!.refs.every((r) => (r & ((1 << PRIM_KIND_BITS) - 1)) <= 1)).toBe(true);
  });

  it('rounds boxes outwards to Float32, by at least one ulp', () => {
    for (const x of [0, 1, -1, 0.1, -0.1, 555, 1e-30, -3.4e38, 123456.789, 2 ** -149]) {
      const lo = f32Below(x);
      const hi = f32Above(x);
      expect(lo).toBeLessThan(x);
      expect(hi).toBeGreaterThan(x);
      expect(Math.fround(lo)).toBe(lo);
      expect(Math.fround(hi)).toBe(hi);
    }
  });

  it('is built only above the measured crossover', () => {
    expect(compileScene(loadScene('cornell')).bvh).toBeNull();
    expect(compileScene(randomSpheresScene(BVH_THRESHOLD)).bvh).not.toBeNull();
  });

  it('compiles no light list for a scene without emitters', () => {
    const compiled = compileScene(loadScene('furnace-diffuse'));
    expect(compiled.lights).toBeNull();
    expect(compiled.quadCount).toBe(0);
    expect(compiled.quads.length).toBe(0);
  });

  it('has the layout that the traversal loops of trace.ts write as literals', () => {
    // trace.ts and quad-list.ts spell these offsets out (a module constant costs a
    // context load and a checked multiply in the loop); they must match the layout.
    expect([BVH_NODE_WORDS, N_RIGHT_BOX, N_LEFT, N_RIGHT, BVH_LEAF_BITS]).toEqual([
      16, 6, 12, 13, 3,
    ]);
    expect([PRIM_KIND_BITS, PRIM_KIND_MASK]).toEqual([2, 3]);
    expect([SHAPE_SPHERE, SHAPE_QUAD, SHAPE_TRIANGLE, SPHERE_STRIDE, QUAD_STRIDE]).toEqual([
      0, 1, 2, 4, 20,
    ]);
    expect([Q_CORNER, Q_NORMAL, Q_PLANE, Q_SAXIS, Q_TAXIS]).toEqual([0, 9, 12, 13, 16]);
    expect([AXIS_STRIDE, VERTICAL_STRIDE, GENERAL_STRIDE]).toEqual([8, 9, 13]);
  });
});
