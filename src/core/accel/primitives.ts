/**
 * What the BVH knows of a primitive: a conservative Float32 box and a
 * 32-bit reference `index << PRIM_KIND_BITS | kind`, where kind is the
 * SHAPE_* tag of geometry/ray.ts and index the primitive's record in its
 * kind's own arrays. Each kind contributes its boxes through one function
 * here; the traversal dispatches on the tag with one switch (trace.ts).
 *
 * Adding a kind (e.g. triangles):
 *   1. a SHAPE_* tag < 2^PRIM_KIND_BITS in geometry/ray.ts;
 *   2. a `<kind>Boxes` function below, called by compile.ts after the others;
 *   3. a `case` in the leaf switches of trace.ts (`leafClosest`, `leafAny`)
 *      calling its intersector, which returns the distance or Infinity;
 *   4. a `case` where the integrator completes a hit (point, normal, material).
 */
import { QUAD_STRIDE, Q_CORNER, Q_U, Q_V, SPHERE_STRIDE } from '../geometry/shapes.ts';
import { SHAPE_QUAD, SHAPE_SPHERE, SHAPE_TRIANGLE } from '../geometry/ray.ts';
import { f32Above, f32Below } from './bvh.ts';
import { checkCancel } from '../util/cancel.ts';

export const PRIM_KIND_BITS = 2;
export const PRIM_KIND_MASK = (1 << PRIM_KIND_BITS) - 1;
/** Most primitives of one kind a reference can address. */
export const PRIM_MAX_INDEX = 2 ** (31 - PRIM_KIND_BITS);

/** Boxes and references of a scene's primitives, in kind order. */
export class PrimitiveBoxes {
  readonly count: number;
  /** Six Float32 per primitive: min x, y, z, max x, y, z (rounded outwards). */
  readonly boxes: Float32Array;
  readonly refs: Int32Array;
  /** Primitives written so far. */
  filled = 0;

  constructor(count: number) {
    this.count = count;
    this.boxes = new Float32Array(count * 6);
    this.refs = new Int32Array(count);
  }

  /** Appends one primitive's box (exact bounds; rounded outwards here). */
  add(
    kind: number,
    index: number,
    x0: number,
    y0: number,
    z0: number,
    x1: number,
    y1: number,
    z1: number,
  ): void {
    const i = this.filled++;
    const b = i * 6;
    const boxes = this.boxes;
    boxes[b] = f32Below(x0);
    boxes[b + 1] = f32Below(y0);
    boxes[b + 2] = f32Below(z0);
    boxes[b + 3] = f32Above(x1);
    boxes[b + 4] = f32Above(y1);
    boxes[b + 5] = f32Above(z1);
    this.refs[i] = (index << PRIM_KIND_BITS) | kind;
  }
}

export function sphereBoxes(spheres: Float64Array, count: number, out: PrimitiveBoxes): void {
  for (let i = 0; i < count; i++) {
    const o = i * SPHERE_STRIDE;
    const x = spheres[o],
      y = spheres[o + 1],
      z = spheres[o + 2],
      r = spheres[o + 3];
    out.add(SHAPE_SPHERE, i, x - r, y - r, z - r, x + r, y + r, z + r);
  }
}

export function quadBoxes(quads: Float64Array, count: number, out: PrimitiveBoxes): void {
  for (let i = 0; i < count; i++) {
    const o = i * QUAD_STRIDE;
    let x0 = Infinity,
      y0 = Infinity,
      z0 = Infinity,
      x1 = -Infinity,
      y1 = -Infinity,
      z1 = -Infinity;
    for (let k = 0; k < 4; k++) {
      const su = k & 1;
      const sv = k >> 1;
      const x = quads[o + Q_CORNER] + su * quads[o + Q_U] + sv * quads[o + Q_V];
      const y = quads[o + Q_CORNER + 1] + su * quads[o + Q_U + 1] + sv * quads[o + Q_V + 1];
      const z = quads[o + Q_CORNER + 2] + su * quads[o + Q_U + 2] + sv * quads[o + Q_V + 2];
      x0 = Math.min(x0, x);
      y0 = Math.min(y0, y);
      z0 = Math.min(z0, z);
      x1 = Math.max(x1, x);
      y1 = Math.max(y1, y);
      z1 = Math.max(z1, z);
    }
    out.add(SHAPE_QUAD, i, x0, y0, z0, x1, y1, z1);
  }
}

export function triangleBoxes(
  positions: Float64Array,
  indices: Uint32Array | Int32Array,
  count: number,
  out: PrimitiveBoxes,
): void {
  for (let t = 0; t < count; t++) {
    if ((t & 65535) === 65535) checkCancel();
    const a = indices[3 * t] * 3,
      b = indices[3 * t + 1] * 3,
      c = indices[3 * t + 2] * 3;
    const ax = positions[a],
      ay = positions[a + 1],
      az = positions[a + 2];
    const bx = positions[b],
      by = positions[b + 1],
      bz = positions[b + 2];
    const cx = positions[c],
      cy = positions[c + 1],
      cz = positions[c + 2];
    out.add(
      SHAPE_TRIANGLE,
      t,
      Math.min(ax, bx, cx),
      Math.min(ay, by, cy),
      Math.min(az, bz, cz),
      Math.max(ax, bx, cx),
      Math.max(ay, by, cy),
      Math.max(az, bz, cz),
    );
  }
}

/** Instances' world boxes (accel/instances.ts), as references of kind PRIM_INSTANCE (3). */
export function instanceBoxesInto(boxes: Float64Array, count: number, out: PrimitiveBoxes): void {
  for (let k = 0; k < count; k++) {
    const o = 6 * k;
    out.add(3, k, boxes[o], boxes[o + 1], boxes[o + 2], boxes[o + 3], boxes[o + 4], boxes[o + 5]);
  }
}
