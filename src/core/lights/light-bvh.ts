/**
 * Many-light sampling: a BVH over every bounded emitter — each emissive sphere, quad
 * and punctual point or spot light, and each triangle of an emissive mesh — that picks
 * one for a reference point in proportion to an estimate of its contribution there
 * (light-bounds.ts), after pbrt-v4's `BVHLightSampler` (pbr-book 4e §12.6.3; Conty
 * Estevez and Kulla 2018). The environment map and directional lights, which no box
 * bounds, are chosen on their own: with n of them, each with probability 1 / (n + 1),
 * the BVH with the rest (pbrt's pInfinite).
 *
 * The choice walks down from the root with one number, picking a child in proportion
 * to its importance and rescaling the number into the child's share, so a stratified
 * number stays stratified over the lights. Its probability is the product of those
 * shares; `pmf` recomputes the same products in the same order, from the root down,
 * so MIS reads exactly the probability with which the light was chosen. A child of
 * importance 0 is never chosen and has probability 0; emitters it holds are then
 * reached by BSDF sampling alone (MIS weight 1), which keeps the estimate unbiased
 * whether or not the bounds are tight.
 *
 * Leaves hold one emitter each. The build splits by pbrt's surface-area–orientation
 * heuristic over 12 buckets per axis; past MAX_SAH_DEPTH it halves the range, so the
 * tree is at most MAX_SAH_DEPTH + log2(n) deep whatever the input.
 */
import {
  LB_MAX,
  LB_MIN,
  LB_PHI,
  LB_STRIDE,
  IP_STRIDE,
  IP_CENTRE,
  IP_R2,
  IP_PHI,
  IP_COS_O,
  copyBounds,
  packBounds,
  importance,
  orientationMeasure,
  unionBounds,
} from './light-bounds.ts';

/** What the BVH is built from: one bounds record per emitter, and what each one is. */
export interface LightBvhInput {
  /** LB_STRIDE numbers per emitter (light-bounds.ts); phi relative to the largest. */
  bounds: Float64Array;
  /** The light-list entry of each emitter. */
  light: Int32Array;
  /** The triangle of a mesh emitter, −1 for the others. */
  triangle: Int32Array;
  /** Light-list entries of the unbounded lights (environment, directional). */
  infinite: Int32Array;
  /** Area of each mesh emitter's triangle (0 for the others). */
  area: Float64Array;
  /**
   * Per light-list entry: its emitter, or for a mesh the emitter of its first triangle
   * (the mesh's triangles follow in order); −1 for the unbounded ones.
   */
  primBase: Int32Array;
  /** Per light-list entry: a mesh's first triangle (0 for the others). */
  firstTriangle: Int32Array;
}

/** What `choose` writes. */
export interface LightChoice {
  light: number;
  triangle: number;
  /** Probability of the choice. */
  pick: number;
}

const BUCKETS = 12;
const MAX_SAH_DEPTH = 48;
const ONE_MINUS_EPSILON = 1 - 2 ** -53;
/**
 * The most lights splitting samples at one point (the default light sampler's, see
 * PathTracer): measured on the 10,000-lamp hall (bench/many-lights.ts, BENCHMARKS.md),
 * where 8 and 16 gave about the same error at equal time, 4 far less.
 */
export const LIGHT_SPLIT = 12;
/**
 * Splitting opens a node only where the point lies within its bounding sphere (half-
 * diagonal over distance above 1): there the node's importance, whose distance is
 * clamped by that half-diagonal, says least about the emitters inside.
 */
const SPLIT_ANGLE2 = 1;
/**
 * Below a node that is far and emits one way, its children are chosen by power alone
 * (childShares): where the node's squared half-diagonal is under FAR2 times the squared
 * distance to its centre (it subtends under about 18° from the point), its children's
 * distances differ by at most about a third, and where its cone of normals is within
 * acos(NARROW) (about 8°) of one axis, they face the point alike. Their importance ratio
 * is then close to their power ratio, so its evaluation (most of a descent's cost) buys
 * little. On the 10,000-lamp hall this made a sample about 20 % cheaper at the same error
 * per sample (FAR2 0.1; 0.25 cost 4 % more error, 1 cost 70 %); on the emissive room,
 * whose lamp is one curved mesh, the cone test keeps the full importance
 * (BENCHMARKS.md, many lights). choose and pmf both read the shares from childShares, so
 * the probability MIS uses stays the choice's to the bit.
 */
const FAR2 = 0.1;
const NARROW = 0.99;

export class LightBvh {
  /** Bounded emitters. */
  readonly count: number;
  readonly primLight: Int32Array;
  readonly primTriangle: Int32Array;
  readonly primArea: Float64Array;
  readonly primBase: Int32Array;
  readonly firstTriangle: Int32Array;
  readonly infinite: Int32Array;
  /** Probability of choosing each unbounded light. */
  readonly infinitePick: number;
  /** Probability of choosing the BVH (1 − n · infinitePick). */
  readonly bvhPick: number;
  /** What importance reads, IP_STRIDE numbers per node (packBounds). */
  readonly packed: Float64Array;
  /** Per node: the right child (the left is the next node), or −1 − the emitter at a leaf. */
  readonly child: Int32Array;
  readonly parent: Int32Array;
  /** The leaf node of each emitter. */
  readonly leafOf: Int32Array;
  readonly depth: number;
  /**
   * The shading point every query reads: (x, y, z) and its normal (nx, ny, nz), all
   * zero where there is no surface. The caller sets it (`setPoint`, a call small enough
   * to inline) before `choose`, `chooseSplit` or `pmf`: these read it from a typed array,
   * not as six arguments, because V8 boxes each double argument of a call it does not
   * inline, and the traversal's calls are not.
   */
  readonly point = new Float64Array(6);
  /** Scratch path of pmf (one BVH per thread's light list). */
  private readonly path: Int32Array;
  /** What childShares writes: the left and right child's share of the last node asked. */
  private share0 = 0;
  private share1 = 0;
  /** Splitting's scratch (chooseSplit, cut): the cut's nodes and their importance. */
  private readonly cutNode = new Int32Array(LIGHT_SPLIT);
  private readonly cutImp = new Float64Array(LIGHT_SPLIT);
  private readonly choice: LightChoice = { light: -1, triangle: -1, pick: 0 };
  /** What chooseSplit writes: the chosen lights, their triangles and probabilities. */
  readonly chosenLight = new Int32Array(LIGHT_SPLIT);
  readonly chosenTriangle = new Int32Array(LIGHT_SPLIT);
  readonly chosenPick = new Float64Array(LIGHT_SPLIT);

  constructor(input: LightBvhInput) {
    const n = input.light.length;
    this.count = n;
    this.primLight = input.light;
    this.primTriangle = input.triangle;
    this.primArea = input.area;
    this.primBase = input.primBase;
    this.firstTriangle = input.firstTriangle;
    this.infinite = input.infinite;
    const ni = input.infinite.length;
    this.infinitePick = ni > 0 ? 1 / (ni + (n > 0 ? 1 : 0)) : 0;
    this.bvhPick = n > 0 ? 1 - ni * this.infinitePick : 0;
    const nodeCount = Math.max(0, 2 * n - 1);
    // Node bounds, LB_STRIDE numbers per node (node 0 is the root): the build's alone.
    // Traversal reads the packed records, so these go once packed.
    const nodes = new Float64Array(nodeCount * LB_STRIDE);
    this.child = new Int32Array(nodeCount);
    this.parent = new Int32Array(nodeCount).fill(-1);
    this.leafOf = new Int32Array(n);
    const order = new Int32Array(n);
    for (let i = 0; i < n; i++) order[i] = i;
    const b = new Builder(input.bounds, order, nodes, this);
    const depth = n > 0 ? b.build(0, n, 0) : 0;
    this.packed = new Float64Array(nodeCount * IP_STRIDE);
    for (let k = 0; k < nodeCount; k++) {
      packBounds(nodes, k * LB_STRIDE, this.packed, k * IP_STRIDE);
    }
    this.depth = depth;
    this.path = new Int32Array(depth + 1);
  }

  /** Sets the point every query reads (see `point`). */
  setPoint(x: number, y: number, z: number, nx: number, ny: number, nz: number): void {
    const p = this.point;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    p[3] = nx;
    p[4] = ny;
    p[5] = nz;
  }

  /** The emitter of light-list entry l (its triangle t for a mesh; else t is ignored). */
  primOf(l: number, t: number): number {
    return this.primBase[l] + (t >= 0 ? t - this.firstTriangle[l] : 0);
  }

  /**
   * Chooses a light for the point (`setPoint`) from u in [0, 1). Returns false when none
   * can contribute (then out is not written).
   */
  choose(u: number, out: LightChoice): boolean {
    const ni = this.infinite.length;
    const pInf = ni * this.infinitePick;
    if (u < pInf) {
      const i = Math.min(Math.floor((u / pInf) * ni), ni - 1);
      out.light = this.infinite[i];
      out.triangle = -1;
      out.pick = this.infinitePick;
      return true;
    }
    if (this.count === 0) return false;
    u = Math.min((u - pInf) / (1 - pInf), ONE_MINUS_EPSILON);
    if (this.child[0] < 0) {
      if (!(importance(this.packed, 0, this.point) > 0)) return false;
    }
    return this.descend(0, this.bvhPick, u, out);
  }

  /**
   * Splitting (Conty Estevez and Kulla 2018, §5): up to `max` lights for the point, one
   * from each subtree of the cut `cut` makes, each chosen as `choose` would from there
   * with the same number u. Writes chosenLight, chosenTriangle and chosenPick (the
   * probability that the light is among those chosen) and returns how many. A light
   * that the point's cut holds in a subtree is then sampled with the probability
   * `pmf(prim, max)` gives, and the sum over the chosen lights of f / pick is an
   * unbiased estimate of the sum over all of them. With max 1 it is `choose`.
   */
  chooseSplit(u: number, max: number): number {
    const ch = this.choice;
    const pInf = this.infinite.length * this.infinitePick;
    if (max <= 1 || u < pInf) {
      if (!this.choose(u, ch)) return 0;
      this.chosenLight[0] = ch.light;
      this.chosenTriangle[0] = ch.triangle;
      this.chosenPick[0] = ch.pick;
      return 1;
    }
    if (this.count === 0) return 0;
    u = Math.min((u - pInf) / (1 - pInf), ONE_MINUS_EPSILON);
    const n = this.cut(max);
    let k = 0;
    for (let j = 0; j < n; j++) {
      if (!this.descend(this.cutNode[j], this.bvhPick, u, ch)) continue;
      this.chosenLight[k] = ch.light;
      this.chosenTriangle[k] = ch.triangle;
      this.chosenPick[k] = ch.pick;
      k++;
    }
    return k;
  }

  /**
   * The cut of the tree splitting makes at the point: starting from the root, the node
   * of largest importance among those the point sees under a wide angle (squared
   * half-diagonal over squared distance above SPLIT_ANGLE2) is replaced by its children
   * of nonzero importance, until none is left or the cut holds `max` nodes. Writes
   * cutNode and returns the count. A function of the point and `max` alone, so `pmf`
   * rebuilds the same cut.
   */
  private cut(max: number): number {
    const p = this.point;
    const x = p[0],
      y = p[1],
      z = p[2];
    const packed = this.packed;
    const child = this.child;
    const cutNode = this.cutNode;
    const cutImp = this.cutImp;
    const i0 = importance(packed, 0, p);
    if (!(i0 > 0)) return 0;
    cutNode[0] = 0;
    cutImp[0] = i0;
    let n = 1;
    max = Math.min(max, LIGHT_SPLIT);
    while (n < max) {
      let best = -1;
      let bestImp = -1;
      for (let j = 0; j < n; j++) {
        const node = cutNode[j];
        if (child[node] < 0 || !(cutImp[j] > bestImp)) continue;
        const od = node * IP_STRIDE;
        const dx = x - packed[od + IP_CENTRE],
          dy = y - packed[od + IP_CENTRE + 1],
          dz = z - packed[od + IP_CENTRE + 2];
        if (packed[od + IP_R2] > SPLIT_ANGLE2 * (dx * dx + dy * dy + dz * dz)) {
          best = j;
          bestImp = cutImp[j];
        }
      }
      if (best < 0) break;
      const node = cutNode[best];
      const c = child[node];
      const a = importance(packed, (node + 1) * IP_STRIDE, p);
      const b = importance(packed, c * IP_STRIDE, p);
      if (a > 0) {
        cutNode[best] = node + 1;
        cutImp[best] = a;
        if (b > 0) {
          cutNode[n] = c;
          cutImp[n] = b;
          n++;
        }
      } else if (b > 0) {
        cutNode[best] = c;
        cutImp[best] = b;
      } else {
        n--;
        cutNode[best] = cutNode[n];
        cutImp[best] = cutImp[n];
      }
    }
    return n;
  }

  /** Walks down from `node` (of nonzero importance) with u; see choose. */
  private descend(node: number, pick: number, u: number, out: LightChoice): boolean {
    const child = this.child;
    for (;;) {
      const c = child[node];
      if (c < 0) {
        const p = -1 - c;
        out.light = this.primLight[p];
        out.triangle = this.primTriangle[p];
        out.pick = pick;
        return true;
      }
      if (!this.childShares(node)) return false;
      const p0 = this.share0;
      if (u < p0) {
        u = Math.min(u / p0, ONE_MINUS_EPSILON);
        pick *= p0;
        node = node + 1;
      } else {
        u = Math.min((u - p0) / (1 - p0), ONE_MINUS_EPSILON);
        pick *= this.share1;
        node = c;
      }
    }
  }

  /**
   * The probability with which `chooseSplit(…, max)` (with max 1: `choose`) picks
   * emitter `prim` at the point: the same cut, then the same shares below it, multiplied
   * in the same order.
   */
  pmf(prim: number, max = 1): number {
    const path = this.path;
    let k = 0;
    for (let node = this.leafOf[prim]; node >= 0; node = this.parent[node]) path[k++] = node;
    // i: the path's entry below which the choice is by shares (k − 1: the root).
    let i = k - 1;
    if (max > 1) {
      const n = this.cut(max);
      const cutNode = this.cutNode;
      find: for (; i >= 0; i--) {
        for (let j = 0; j < n; j++) if (cutNode[j] === path[i]) break find;
      }
      if (i < 0) return 0;
    } else if (k === 1 && !(importance(this.packed, 0, this.point) > 0)) {
      return 0;
    }
    let pick = this.bvhPick;
    for (; i > 0; i--) {
      const node = path[i];
      if (!this.childShares(node)) return 0;
      pick *= path[i - 1] === node + 1 ? this.share0 : this.share1;
    }
    return pick;
  }

  /**
   * The shares of interior node `node`'s children at the point, into share0 (the left,
   * node + 1) and share1 (the right): each child's importance over their sum (their power
   * over their sum below a far node that faces one way: FAR2). `choose`
   * and `pmf` both read them from here, so the probability MIS reads is the choice's to
   * the bit. False when neither child can contribute.
   */
  private childShares(node: number): boolean {
    const p = this.point;
    const packed = this.packed;
    const c = this.child[node];
    const od = node * IP_STRIDE;
    if (packed[od + IP_COS_O] >= NARROW) {
      const dx = p[0] - packed[od + IP_CENTRE],
        dy = p[1] - packed[od + IP_CENTRE + 1],
        dz = p[2] - packed[od + IP_CENTRE + 2];
      if (packed[od + IP_R2] < FAR2 * (dx * dx + dy * dy + dz * dz)) {
        // Far and facing one way: by power (see FAR2).
        const f0 = packed[(node + 1) * IP_STRIDE + IP_PHI];
        const f1 = packed[c * IP_STRIDE + IP_PHI];
        const fs = f0 + f1;
        if (fs > 0 && fs < Infinity) {
          this.share0 = f0 / fs;
          this.share1 = f1 / fs;
          return true;
        }
      }
    }
    let c0 = importance(packed, (node + 1) * IP_STRIDE, p);
    let c1 = importance(packed, c * IP_STRIDE, p);
    if (c0 === Infinity || c1 === Infinity) {
      // Overflow (a point on a point light, say): the infinite ones share equally.
      c0 = c0 === Infinity ? 1 : 0;
      c1 = c1 === Infinity ? 1 : 0;
    }
    const sum = c0 + c1;
    if (!(sum > 0)) return false;
    this.share0 = c0 / sum;
    this.share1 = c1 / sum;
    return true;
  }
}

/** The top-down build (pbrt-v4 `BVHLightSampler::buildBVH`), nodes in depth-first order. */
class Builder {
  private next = 0;
  /** Scratch bounds: the buckets, and the running unions of a sweep. */
  private readonly bucket = new Float64Array(BUCKETS * LB_STRIDE);
  private readonly below = new Float64Array(BUCKETS * LB_STRIDE);
  private readonly acc = new Float64Array(LB_STRIDE);
  private readonly count = new Int32Array(BUCKETS);
  private readonly scratch: Int32Array;

  constructor(
    private readonly prims: Float64Array,
    private readonly order: Int32Array,
    private readonly nodes: Float64Array,
    private readonly bvh: LightBvh,
  ) {
    this.scratch = new Int32Array(order.length);
  }

  /** Builds the node for order[start, end); returns the subtree's depth. */
  build(start: number, end: number, depth: number): number {
    const node = this.next++;
    const nodes = this.nodes;
    const o = node * LB_STRIDE;
    const prims = this.prims;
    const order = this.order;
    if (end - start === 1) {
      const p = order[start];
      copyBounds(prims, p * LB_STRIDE, nodes, o);
      this.bvh.child[node] = -1 - p;
      this.bvh.leafOf[p] = node;
      return 0;
    }
    const mid = this.split(start, end, depth);
    const d0 = this.build(start, mid, depth + 1);
    const right = this.next;
    const d1 = this.build(mid, end, depth + 1);
    this.bvh.child[node] = right;
    this.bvh.parent[node + 1] = node;
    this.bvh.parent[right] = node;
    unionBounds(nodes, (node + 1) * LB_STRIDE, nodes, right * LB_STRIDE, nodes, o);
    return 1 + Math.max(d0, d1);
  }

  /** Orders order[start, end) and returns where its second part starts. */
  private split(start: number, end: number, depth: number): number {
    const half = (start + end) >> 1;
    if (depth >= MAX_SAH_DEPTH) return half;
    const prims = this.prims;
    const order = this.order;
    // Bounds of everything and of the centroids.
    const lo = [Infinity, Infinity, Infinity];
    const hi = [-Infinity, -Infinity, -Infinity];
    const clo = [Infinity, Infinity, Infinity];
    const chi = [-Infinity, -Infinity, -Infinity];
    for (let i = start; i < end; i++) {
      const o = order[i] * LB_STRIDE;
      for (let k = 0; k < 3; k++) {
        const a = prims[o + LB_MIN + k],
          b = prims[o + LB_MAX + k];
        lo[k] = Math.min(lo[k], a);
        hi[k] = Math.max(hi[k], b);
        const c = 0.5 * a + 0.5 * b;
        clo[k] = Math.min(clo[k], c);
        chi[k] = Math.max(chi[k], c);
      }
    }
    const extent = [
      0.5 * hi[0] - 0.5 * lo[0],
      0.5 * hi[1] - 0.5 * lo[1],
      0.5 * hi[2] - 0.5 * lo[2],
    ];
    const maxExtent = Math.max(extent[0], extent[1], extent[2]);
    let bestCost = Infinity;
    let bestDim = -1;
    let bestBucket = -1;
    const bucket = this.bucket;
    const below = this.below;
    const acc = this.acc;
    for (let dim = 0; dim < 3; dim++) {
      if (!(chi[dim] > clo[dim])) continue;
      const scale = BUCKETS / (chi[dim] - clo[dim]);
      if (!(scale < Infinity)) continue;
      bucket.fill(0);
      this.count.fill(0);
      for (let i = start; i < end; i++) {
        const o = order[i] * LB_STRIDE;
        const b = this.bucketOf(o, dim, clo[dim], scale);
        const bo = b * LB_STRIDE;
        if (this.count[b]++ === 0) copyBounds(prims, o, bucket, bo);
        else unionBounds(bucket, bo, prims, o, bucket, bo);
      }
      // Sweep from the left: below[i] = union of buckets 0…i.
      for (let i = 0; i < BUCKETS; i++) {
        if (i === 0) copyBounds(bucket, 0, below, 0);
        else unionBounds(below, (i - 1) * LB_STRIDE, bucket, i * LB_STRIDE, below, i * LB_STRIDE);
      }
      // From the right, costing each split between buckets i and i + 1.
      const kr = extent[dim] > 0 ? maxExtent / extent[dim] : Infinity;
      let rightCount = 0;
      let leftCount = end - start;
      for (let i = BUCKETS - 1; i > 0; i--) {
        rightCount += this.count[i];
        leftCount -= this.count[i];
        if (i === BUCKETS - 1) copyBounds(bucket, i * LB_STRIDE, acc, 0);
        else unionBounds(acc, 0, bucket, i * LB_STRIDE, acc, 0);
        if (rightCount === 0 || leftCount === 0) continue;
        const cost = kr * (cost1(below, (i - 1) * LB_STRIDE) + cost1(acc, 0));
        if (cost < bestCost) {
          bestCost = cost;
          bestDim = dim;
          bestBucket = i;
        }
      }
    }
    if (bestDim < 0) return half;
    // A stable partition: buckets below bestBucket first.
    const scale = BUCKETS / (chi[bestDim] - clo[bestDim]);
    const scratch = this.scratch;
    let a = start;
    let c = 0;
    for (let i = start; i < end; i++) {
      const p = order[i];
      if (this.bucketOf(p * LB_STRIDE, bestDim, clo[bestDim], scale) < bestBucket) order[a++] = p;
      else scratch[c++] = p;
    }
    for (let i = 0; i < c; i++) order[a + i] = scratch[i];
    return a === start || a === end ? half : a;
  }

  private bucketOf(o: number, dim: number, lo: number, scale: number): number {
    const prims = this.prims;
    const c = 0.5 * prims[o + LB_MIN + dim] + 0.5 * prims[o + LB_MAX + dim];
    const b = Math.floor((c - lo) * scale);
    return b < 0 ? 0 : b >= BUCKETS ? BUCKETS - 1 : b;
  }
}

/**
 * One side's cost (pbrt-v4 `EvaluateCost` without Kr): power × orientation measure ×
 * surface area of the box (computed on half-extents, so it does not overflow).
 */
function cost1(b: Float64Array, o: number): number {
  const phi = b[o + LB_PHI];
  if (!(phi > 0)) return 0;
  const dx = 0.5 * b[o + LB_MAX] - 0.5 * b[o + LB_MIN];
  const dy = 0.5 * b[o + LB_MAX + 1] - 0.5 * b[o + LB_MIN + 1];
  const dz = 0.5 * b[o + LB_MAX + 2] - 0.5 * b[o + LB_MIN + 2];
  // The surface area up to a factor 8; a flat box (one emitter's plane) still counts.
  const area = dx * dy + dy * dz + dz * dx;
  return phi * orientationMeasure(b, o) * (area > 0 ? area : Number.MIN_VALUE);
}
