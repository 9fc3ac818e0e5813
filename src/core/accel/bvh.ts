/**
 * Bounding volume hierarchy over spheres and quads, built with the binned
 * surface area heuristic (pbr-book 4e §7.3.2; Wald, "On fast Construction of
 * SAH-based Bounding Volume Hierarchies", 2007) and flattened depth-first
 * into typed arrays (pbr-book 4e §7.3.4): the left child of node i is i + 1,
 * the right child's index is stored. Traversal is iterative over a
 * preallocated stack and visits the nearer child first.
 *
 * Primitive ids: 0 … sphereCount−1 are spheres, the rest quads.
 */
import { QUAD_STRIDE, Q_CORNER, Q_U, Q_V, SPHERE_STRIDE } from '../geometry/shapes.ts';

export const BVH_MAX_LEAF = 4;
const BINS = 16;
/** Relative cost of one box test against one primitive test. */
const TRAVERSAL_COST = 0.5;

export class Bvh {
  /** Per node: min x, y, z, max x, y, z. */
  readonly bounds: Float64Array;
  /** Per node: [offset, count, axis]: leaves have count > 0 and offset into primIds; interior nodes count 0 and offset = right child. */
  readonly nodes: Int32Array;
  readonly primIds: Int32Array;
  readonly nodeCount: number;
  /** Traversal stack, sized for the tree's depth. */
  readonly stack: Int32Array;

  constructor(
    bounds: Float64Array,
    nodes: Int32Array,
    primIds: Int32Array,
    nodeCount: number,
    depth: number,
  ) {
    this.bounds = bounds;
    this.nodes = nodes;
    this.primIds = primIds;
    this.nodeCount = nodeCount;
    this.stack = new Int32Array(depth + 2);
  }
}

/** Bounds and centroids of every primitive, 6 + 3 numbers each. */
function primitiveBounds(
  spheres: Float64Array,
  sphereCount: number,
  quads: Float64Array,
  quadCount: number,
): { boxes: Float64Array; centroids: Float64Array } {
  const n = sphereCount + quadCount;
  const boxes = new Float64Array(n * 6);
  const centroids = new Float64Array(n * 3);
  for (let i = 0; i < sphereCount; i++) {
    const o = i * SPHERE_STRIDE;
    const r = spheres[o + 3];
    for (let a = 0; a < 3; a++) {
      boxes[i * 6 + a] = spheres[o + a] - r;
      boxes[i * 6 + 3 + a] = spheres[o + a] + r;
    }
  }
  for (let j = 0; j < quadCount; j++) {
    const o = j * QUAD_STRIDE;
    const i = sphereCount + j;
    for (let a = 0; a < 3; a++) {
      const c = quads[o + Q_CORNER + a];
      const u = quads[o + Q_U + a];
      const v = quads[o + Q_V + a];
      boxes[i * 6 + a] = Math.min(c, c + u, c + v, c + u + v);
      boxes[i * 6 + 3 + a] = Math.max(c, c + u, c + v, c + u + v);
    }
  }
  for (let i = 0; i < n; i++) {
    for (let a = 0; a < 3; a++)
      centroids[i * 3 + a] = 0.5 * (boxes[i * 6 + a] + boxes[i * 6 + 3 + a]);
  }
  return { boxes, centroids };
}

function halfArea(
  minX: number,
  minY: number,
  minZ: number,
  maxX: number,
  maxY: number,
  maxZ: number,
): number {
  const dx = maxX - minX;
  const dy = maxY - minY;
  const dz = maxZ - minZ;
  return dx * dy + dy * dz + dz * dx;
}

export function buildBvh(
  spheres: Float64Array,
  sphereCount: number,
  quads: Float64Array,
  quadCount: number,
): Bvh {
  const n = sphereCount + quadCount;
  const { boxes, centroids } = primitiveBounds(spheres, sphereCount, quads, quadCount);
  const primIds = new Int32Array(n);
  for (let i = 0; i < n; i++) primIds[i] = i;
  const maxNodes = Math.max(1, 2 * n - 1);
  const bounds = new Float64Array(maxNodes * 6);
  const nodes = new Int32Array(maxNodes * 3);
  let nodeCount = 0;
  let maxDepth = 0;
  const binBox = new Float64Array(BINS * 6);
  const binCount = new Int32Array(BINS);
  const rightArea = new Float64Array(BINS);
  const rightCount = new Int32Array(BINS);

  const build = (start: number, end: number, depth: number): number => {
    const node = nodeCount++;
    if (depth > maxDepth) maxDepth = depth;
    let minX = Infinity,
      minY = Infinity,
      minZ = Infinity;
    let maxX = -Infinity,
      maxY = -Infinity,
      maxZ = -Infinity;
    let cMinX = Infinity,
      cMinY = Infinity,
      cMinZ = Infinity;
    let cMaxX = -Infinity,
      cMaxY = -Infinity,
      cMaxZ = -Infinity;
    for (let k = start; k < end; k++) {
      const p = primIds[k];
      minX = Math.min(minX, boxes[p * 6]);
      minY = Math.min(minY, boxes[p * 6 + 1]);
      minZ = Math.min(minZ, boxes[p * 6 + 2]);
      maxX = Math.max(maxX, boxes[p * 6 + 3]);
      maxY = Math.max(maxY, boxes[p * 6 + 4]);
      maxZ = Math.max(maxZ, boxes[p * 6 + 5]);
      cMinX = Math.min(cMinX, centroids[p * 3]);
      cMinY = Math.min(cMinY, centroids[p * 3 + 1]);
      cMinZ = Math.min(cMinZ, centroids[p * 3 + 2]);
      cMaxX = Math.max(cMaxX, centroids[p * 3]);
      cMaxY = Math.max(cMaxY, centroids[p * 3 + 1]);
      cMaxZ = Math.max(cMaxZ, centroids[p * 3 + 2]);
    }
    bounds.set([minX, minY, minZ, maxX, maxY, maxZ], node * 6);
    const count = end - start;
    const makeLeaf = (): number => {
      nodes[node * 3] = start;
      nodes[node * 3 + 1] = count;
      nodes[node * 3 + 2] = 0;
      return node;
    };
    if (count <= 1) return makeLeaf();
    // Split axis: the longest extent of the centroids.
    const ex = cMaxX - cMinX;
    const ey = cMaxY - cMinY;
    const ez = cMaxZ - cMinZ;
    const axis = ex >= ey && ex >= ez ? 0 : ey >= ez ? 1 : 2;
    const cMin = axis === 0 ? cMinX : axis === 1 ? cMinY : cMinZ;
    const extent = axis === 0 ? ex : axis === 1 ? ey : ez;
    if (!(extent > 0)) {
      if (count <= BVH_MAX_LEAF) return makeLeaf();
      // All centroids coincide: split in the middle of the list.
      return interior(node, start, start + (count >> 1), end, axis, depth);
    }
    binBox.fill(0);
    binCount.fill(0);
    for (let b = 0; b < BINS; b++) {
      binBox[b * 6] = binBox[b * 6 + 1] = binBox[b * 6 + 2] = Infinity;
      binBox[b * 6 + 3] = binBox[b * 6 + 4] = binBox[b * 6 + 5] = -Infinity;
    }
    const scale = BINS / extent;
    for (let k = start; k < end; k++) {
      const p = primIds[k];
      const b = Math.min(BINS - 1, Math.floor((centroids[p * 3 + axis] - cMin) * scale));
      binCount[b]++;
      for (let a = 0; a < 3; a++) {
        binBox[b * 6 + a] = Math.min(binBox[b * 6 + a], boxes[p * 6 + a]);
        binBox[b * 6 + 3 + a] = Math.max(binBox[b * 6 + 3 + a], boxes[p * 6 + 3 + a]);
      }
    }
    // Sweep from the right to know the area and count right of each plane.
    let rx0 = Infinity,
      ry0 = Infinity,
      rz0 = Infinity;
    let rx1 = -Infinity,
      ry1 = -Infinity,
      rz1 = -Infinity;
    let rc = 0;
    for (let b = BINS - 1; b > 0; b--) {
      rx0 = Math.min(rx0, binBox[b * 6]);
      ry0 = Math.min(ry0, binBox[b * 6 + 1]);
      rz0 = Math.min(rz0, binBox[b * 6 + 2]);
      rx1 = Math.max(rx1, binBox[b * 6 + 3]);
      ry1 = Math.max(ry1, binBox[b * 6 + 4]);
      rz1 = Math.max(rz1, binBox[b * 6 + 5]);
      rc += binCount[b];
      rightCount[b] = rc;
      rightArea[b] = rc > 0 ? halfArea(rx0, ry0, rz0, rx1, ry1, rz1) : 0;
    }
    let lx0 = Infinity,
      ly0 = Infinity,
      lz0 = Infinity;
    let lx1 = -Infinity,
      ly1 = -Infinity,
      lz1 = -Infinity;
    let lc = 0;
    let bestCost = Infinity;
    let bestPlane = -1;
    for (let b = 0; b < BINS - 1; b++) {
      lx0 = Math.min(lx0, binBox[b * 6]);
      ly0 = Math.min(ly0, binBox[b * 6 + 1]);
      lz0 = Math.min(lz0, binBox[b * 6 + 2]);
      lx1 = Math.max(lx1, binBox[b * 6 + 3]);
      ly1 = Math.max(ly1, binBox[b * 6 + 4]);
      lz1 = Math.max(lz1, binBox[b * 6 + 5]);
      lc += binCount[b];
      const rcount = rightCount[b + 1];
      if (lc === 0 || rcount === 0) continue;
      const cost = lc * halfArea(lx0, ly0, lz0, lx1, ly1, lz1) + rcount * rightArea[b + 1];
      if (cost < bestCost) {
        bestCost = cost;
        bestPlane = b;
      }
    }
    const parentArea = halfArea(minX, minY, minZ, maxX, maxY, maxZ);
    const leafCost = count;
    const splitCost = TRAVERSAL_COST + (parentArea > 0 ? bestCost / parentArea : count);
    if (bestPlane < 0) {
      return count <= BVH_MAX_LEAF
        ? makeLeaf()
        : interior(node, start, start + (count >> 1), end, axis, depth);
    }
    if (count <= BVH_MAX_LEAF && leafCost <= splitCost) return makeLeaf();
    // Partition primIds[start, end) by bin.
    let i = start;
    let j = end - 1;
    while (i <= j) {
      const p = primIds[i];
      const b = Math.min(BINS - 1, Math.floor((centroids[p * 3 + axis] - cMin) * scale));
      if (b <= bestPlane) i++;
      else {
        primIds[i] = primIds[j];
        primIds[j] = p;
        j--;
      }
    }
    return interior(node, start, i, end, axis, depth);
  };

  const interior = (
    node: number,
    start: number,
    mid: number,
    end: number,
    axis: number,
    depth: number,
  ): number => {
    build(start, mid, depth + 1);
    const right = build(mid, end, depth + 1);
    nodes[node * 3] = right;
    nodes[node * 3 + 1] = 0;
    nodes[node * 3 + 2] = axis;
    return node;
  };

  if (n > 0) build(0, n, 0);
  return new Bvh(
    bounds.slice(0, nodeCount * 6),
    nodes.slice(0, nodeCount * 3),
    primIds,
    nodeCount,
    maxDepth,
  );
}
