/**
 * One bounding volume hierarchy over every primitive of a scene, whatever
 * its kind, built with the binned surface area heuristic (Wald, "On fast
 * Construction of SAH-based Bounding Volume Hierarchies", 2007; pbr-book 4e
 * §7.3.2).
 *
 * The hierarchy knows primitives only as boxes and *references*: a 32-bit
 * word `index << PRIM_KIND_BITS | kind` per primitive (see primitives.ts),
 * so a new kind of primitive needs no change here.
 *
 * Node layout (BVH_NODE_WORDS = 16 words, 64 bytes, one cache line): each
 * interior node stores the boxes of its *two children*, so one visit tests
 * both and descends into the nearer first (a "BVH2 with child bounds in the
 * parent", as in Embree's BVH4 with two lanes; Aila & Laine 2009 use the
 * same layout on GPUs):
 *   f32 [0, 6)   left child box  min x, y, z, max x, y, z
 *   f32 [6, 12)  right child box
 *   i32 12, 13   left, right child: an interior node's index (≥ 0), or a
 *                leaf as ~(first << BVH_LEAF_BITS | count) (< 0): its
 *                references are refs[first, first + count)
 *   i32 14       the split axis (0, 1, 2): a ray going down that axis
 *                visits the right child first
 *   i32 15       unused (keeps nodes on cache-line boundaries)
 * Boxes are Float32, rounded outwards (and padded by one float ulp), so they
 * always contain the exact double-precision primitive: the box test may let a
 * ray through that misses, never the reverse. Node 0 is the root; there are
 * at most n − 1 nodes for n primitives (one node for n = 1, its right child an
 * empty box that no ray enters).
 */

import { checkCancel } from '../util/cancel.ts';

export const BVH_NODE_WORDS = 16;
/** Word offsets inside a node. */
export const N_LEFT_BOX = 0;
export const N_RIGHT_BOX = 6;
export const N_LEFT = 12;
export const N_RIGHT = 13;
export const N_AXIS = 14;
/** Bits of a leaf code that hold its reference count. */
export const BVH_LEAF_BITS = 3;
export const BVH_LEAF_MASK = (1 << BVH_LEAF_BITS) - 1;

/** Largest leaf the builder makes (a larger range is always split); < 2^BVH_LEAF_BITS. */
export const BVH_MAX_LEAF = 4;
/** Leaf codes hold first << BVH_LEAF_BITS in 31 bits. */
export const BVH_MAX_PRIMS = 2 ** (31 - BVH_LEAF_BITS);
const BINS = 16;
/** The largest finite Float32. */
const F32_MAX = 3.4028234663852886e38;
/**
 * SAH splits go this many levels deeper than a balanced tree's 2·log2 n at most;
 * past that, ranges are split at their median (ordinary scenes stay far above it:
 * the 10,000-sphere field and the million-triangle mesh reach about 2·log2 n).
 */
const SAH_DEPTH = 32;
/**
 * SAH cost of a node visit (two boxes, tested branch-free) relative to one
 * primitive test. On the 10,000-sphere scene's recorded rays, node costs of
 * 0.25 to 2 gave times within the noise of the shared 2-core machine; 1
 * gives single-sphere leaves there and 2–4-quad leaves in the Cornell box.
 * A larger cost gives larger leaves and fewer nodes: 2 takes 42 bytes per
 * primitive (nodes + references) for a million triangle-sized boxes, 1
 * takes 68 (bench/bvh-build.ts) — what a mesh's memory budget may call for.
 */
export const BVH_NODE_COST = 1;
const COST_PRIM = 1;

export class Bvh {
  /** The node buffer: `nodes` and `words` view the same bytes. */
  readonly buffer: ArrayBuffer | SharedArrayBuffer;
  readonly nodes: Float32Array;
  readonly words: Int32Array;
  readonly nodeCount: number;
  /** Primitive references, leaf by leaf. */
  readonly refs: Int32Array;
  /** Depth of the deepest node (root = 0): the traversal stack needs depth + 1 entries. */
  readonly depth: number;

  constructor(
    buffer: ArrayBuffer | SharedArrayBuffer,
    byteOffset: number,
    nodeCount: number,
    refs: Int32Array,
    depth: number,
  ) {
    this.buffer = buffer;
    this.nodes = new Float32Array(buffer, byteOffset, nodeCount * BVH_NODE_WORDS);
    this.words = new Int32Array(buffer, byteOffset, nodeCount * BVH_NODE_WORDS);
    this.nodeCount = nodeCount;
    this.refs = refs;
    this.depth = depth;
  }

  get byteLength(): number {
    return this.nodes.byteLength + this.refs.byteLength;
  }
}

const f32 = new Float32Array(1);
const i32 = new Int32Array(f32.buffer);

/** The next Float32 below the Float32 v. */
function stepDown(v: number): number {
  if (v === -Infinity || v !== v) return v;
  if (v === Infinity) return 3.4028234663852886e38;
  if (v === 0) return -1.401298464324817e-45;
  f32[0] = v;
  i32[0] += v > 0 ? -1 : 1;
  return f32[0];
}

/** A Float32 below x by at least one ulp: the lower side of a conservative box. */
export function f32Below(x: number): number {
  const v = Math.fround(x);
  return stepDown(v > x ? stepDown(v) : v);
}

/** A Float32 above x by at least one ulp: the upper side of a conservative box. */
export function f32Above(x: number): number {
  return -f32Below(-x);
}

/**
 * Builds the hierarchy over n primitives. `boxes` holds six Float32 numbers
 * per primitive (min x, y, z, max x, y, z, already rounded outwards) and
 * `refs` their references; both are indexed by primitive and both are
 * *reordered in place* (the refs array becomes the tree's leaf order: the
 * caller hands them over). Returns null for n = 0.
 *
 * The work is split into small functions (binning, sweep, partition), each
 * called once per node: V8 optimises them after a few calls, where one long
 * function would run on on-stack replacement and deoptimise whenever the
 * build reaches a branch it had not seen yet (1,359 deopts for a million
 * boxes). Primitives' boxes, centroids and references are swapped in place
 * as ranges are partitioned, so every pass reads memory in order: through
 * an index permutation the same passes missed the cache at every step (7 s
 * for a million boxes against ~1 s; bench/bvh-build.ts).
 */
export function buildBvh(
  boxes: Float32Array,
  refs: Int32Array,
  n: number,
  nodeCost = BVH_NODE_COST,
): Bvh | null {
  if (n === 0) return null;
  if (n > BVH_MAX_PRIMS)
    throw new RangeError(`${n} primitives: a BVH holds at most ${BVH_MAX_PRIMS}`);
  const b = new Builder(boxes, refs, n, nodeCost);
  if (n === 1) {
    const nodes = b.nodes;
    for (let a = 0; a < 6; a++) nodes[N_LEFT_BOX + a] = boxes[a];
    for (let a = 0; a < 3; a++) {
      nodes[N_RIGHT_BOX + a] = Infinity;
      nodes[N_RIGHT_BOX + 3 + a] = -Infinity;
    }
    b.words[N_LEFT] = ~((0 << BVH_LEAF_BITS) | 1);
    b.words[N_RIGHT] = ~((0 << BVH_LEAF_BITS) | 1);
    b.nodeCount = 1;
  } else {
    b.build();
  }
  return new Bvh(
    b.nodes.buffer.slice(0, b.nodeCount * BVH_NODE_WORDS * 4),
    0,
    b.nodeCount,
    refs.subarray(0, n),
    b.maxDepth,
  );
}

/**
 * Per task on the build stack: start, end, slot (node·2 + side, −1 for the root), depth,
 * and 1 when its range is already in median order (see `medianSplit`).
 */
const T_WORDS = 5;
/** Per task: its primitives' box (6) and centroid bounds (6). */
const T_BOUNDS = 12;

class Builder {
  readonly boxes: Float32Array;
  readonly n: number;
  /** Centroids times two (min + max), per primitive, in the same (changing) order. */
  readonly cen: Float32Array;
  readonly refs: Int32Array;
  readonly nodes: Float32Array;
  readonly words: Int32Array;
  nodeCount = 0;
  maxDepth = 0;
  private tasks = new Int32Array(64 * T_WORDS);
  /** Depth past which ranges are split at their median (see `medianSplit`). */
  private readonly sahDepth: number;
  private taskBounds = new Float64Array(64 * T_BOUNDS);
  private top = 0;
  private readonly binCount = new Int32Array(BINS);
  private readonly binBox = new Float64Array(BINS * 6);
  private readonly rightArea = new Float64Array(BINS);
  /** Result of sweep(): the bounds of the two sides of the best plane. */
  private readonly split = new Float64Array(12);
  private bestPlane = -1;
  private bestCost = Infinity;
  private leftCount = 0;

  private readonly nodeCost: number;

  constructor(boxes: Float32Array, refs: Int32Array, n: number, nodeCost: number) {
    this.nodeCost = nodeCost;
    this.sahDepth = SAH_DEPTH + 2 * Math.ceil(Math.log2(n));
    this.boxes = boxes;
    this.refs = refs;
    this.n = n;
    this.cen = new Float32Array(n * 3);
    const buffer = new ArrayBuffer(Math.max(1, n - 1) * BVH_NODE_WORDS * 4);
    this.nodes = new Float32Array(buffer);
    this.words = new Int32Array(buffer);
  }

  build(): void {
    const { boxes, cen, n } = this;
    const root = this.split;
    root.fill(Infinity, 0, 3);
    root.fill(-Infinity, 3, 6);
    root.fill(Infinity, 6, 9);
    root.fill(-Infinity, 9, 12);
    for (let i = 0; i < n; i++) {
      if ((i & 65535) === 65535) checkCancel();
      const b = i * 6;
      for (let a = 0; a < 3; a++) {
        const lo = boxes[b + a];
        const hi = boxes[b + 3 + a];
        // The centre of the box with its sides held to the finite Float32 range: a
        // primitive beyond it (valid in double precision) has an infinite side, and
        // an infinite centroid would leave every bin plane without a side to put it.
        // Halving is exact, so ordinary scenes bin exactly as with lo + hi.
        const c = 0.5 * ((lo < -F32_MAX ? -F32_MAX : lo) + (hi > F32_MAX ? F32_MAX : hi));
        cen[i * 3 + a] = c;
        if (lo < root[a]) root[a] = lo;
        if (hi > root[3 + a]) root[3 + a] = hi;
        if (c < root[6 + a]) root[6 + a] = c;
        if (c > root[9 + a]) root[9 + a] = c;
      }
    }
    this.push(0, n, -1, 0, root, 0, 0);
    this.nodeCount = 1;
    // A cancelled load stops here (cancel.ts): checked every 2^16 primitives of work,
    // since one step near the root covers a large share of them.
    let work = 0;
    while (this.top > 0) {
      const t = (this.top - 1) * T_WORDS;
      work += this.tasks[t + 1] - this.tasks[t];
      this.step();
      if (work >= 65536) {
        work = 0;
        checkCancel();
      }
    }
  }

  private push(
    start: number,
    end: number,
    slot: number,
    depth: number,
    bounds: Float64Array,
    at: number,
    sorted: number,
  ): void {
    if (this.top * T_WORDS === this.tasks.length) {
      const t = new Int32Array(this.tasks.length * 2);
      t.set(this.tasks);
      this.tasks = t;
      const tb = new Float64Array(this.taskBounds.length * 2);
      tb.set(this.taskBounds);
      this.taskBounds = tb;
    }
    const t = this.top * T_WORDS;
    this.tasks[t] = start;
    this.tasks[t + 1] = end;
    this.tasks[t + 2] = slot;
    this.tasks[t + 3] = depth;
    this.tasks[t + 4] = sorted;
    const tb = this.top * T_BOUNDS;
    for (let k = 0; k < T_BOUNDS; k++) this.taskBounds[tb + k] = bounds[at + k];
    this.top++;
  }

  /** Places the task on top of the stack: a leaf, or a node with two new tasks. */
  private step(): void {
    const top = --this.top;
    const t = top * T_WORDS;
    const start = this.tasks[t];
    const end = this.tasks[t + 1];
    const slot = this.tasks[t + 2];
    const depth = this.tasks[t + 3];
    const sorted = this.tasks[t + 4];
    const tb = top * T_BOUNDS;
    const bounds = this.taskBounds;
    const count = end - start;
    // Split axis: the longest extent of the centroids.
    const ex = bounds[tb + 9] - bounds[tb + 6];
    const ey = bounds[tb + 10] - bounds[tb + 7];
    const ez = bounds[tb + 11] - bounds[tb + 8];
    const axis = ex >= ey && ex >= ez ? 0 : ey >= ez ? 1 : 2;
    const extent = axis === 0 ? ex : axis === 1 ? ey : ez;
    const cMin = bounds[tb + 6 + axis];
    const isRoot = slot < 0;
    let mid: number;
    let childSorted = 0;
    if (count === 1) {
      this.leaf(slot, start, count);
      return;
    } else if (!(extent > 0) || sorted === 1 || depth >= this.sahDepth) {
      // Every centroid coincides, so no plane separates them; or the SAH has
      // gone deeper than any ordinary scene takes it (primitives spread over
      // many orders of magnitude peel off a few per level): split at the
      // median, so the build stays O(n log n) whatever the magnitudes. The
      // root must split all the same: it is a node.
      if (count <= BVH_MAX_LEAF && !isRoot) {
        this.leaf(slot, start, count);
        return;
      }
      if (extent > 0 && sorted === 0) this.sortRange(start, end, axis);
      childSorted = extent > 0 ? 1 : 0;
      mid = this.middleSplit(start, end);
    } else {
      const scale = (BINS * (1 - 1e-6)) / extent;
      this.bin(start, end, axis, cMin, scale);
      this.sweep(count);
      const parentArea = halfArea(
        bounds[tb],
        bounds[tb + 1],
        bounds[tb + 2],
        bounds[tb + 3],
        bounds[tb + 4],
        bounds[tb + 5],
      );
      const splitCost =
        this.nodeCost +
        (parentArea > 0 ? (COST_PRIM * this.bestCost) / parentArea : COST_PRIM * count);
      if (count <= BVH_MAX_LEAF && COST_PRIM * count <= splitCost && !isRoot) {
        this.leaf(slot, start, count);
        return;
      }
      // No plane with primitives on both sides: the centroids differ by less
      // than their Float32 rounding. They are split in the middle.
      mid =
        this.bestPlane < 0 ? start : this.partition(start, end, axis, cMin, scale, this.bestPlane);
      if (mid === start || mid === end) mid = this.middleSplit(start, end);
    }
    // An interior node: the children's boxes go into it, their ranges onto
    // the stack (right first, so that the left child is built next and
    // lands at node + 1).
    const node = isRoot ? 0 : this.nodeCount++;
    if (!isRoot) this.words[(slot >> 1) * BVH_NODE_WORDS + N_LEFT + (slot & 1)] = node;
    if (depth > this.maxDepth) this.maxDepth = depth;
    const split = this.split;
    const o = node * BVH_NODE_WORDS;
    this.words[o + N_AXIS] = axis;
    for (let k = 0; k < 6; k++) {
      this.nodes[o + N_LEFT_BOX + k] = split[k];
      this.nodes[o + N_RIGHT_BOX + k] = split[6 + k];
    }
    // Child tasks: box from `split`, centroid bounds from `childCen`.
    const cb = this.childCen;
    for (let k = 0; k < 6; k++) {
      this.childTask[k] = split[6 + k];
      this.childTask[6 + k] = cb[6 + k];
    }
    this.push(mid, end, node * 2 + 1, depth + 1, this.childTask, 0, childSorted);
    for (let k = 0; k < 6; k++) {
      this.childTask[k] = split[k];
      this.childTask[6 + k] = cb[k];
    }
    this.push(start, mid, node * 2, depth + 1, this.childTask, 0, childSorted);
  }

  private readonly childTask = new Float64Array(T_BOUNDS);
  /** Centroid bounds of the left (0–5) and right (6–11) sides after a partition. */
  private readonly childCen = new Float64Array(12);

  private leaf(slot: number, start: number, count: number): void {
    this.words[(slot >> 1) * BVH_NODE_WORDS + N_LEFT + (slot & 1)] = ~(
      (start << BVH_LEAF_BITS) |
      count
    );
  }

  /** Counts and boxes of the primitives [start, end) per bin along `axis`. */
  private bin(start: number, end: number, axis: number, cMin: number, scale: number): void {
    const { boxes, cen, binCount, binBox } = this;
    binCount.fill(0);
    for (let b = 0; b < BINS * 6; b += 6) {
      binBox[b] = binBox[b + 1] = binBox[b + 2] = Infinity;
      binBox[b + 3] = binBox[b + 4] = binBox[b + 5] = -Infinity;
    }
    for (let p = start; p < end; p++) {
      const bin = binOf(cen[p * 3 + axis], cMin, scale);
      binCount[bin]++;
      const o = bin * 6;
      const b = p * 6;
      const x0 = boxes[b],
        y0 = boxes[b + 1],
        z0 = boxes[b + 2],
        x1 = boxes[b + 3],
        y1 = boxes[b + 4],
        z1 = boxes[b + 5];
      if (x0 < binBox[o]) binBox[o] = x0;
      if (y0 < binBox[o + 1]) binBox[o + 1] = y0;
      if (z0 < binBox[o + 2]) binBox[o + 2] = z0;
      if (x1 > binBox[o + 3]) binBox[o + 3] = x1;
      if (y1 > binBox[o + 4]) binBox[o + 4] = y1;
      if (z1 > binBox[o + 5]) binBox[o + 5] = z1;
    }
  }

  /**
   * The SAH sweep over the bin planes: sets bestPlane, bestCost (the sum
   * of area × count of both sides) and the two sides' boxes in split[0, 12).
   */
  private sweep(count: number): void {
    const { binCount, binBox, rightArea, split } = this;
    let x0 = Infinity,
      y0 = Infinity,
      z0 = Infinity,
      x1 = -Infinity,
      y1 = -Infinity,
      z1 = -Infinity;
    for (let b = BINS - 1; b > 0; b--) {
      const o = b * 6;
      if (binBox[o] < x0) x0 = binBox[o];
      if (binBox[o + 1] < y0) y0 = binBox[o + 1];
      if (binBox[o + 2] < z0) z0 = binBox[o + 2];
      if (binBox[o + 3] > x1) x1 = binBox[o + 3];
      if (binBox[o + 4] > y1) y1 = binBox[o + 4];
      if (binBox[o + 5] > z1) z1 = binBox[o + 5];
      rightArea[b] = x1 >= x0 ? halfArea(x0, y0, z0, x1, y1, z1) : 0;
    }
    x0 = y0 = z0 = Infinity;
    x1 = y1 = z1 = -Infinity;
    let left = 0;
    let bestCost = Infinity;
    let bestPlane = -1;
    for (let b = 0; b < BINS - 1; b++) {
      const o = b * 6;
      if (binBox[o] < x0) x0 = binBox[o];
      if (binBox[o + 1] < y0) y0 = binBox[o + 1];
      if (binBox[o + 2] < z0) z0 = binBox[o + 2];
      if (binBox[o + 3] > x1) x1 = binBox[o + 3];
      if (binBox[o + 4] > y1) y1 = binBox[o + 4];
      if (binBox[o + 5] > z1) z1 = binBox[o + 5];
      left += binCount[b];
      const right = count - left;
      if (left === 0 || right === 0) continue;
      const cost = left * halfArea(x0, y0, z0, x1, y1, z1) + right * rightArea[b + 1];
      if (cost < bestCost) {
        bestCost = cost;
        bestPlane = b;
      }
    }
    this.bestCost = bestCost;
    this.bestPlane = bestPlane;
    // The two sides' boxes: unions of their bins.
    split.fill(Infinity, 0, 3);
    split.fill(-Infinity, 3, 6);
    split.fill(Infinity, 6, 9);
    split.fill(-Infinity, 9, 12);
    for (let b = 0; b < BINS; b++) {
      if (binCount[b] === 0) continue;
      const s = b <= bestPlane ? 0 : 6;
      const o = b * 6;
      for (let a = 0; a < 3; a++) {
        if (binBox[o + a] < split[s + a]) split[s + a] = binBox[o + a];
        if (binBox[o + 3 + a] > split[s + 3 + a]) split[s + 3 + a] = binBox[o + 3 + a];
      }
    }
  }

  /**
   * Moves the primitives whose bin is ≤ plane to the front of [start, end)
   * (boxes, centroids and references together), gathering each side's
   * centroid bounds into childCen; returns the first index of the right side.
   */
  private partition(
    start: number,
    end: number,
    axis: number,
    cMin: number,
    scale: number,
    plane: number,
  ): number {
    const { boxes, cen, refs } = this;
    // Bounds gathered in the array itself: a long first call runs on
    // on-stack replacement, and code after its loop would deoptimise for
    // want of type feedback (it did, 1,489 times for 300k boxes).
    const cc = this.childCen;
    cc.fill(Infinity, 0, 3);
    cc.fill(-Infinity, 3, 6);
    cc.fill(Infinity, 6, 9);
    cc.fill(-Infinity, 9, 12);
    let i = start;
    let j = end - 1;
    while (i <= j) {
      const x = cen[i * 3],
        y = cen[i * 3 + 1],
        z = cen[i * 3 + 2];
      const c = axis === 0 ? x : axis === 1 ? y : z;
      let side = 0;
      if (binOf(c, cMin, scale) <= plane) i++;
      else {
        side = 6;
        // Swap primitive i with primitive j.
        cen[i * 3] = cen[j * 3];
        cen[i * 3 + 1] = cen[j * 3 + 1];
        cen[i * 3 + 2] = cen[j * 3 + 2];
        cen[j * 3] = x;
        cen[j * 3 + 1] = y;
        cen[j * 3 + 2] = z;
        const bi = i * 6;
        const bj = j * 6;
        for (let k = 0; k < 6; k++) {
          const v = boxes[bi + k];
          boxes[bi + k] = boxes[bj + k];
          boxes[bj + k] = v;
        }
        const r = refs[i];
        refs[i] = refs[j];
        refs[j] = r;
        j--;
      }
      if (x < cc[side]) cc[side] = x;
      if (y < cc[side + 1]) cc[side + 1] = y;
      if (z < cc[side + 2]) cc[side + 2] = z;
      if (x > cc[side + 3]) cc[side + 3] = x;
      if (y > cc[side + 4]) cc[side + 4] = y;
      if (z > cc[side + 5]) cc[side + 5] = z;
    }
    return i;
  }

  /** Splits [start, end) in the middle of its order: boxes into split, centroids into childCen. */
  private middleSplit(start: number, end: number): number {
    const mid = start + ((end - start) >> 1);
    this.rangeBounds(start, mid, 0);
    this.rangeBounds(mid, end, 6);
    return mid;
  }

  /**
   * Orders the primitives [start, end) by centroid along `axis` (ties by their
   * present order, so the result is deterministic). Done once per range that
   * falls back to median splits; its halves stay ordered, so the subtree below
   * costs O(m log m) in all.
   */
  private sortRange(start: number, end: number, axis: number): void {
    const { boxes, cen, refs } = this;
    const m = end - start;
    const order = new Int32Array(m);
    for (let k = 0; k < m; k++) order[k] = start + k;
    const key = new Float64Array(m);
    for (let k = 0; k < m; k++) key[k] = cen[(start + k) * 3 + axis];
    const sortedOrder = Array.from(order).sort((a, b) => key[a - start] - key[b - start] || a - b);
    const box = boxes.slice(start * 6, end * 6);
    const c = cen.slice(start * 3, end * 3);
    const r = refs.slice(start, end);
    for (let k = 0; k < m; k++) {
      const from = sortedOrder[k] - start;
      const to = start + k;
      for (let q = 0; q < 6; q++) boxes[to * 6 + q] = box[from * 6 + q];
      for (let q = 0; q < 3; q++) cen[to * 3 + q] = c[from * 3 + q];
      refs[to] = r[from];
    }
  }

  /**
   * Box (into split[at, at + 6)) and centroid bounds (into childCen[at,
   * at + 6)) of primitives [start, end), for the middle split of
   * coincident centroids.
   */
  private rangeBounds(start: number, end: number, at: number): void {
    const { boxes, cen, split, childCen } = this;
    for (let a = 0; a < 3; a++) {
      split[at + a] = childCen[at + a] = Infinity;
      split[at + 3 + a] = childCen[at + 3 + a] = -Infinity;
    }
    for (let p = start; p < end; p++) {
      for (let a = 0; a < 3; a++) {
        const lo = boxes[p * 6 + a];
        const hi = boxes[p * 6 + 3 + a];
        const c = cen[p * 3 + a];
        if (lo < split[at + a]) split[at + a] = lo;
        if (hi > split[at + 3 + a]) split[at + 3 + a] = hi;
        if (c < childCen[at + a]) childCen[at + a] = c;
        if (c > childCen[at + 3 + a]) childCen[at + 3 + a] = c;
      }
    }
  }
}

/**
 * The bin of centroid coordinate c: held to [0, BINS), since a Float32 centroid may round
 * a little outside the bounds its task was given in double precision.
 */
function binOf(c: number, cMin: number, scale: number): number {
  const bin = ((c - cMin) * scale) | 0;
  return bin < 0 ? 0 : bin >= BINS ? BINS - 1 : bin;
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
