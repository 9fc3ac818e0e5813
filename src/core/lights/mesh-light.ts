/**
 * An emissive triangle mesh as one light: a point is drawn uniformly by area over all
 * its triangles (pbr-book 4e §6.5.4, "Triangle sampling", with the choice of triangle
 * from a CDF over their areas), so the area density is 1 / (total area) everywhere on
 * the mesh, and the solid-angle density seen from a point is d² / (A · cos θ_light).
 * The scene picks among its emitters first (in proportion to power), then this picks
 * within the mesh.
 *
 * u0 picks the triangle and is then reused, rescaled to [0, 1), with u1 for the point
 * inside it: one 2D sample, stratified over the whole mesh.
 */
import { TriangleEdges, triangleEdges } from '../geometry/triangle-edges.ts';
import { Distribution1D } from '../sampling/distribution.ts';
import {
  squareToUniformTriangle,
  uniformTriangleToSquare,
  type Vec2Out,
} from '../sampling/warps.ts';

/** What `sample` writes: the point, the unit geometric normal there, and the triangle. */
export class MeshLightSample {
  px = 0;
  py = 0;
  pz = 0;
  nx = 0;
  ny = 0;
  nz = 1;
  triangle = -1;
  /** Barycentrics of the point: weights of the triangle's vertices 1 and 2. */
  b1 = 0;
  b2 = 0;
}

export class MeshLight {
  readonly positions: Float64Array;
  readonly indices: Uint32Array | Int32Array;
  /** The mesh's triangles are first … first + count − 1 of `indices`. */
  readonly first: number;
  readonly count: number;
  readonly area: number;
  readonly distribution: Distribution1D;

  constructor(
    positions: Float64Array,
    indices: Uint32Array | Int32Array,
    first: number,
    count: number,
  ) {
    this.positions = positions;
    this.indices = indices;
    this.first = first;
    this.count = count;
    const areas = new Float64Array(count);
    for (let k = 0; k < count; k++) areas[k] = triangleArea(positions, indices, first + k);
    this.distribution = new Distribution1D(areas);
    this.area = this.distribution.total;
    if (!(this.area > 0 && this.area < Infinity)) {
      throw new RangeError(`an emissive mesh must have a finite, non-zero area, got ${this.area}`);
    }
  }

  /** Density by area: the same on every point of the mesh. */
  pdfArea(): number {
    return 1 / this.area;
  }

  sample(u0: number, u1: number, out: MeshLightSample): void {
    const d = this.distribution;
    const k = d.find(u0);
    const b = BARY;
    squareToUniformTriangle(d.remap(u0, k), u1, b);
    this.writePoint(this.first + k, b.x, b.y, out);
  }

  /** The point of triangle t with barycentrics (b0, b1), its normal and barycentrics. */
  private writePoint(t: number, b0: number, b1: number, out: MeshLightSample): void {
    const p = this.positions;
    const i0 = this.indices[3 * t] * 3,
      i1 = this.indices[3 * t + 1] * 3,
      i2 = this.indices[3 * t + 2] * 3;
    const b2 = 1 - b0 - b1;
    out.px = b0 * p[i0] + b1 * p[i1] + b2 * p[i2];
    out.py = b0 * p[i0 + 1] + b1 * p[i1 + 1] + b2 * p[i2 + 1];
    out.pz = b0 * p[i0 + 2] + b1 * p[i1 + 2] + b2 * p[i2 + 2];
    triangleNormal(p, i0, i1, i2, out);
    out.triangle = t;
    out.b1 = b1;
    out.b2 = b2;
  }

  /**
   * A point uniformly by area on triangle t alone (one of this mesh's), for a choice of
   * triangle made elsewhere (the light BVH).
   */
  sampleTriangle(t: number, u0: number, u1: number, out: MeshLightSample): void {
    const b = BARY;
    squareToUniformTriangle(u0, u1, b);
    this.writePoint(t, b.x, b.y, out);
  }

  /** The (u0, u1) that `sample` takes to the point of triangle t with barycentrics (b0, b1). */
  invert(t: number, b0: number, b1: number, out: Vec2Out): void {
    const k = t - this.first;
    uniformTriangleToSquare(b0, b1, out);
    out.x = this.distribution.invert(k, out.x);
  }
}

const BARY: Vec2Out = { x: 0, y: 0 };
/** triangleArea's scratch (compile time only; one thread each). */
const EDGES = new TriangleEdges();

/**
 * Area of triangle t. The edges are scaled to a largest component of 1 before the cross
 * product, so a tiny triangle's area does not underflow to 0 on the way.
 */
export function triangleArea(
  p: Float64Array,
  indices: Uint32Array | Int32Array,
  t: number,
): number {
  const E = EDGES;
  triangleEdges(p, indices[3 * t] * 3, indices[3 * t + 1] * 3, indices[3 * t + 2] * 3, E);
  const m = E.m;
  if (m === 0) return 0;
  const s = 1 / m;
  const ax = E.e1x * s,
    ay = E.e1y * s,
    az = E.e1z * s;
  const bx = E.e2x * s,
    by = E.e2y * s,
    bz = E.e2z * s;
  // |edge| up to ~1e154 keeps m² finite: far beyond any scene's scale.
  return 0.5 * Math.hypot(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx) * m * m;
}

/**
 * Unit geometric normal normalize(cross(p1 − p0, p2 − p0)) into out.nx, ny, nz.
 * Deliberate copy: written out from triangleEdges (geometry/triangle-edges.ts) for V8's
 * inlining; checked by test tests/unit/core/triangle.test.ts ("triangleNormal").
 */
export function triangleNormal(
  p: Float64Array,
  a: number,
  b: number,
  c: number,
  out: { nx: number; ny: number; nz: number },
): void {
  const e1x = p[b] - p[a],
    e1y = p[b + 1] - p[a + 1],
    e1z = p[b + 2] - p[a + 2];
  const e2x = p[c] - p[a],
    e2y = p[c + 1] - p[a + 1],
    e2z = p[c + 2] - p[a + 2];
  // Scaled so that neither huge nor tiny triangles over- or underflow the products.
  const m = Math.max(
    Math.abs(e1x),
    Math.abs(e1y),
    Math.abs(e1z),
    Math.abs(e2x),
    Math.abs(e2y),
    Math.abs(e2z),
  );
  const s = m > 0 ? 1 / m : 1;
  const ax = e1x * s,
    ay = e1y * s,
    az = e1z * s;
  const bx = e2x * s,
    by = e2y * s,
    bz = e2z * s;
  const nx = ay * bz - az * by;
  const ny = az * bx - ax * bz;
  const nz = ax * by - ay * bx;
  const len = Math.sqrt(nx * nx + ny * ny + nz * nz);
  out.nx = nx / len;
  out.ny = ny / len;
  out.nz = nz / len;
}
