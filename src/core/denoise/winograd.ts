/**
 * The U-Net's 3×3 convolutions by Winograd's minimal filtering F(6×6, 3×3) (Lavin and
 * Gray 2016, "Fast Algorithms for Convolutional Neural Networks", §4–5): each 6×6 block
 * of outputs is Aᵀ[(G g Gᵀ) ⊙ (Bᵀ d B)]A over the 8×8 input window d. Per block and
 * pair of channels that is 64 multiply-adds instead of the direct convolution's 324, so
 * the layer becomes 64 small matrix products (tiles × in-channels by in-channels ×
 * out-channels, one per point of the 8×8 transform domain) between two cheap linear
 * transforms. Scalar JavaScript has no SIMD (docs/denoise.md, Speed): fewer
 * multiplications is the lever left.
 *
 * Precision: the transforms and the products run in double, the input transform and the
 * products are kept in Float64Array scratch, and only the transformed weights are stored
 * as float32 (a relative rounding of 2⁻²⁴ each). The result differs from the direct
 * convolution's by rounding only (tests/unit/core/denoise-winograd.test.ts).
 *
 * Determinism: a pixel's value depends only on its 6×6 block's 8×8 input window, the
 * weights and a fixed order of additions, never on the block of tiles it is computed in
 * or the thread; tile positions are fixed by the feature map, as the direct
 * convolution's rows were.
 *
 * The matrices are Cook–Toom's for the points 0, ±1, ±1/2, ±2 and ∞ (as in Lavin and
 * Gray, and NNPACK's F(6×6, 3×3)), checked in exact rational arithmetic against the
 * correlation they compute when they were written out here; the tests compare every
 * layer shape the network uses with the direct convolution. F(4×4, 3×3) (36 per 16
 * outputs) ran 9–18 % slower per layer on the 2-core machine, with the same rounding
 * (under 16 ulps of Σ|w·x| in the tests).
 */
import type { Planes } from './planes.ts';
import type { ConvLayer } from './unet-weights.ts';

/** Tiles transformed and multiplied together (64 ran 8 % faster than 32 in the products). */
export const WINOGRAD_TILES = 64;

/** Scratch for `winogradConv3x3Relu`, sized for the widest layer it will see. */
export interface WinogradScratch {
  /** Transformed inputs: [64][inChannels][WINOGRAD_TILES]. */
  readonly v: Float64Array;
  /** Products: [64][outChannels][WINOGRAD_TILES]. */
  readonly m: Float64Array;
  /** One 8×8 window between the transform's two passes. */
  readonly t: Float64Array;
}

/**
 * Floats between one transform point's matrix and the next: the matrix plus one cache
 * line. Unpadded, the 64 values of one tile lay a multiple of 4 KB apart and fell into
 * the same L1 set.
 */
function pointStride(channels: number): number {
  return channels * WINOGRAD_TILES + 8;
}

export function allocWinogradScratch(maxIn: number, maxOut: number): WinogradScratch {
  return {
    v: new Float64Array(64 * pointStride(maxIn)),
    m: new Float64Array(64 * pointStride(maxOut)),
    t: new Float64Array(64),
  };
}

/** Whether a layer goes through Winograd: out-channels in fours (dec_conv0's 3 does not). */
export function winogradFits(layer: ConvLayer): boolean {
  return layer.outChannels % 4 === 0;
}

const transformed = new WeakMap<ConvLayer, Float32Array>();

/**
 * U = G g Gᵀ for every (out, in) pair, laid out [64][inChannels][outChannels] so that the
 * product's inner loop (over in-channels) reads four adjacent out-channels. Computed once
 * per layer and thread.
 */
export function winogradWeights(layer: ConvLayer): Float32Array {
  let u = transformed.get(layer);
  if (u) return u;
  const cin = layer.inChannels;
  const cout = layer.outChannels;
  const w = layer.weight;
  u = new Float32Array(64 * cin * cout);
  const gg = new Float64Array(24);
  const step = cin * cout;
  for (let o = 0; o < cout; o++)
    for (let c = 0; c < cin; c++) {
      const q = (o * cin + c) * 9;
      // G g: 8×3, one column of g at a time.
      for (let j = 0; j < 3; j++) applyG(w[q + j]!, w[q + 3 + j]!, w[q + 6 + j]!, gg, j, 3);
      // (G g) Gᵀ: 8×8, one row of G g at a time.
      for (let i = 0; i < 8; i++) {
        const r = i * 3;
        applyG(gg[r]!, gg[r + 1]!, gg[r + 2]!, u, (i * 8 * cin + c) * cout + o, step);
      }
    }
  transformed.set(layer, u);
  return u;
}

/** out[o + i·step] ← (G g)ᵢ for the 3-vector g, i = 0 … 7 (computed in double). */
function applyG(
  g0: number,
  g1: number,
  g2: number,
  out: Float32Array | Float64Array,
  o: number,
  step: number,
): void {
  out[o] = -g0;
  out[o + step] = -(2 / 9) * g0 - (2 / 9) * g1 - (2 / 9) * g2;
  out[o + 2 * step] = -(2 / 9) * g0 + (2 / 9) * g1 - (2 / 9) * g2;
  out[o + 3 * step] = (32 / 45) * g0 + (16 / 45) * g1 + (8 / 45) * g2;
  out[o + 4 * step] = (32 / 45) * g0 - (16 / 45) * g1 + (8 / 45) * g2;
  out[o + 5 * step] = (1 / 90) * g0 + (1 / 45) * g1 + (2 / 45) * g2;
  out[o + 6 * step] = (1 / 90) * g0 - (1 / 45) * g1 + (2 / 45) * g2;
  out[o + 7 * step] = g2;
}

/** Rows of 6×6 blocks that cover a map of h rows. */
export function winogradRows(h: number): number {
  return Math.ceil(h / 6);
}

/**
 * dst ← ReLU(conv3x3([a, b], layer)), as `conv3x3Relu`, for block rows r0 … r1 − 1 (of
 * `winogradRows(dst.h)`); the layer must `winogradFits`.
 */
export function winogradConv3x3Relu(
  a: Planes,
  b: Planes | null,
  layer: ConvLayer,
  dst: Planes,
  scratch: WinogradScratch,
  r0 = 0,
  r1 = winogradRows(dst.h),
): void {
  const cin = a.c + (b ? b.c : 0);
  const cout = layer.outChannels;
  if (cin !== layer.inChannels)
    throw new RangeError(`${layer.name}: ${cin} input channels, expected ${layer.inChannels}`);
  if (cout > dst.capacity)
    throw new RangeError(`${layer.name}: output has room for ${dst.capacity} channels`);
  if (a.h !== dst.h || a.w !== dst.w || (b && (b.h !== dst.h || b.w !== dst.w)))
    throw new RangeError(`${layer.name}: inputs and output differ in size`);
  if (!winogradFits(layer)) throw new RangeError(`${layer.name}: ${cout} outputs, not in fours`);
  if (scratch.v.length < 64 * pointStride(cin) || scratch.m.length < 64 * pointStride(cout))
    throw new RangeError(`${layer.name}: Winograd scratch too small`);
  dst.c = cout;
  const u = winogradWeights(layer);
  const tilesX = Math.ceil(dst.w / 6);
  const tiles = tilesX * Math.min(r1, winogradRows(dst.h));
  for (let t0 = tilesX * r0; t0 < tiles; t0 += WINOGRAD_TILES) {
    const n = Math.min(WINOGRAD_TILES, tiles - t0);
    for (let c = 0; c < cin; c++) {
      const fromA = c < a.c;
      const src = fromA ? a : b!;
      inputTransform(src, fromA ? c : c - a.c, c, cin, t0, n, tilesX, scratch);
    }
    products(scratch.v, u, scratch.m, cin, cout, n);
    for (let o = 0; o < cout; o++)
      outputTransform(scratch, o, cout, layer.bias[o]!, dst, t0, n, tilesX);
  }
}

/**
 * V[ξ][c][t] ← (Bᵀ d B)[ξ] for tiles t0 … t0 + n − 1 of channel `ch` of `src`.
 */
function inputTransform(
  src: Planes,
  ch: number,
  c: number,
  cin: number,
  t0: number,
  n: number,
  tilesX: number,
  s: WinogradScratch,
): void {
  const { h, w, stride } = src;
  const data = src.data;
  const base = ch * src.plane;
  const v = s.v;
  const tmp = s.t;
  const xiStride = pointStride(cin);
  const vc = c * WINOGRAD_TILES;
  for (let k = 0; k < n; k++) {
    const t = t0 + k;
    const ty = (t / tilesX) | 0;
    const tx = t - ty * tilesX;
    // The window's top-left, in the padded plane: rows 6ty … 6ty + 7, columns 6tx … 6tx + 7.
    const r0 = ty * 6;
    const c0 = tx * 6;
    const inside = r0 + 7 <= h + 1 && c0 + 7 <= w + 1;
    // Pass 1 (Bᵀ d), column by column; outside the padded plane the window reads zero.
    for (let j = 0; j < 8; j++) {
      const p = base + r0 * stride + c0 + j;
      let d0 = 0,
        d1 = 0,
        d2 = 0,
        d3 = 0,
        d4 = 0,
        d5 = 0,
        d6 = 0,
        d7 = 0;
      if (inside) {
        d0 = data[p]!;
        d1 = data[p + 1 * stride]!;
        d2 = data[p + 2 * stride]!;
        d3 = data[p + 3 * stride]!;
        d4 = data[p + 4 * stride]!;
        d5 = data[p + 5 * stride]!;
        d6 = data[p + 6 * stride]!;
        d7 = data[p + 7 * stride]!;
      } else if (c0 + j <= w + 1) {
        if (r0 + 0 <= h + 1) d0 = data[p]!;
        if (r0 + 1 <= h + 1) d1 = data[p + 1 * stride]!;
        if (r0 + 2 <= h + 1) d2 = data[p + 2 * stride]!;
        if (r0 + 3 <= h + 1) d3 = data[p + 3 * stride]!;
        if (r0 + 4 <= h + 1) d4 = data[p + 4 * stride]!;
        if (r0 + 5 <= h + 1) d5 = data[p + 5 * stride]!;
        if (r0 + 6 <= h + 1) d6 = data[p + 6 * stride]!;
        if (r0 + 7 <= h + 1) d7 = data[p + 7 * stride]!;
      }
      tmp[j] = -d0 + 5.25 * d2 - 5.25 * d4 + d6;
      tmp[8 + j] = d1 + d2 - 4.25 * d3 - 4.25 * d4 + d5 + d6;
      tmp[16 + j] = -d1 + d2 + 4.25 * d3 - 4.25 * d4 - d5 + d6;
      tmp[24 + j] = 2 * d1 + 4 * d2 - 2.5 * d3 - 5 * d4 + 0.5 * d5 + d6;
      tmp[32 + j] = -2 * d1 + 4 * d2 + 2.5 * d3 - 5 * d4 - 0.5 * d5 + d6;
      tmp[40 + j] = 0.5 * d1 + 0.25 * d2 - 2.5 * d3 - 1.25 * d4 + 2 * d5 + d6;
      tmp[48 + j] = -0.5 * d1 + 0.25 * d2 + 2.5 * d3 - 1.25 * d4 - 2 * d5 + d6;
      tmp[56 + j] = -d1 + 5.25 * d3 - 5.25 * d5 + d7;
    }
    // Pass 2 (… B), row by row, into V. Both passes stay written out: one helper for
    // both (as applyG is for the weights) was not inlined and made the network 30 % slower.
    const o = vc + k;
    for (let i = 0; i < 8; i++) {
      const e0 = tmp[i * 8]!,
        e1 = tmp[i * 8 + 1]!,
        e2 = tmp[i * 8 + 2]!,
        e3 = tmp[i * 8 + 3]!,
        e4 = tmp[i * 8 + 4]!,
        e5 = tmp[i * 8 + 5]!,
        e6 = tmp[i * 8 + 6]!,
        e7 = tmp[i * 8 + 7]!;
      const q = o + i * 8 * xiStride;
      v[q] = -e0 + 5.25 * e2 - 5.25 * e4 + e6;
      v[q + 1 * xiStride] = e1 + e2 - 4.25 * e3 - 4.25 * e4 + e5 + e6;
      v[q + 2 * xiStride] = -e1 + e2 + 4.25 * e3 - 4.25 * e4 - e5 + e6;
      v[q + 3 * xiStride] = 2 * e1 + 4 * e2 - 2.5 * e3 - 5 * e4 + 0.5 * e5 + e6;
      v[q + 4 * xiStride] = -2 * e1 + 4 * e2 + 2.5 * e3 - 5 * e4 - 0.5 * e5 + e6;
      v[q + 5 * xiStride] = 0.5 * e1 + 0.25 * e2 - 2.5 * e3 - 1.25 * e4 + 2 * e5 + e6;
      v[q + 6 * xiStride] = -0.5 * e1 + 0.25 * e2 + 2.5 * e3 - 1.25 * e4 - 2 * e5 + e6;
      v[q + 7 * xiStride] = -e1 + 5.25 * e3 - 5.25 * e5 + e7;
    }
  }
}

/**
 * M[ξ][o][t] = Σ_c V[ξ][c][t] U[ξ][c][o] for the 64 points ξ. The inner loop runs over the
 * tiles with a block of 4 in-channels × 16 out-channels of U held in locals (V8 keeps the
 * ones that do not fit in registers on the stack, read without bounds checks): 4 loads and
 * 16 read-modify-writes per 64 multiply-adds. That ran at 5.0–5.2 GMAC/s on the 2-core
 * machine, × 8 out-channels at 4.5–4.9 (as fast as the direct convolution), and 4 tiles ×
 * 4 out-channels summed in registers (8 loads per 16) at 3.1. Leftover in-channels go
 * one at a time, and so do all in-channels of leftover out-channels. The sum for each M
 * is taken in a fixed order: in-channel blocks in turn, four products inside a block.
 */
function products(
  v: Float64Array,
  u: Float32Array,
  m: Float64Array,
  cin: number,
  cout: number,
  n: number,
): void {
  const T = WINOGRAD_TILES;
  m.fill(0, 0, 64 * pointStride(cout));
  for (let xi = 0; xi < 64; xi++) {
    const vb = xi * pointStride(cin);
    const ub = xi * cin * cout;
    const mb = xi * pointStride(cout);
    let o = 0;
    for (; o + 16 <= cout; o += 16) {
      let c = 0;
      for (; c + 4 <= cin; c += 4)
        block4x16(v, u, m, vb + c * T, ub + c * cout + o, mb + o * T, cout, n);
      for (; c < cin; c++) block1xK(v, u, m, vb + c * T, ub + c * cout + o, mb + o * T, 16, n);
    }
    // Out-channels past the last 16 (none in OIDN's base and small networks, whose
    // widths all come in 16s), one in-channel at a time.
    if (o < cout)
      for (let c = 0; c < cin; c++)
        block1xK(v, u, m, vb + c * T, ub + c * cout + o, mb + o * T, cout - o, n);
  }
}

/** M[o … o + 15][t] += Σ over 4 in-channels c of V[c][t] U[c][o]. */
function block4x16(
  v: Float64Array,
  u: Float32Array,
  m: Float64Array,
  p0: number,
  q: number,
  k0: number,
  cout: number,
  n: number,
): void {
  const T = WINOGRAD_TILES;
  const a0 = u[q]!,
    a1 = u[q + 1]!,
    a2 = u[q + 2]!,
    a3 = u[q + 3]!,
    a4 = u[q + 4]!,
    a5 = u[q + 5]!,
    a6 = u[q + 6]!,
    a7 = u[q + 7]!,
    a8 = u[q + 8]!,
    a9 = u[q + 9]!,
    a10 = u[q + 10]!,
    a11 = u[q + 11]!,
    a12 = u[q + 12]!,
    a13 = u[q + 13]!,
    a14 = u[q + 14]!,
    a15 = u[q + 15]!;
  const q1 = q + 1 * cout;
  const b0 = u[q1]!,
    b1 = u[q1 + 1]!,
    b2 = u[q1 + 2]!,
    b3 = u[q1 + 3]!,
    b4 = u[q1 + 4]!,
    b5 = u[q1 + 5]!,
    b6 = u[q1 + 6]!,
    b7 = u[q1 + 7]!,
    b8 = u[q1 + 8]!,
    b9 = u[q1 + 9]!,
    b10 = u[q1 + 10]!,
    b11 = u[q1 + 11]!,
    b12 = u[q1 + 12]!,
    b13 = u[q1 + 13]!,
    b14 = u[q1 + 14]!,
    b15 = u[q1 + 15]!;
  const q2 = q + 2 * cout;
  const c0 = u[q2]!,
    c1 = u[q2 + 1]!,
    c2 = u[q2 + 2]!,
    c3 = u[q2 + 3]!,
    c4 = u[q2 + 4]!,
    c5 = u[q2 + 5]!,
    c6 = u[q2 + 6]!,
    c7 = u[q2 + 7]!,
    c8 = u[q2 + 8]!,
    c9 = u[q2 + 9]!,
    c10 = u[q2 + 10]!,
    c11 = u[q2 + 11]!,
    c12 = u[q2 + 12]!,
    c13 = u[q2 + 13]!,
    c14 = u[q2 + 14]!,
    c15 = u[q2 + 15]!;
  const q3 = q + 3 * cout;
  const d0 = u[q3]!,
    d1 = u[q3 + 1]!,
    d2 = u[q3 + 2]!,
    d3 = u[q3 + 3]!,
    d4 = u[q3 + 4]!,
    d5 = u[q3 + 5]!,
    d6 = u[q3 + 6]!,
    d7 = u[q3 + 7]!,
    d8 = u[q3 + 8]!,
    d9 = u[q3 + 9]!,
    d10 = u[q3 + 10]!,
    d11 = u[q3 + 11]!,
    d12 = u[q3 + 12]!,
    d13 = u[q3 + 13]!,
    d14 = u[q3 + 14]!,
    d15 = u[q3 + 15]!;
  for (let t = 0; t < n; t++) {
    const p = p0 + t;
    const x0 = v[p]!,
      x1 = v[p + T]!,
      x2 = v[p + 2 * T]!,
      x3 = v[p + 3 * T]!;
    const k = k0 + t;
    m[k] = m[k]! + (x0 * a0 + x1 * b0 + (x2 * c0 + x3 * d0));
    m[k + T] = m[k + T]! + (x0 * a1 + x1 * b1 + (x2 * c1 + x3 * d1));
    m[k + 2 * T] = m[k + 2 * T]! + (x0 * a2 + x1 * b2 + (x2 * c2 + x3 * d2));
    m[k + 3 * T] = m[k + 3 * T]! + (x0 * a3 + x1 * b3 + (x2 * c3 + x3 * d3));
    m[k + 4 * T] = m[k + 4 * T]! + (x0 * a4 + x1 * b4 + (x2 * c4 + x3 * d4));
    m[k + 5 * T] = m[k + 5 * T]! + (x0 * a5 + x1 * b5 + (x2 * c5 + x3 * d5));
    m[k + 6 * T] = m[k + 6 * T]! + (x0 * a6 + x1 * b6 + (x2 * c6 + x3 * d6));
    m[k + 7 * T] = m[k + 7 * T]! + (x0 * a7 + x1 * b7 + (x2 * c7 + x3 * d7));
    m[k + 8 * T] = m[k + 8 * T]! + (x0 * a8 + x1 * b8 + (x2 * c8 + x3 * d8));
    m[k + 9 * T] = m[k + 9 * T]! + (x0 * a9 + x1 * b9 + (x2 * c9 + x3 * d9));
    m[k + 10 * T] = m[k + 10 * T]! + (x0 * a10 + x1 * b10 + (x2 * c10 + x3 * d10));
    m[k + 11 * T] = m[k + 11 * T]! + (x0 * a11 + x1 * b11 + (x2 * c11 + x3 * d11));
    m[k + 12 * T] = m[k + 12 * T]! + (x0 * a12 + x1 * b12 + (x2 * c12 + x3 * d12));
    m[k + 13 * T] = m[k + 13 * T]! + (x0 * a13 + x1 * b13 + (x2 * c13 + x3 * d13));
    m[k + 14 * T] = m[k + 14 * T]! + (x0 * a14 + x1 * b14 + (x2 * c14 + x3 * d14));
    m[k + 15 * T] = m[k + 15 * T]! + (x0 * a15 + x1 * b15 + (x2 * c15 + x3 * d15));
  }
}

/** M[o … o + K − 1][t] += V[c][t] U[c][o …]: one in-channel, K out-channels. */
function block1xK(
  v: Float64Array,
  u: Float32Array,
  m: Float64Array,
  p0: number,
  q: number,
  k0: number,
  K: number,
  n: number,
): void {
  const T = WINOGRAD_TILES;
  for (let j = 0; j < K; j++) {
    const a = u[q + j]!;
    const k = k0 + j * T;
    for (let t = 0; t < n; t++) m[k + t] = m[k + t]! + v[p0 + t]! * a;
  }
}

/** Out-channel o of tiles t0 … t0 + n − 1: bias + Aᵀ M A, ReLU, into dst's interior. */
function outputTransform(
  s: WinogradScratch,
  o: number,
  cout: number,
  bias: number,
  dst: Planes,
  t0: number,
  n: number,
  tilesX: number,
): void {
  const { h, w, stride } = dst;
  const out = dst.data;
  const m = s.m;
  const tmp = s.t;
  const xiStride = pointStride(cout);
  const base = o * dst.plane + stride + 1;
  for (let k = 0; k < n; k++) {
    const t = t0 + k;
    const ty = (t / tilesX) | 0;
    const tx = t - ty * tilesX;
    const q = o * WINOGRAD_TILES + k;
    // Pass 1 (Aᵀ M), column by column: 6 rows of 8.
    for (let j = 0; j < 8; j++) {
      const p = q + j * xiStride;
      const m0 = m[p]!,
        m1 = m[p + 8 * xiStride]!,
        m2 = m[p + 16 * xiStride]!,
        m3 = m[p + 24 * xiStride]!,
        m4 = m[p + 32 * xiStride]!,
        m5 = m[p + 40 * xiStride]!,
        m6 = m[p + 48 * xiStride]!,
        m7 = m[p + 56 * xiStride]!;
      tmp[j] = m0 + m1 + m2 + m3 + m4 + m5 + m6;
      tmp[8 + j] = m1 - m2 + 0.5 * m3 - 0.5 * m4 + 2 * m5 - 2 * m6;
      tmp[16 + j] = m1 + m2 + 0.25 * m3 + 0.25 * m4 + 4 * m5 + 4 * m6;
      tmp[24 + j] = m1 - m2 + 0.125 * m3 - 0.125 * m4 + 8 * m5 - 8 * m6;
      tmp[32 + j] = m1 + m2 + 0.0625 * m3 + 0.0625 * m4 + 16 * m5 + 16 * m6;
      tmp[40 + j] = m1 - m2 + 0.03125 * m3 - 0.03125 * m4 + 32 * m5 - 32 * m6 + m7;
    }
    // Pass 2 (… A), row by row, with bias and ReLU.
    const y0 = ty * 6;
    const x0 = tx * 6;
    const rows = Math.min(6, h - y0);
    const cols = Math.min(6, w - x0);
    for (let r = 0; r < rows; r++) {
      const e0 = tmp[r * 8]!,
        e1 = tmp[r * 8 + 1]!,
        e2 = tmp[r * 8 + 2]!,
        e3 = tmp[r * 8 + 3]!,
        e4 = tmp[r * 8 + 4]!,
        e5 = tmp[r * 8 + 5]!,
        e6 = tmp[r * 8 + 6]!,
        e7 = tmp[r * 8 + 7]!;
      const d = base + (y0 + r) * stride + x0;
      const z0 = bias + (e0 + e1 + e2 + e3 + e4 + e5 + e6);
      const z1 = bias + (e1 - e2 + 0.5 * e3 - 0.5 * e4 + 2 * e5 - 2 * e6);
      const z2 = bias + (e1 + e2 + 0.25 * e3 + 0.25 * e4 + 4 * e5 + 4 * e6);
      const z3 = bias + (e1 - e2 + 0.125 * e3 - 0.125 * e4 + 8 * e5 - 8 * e6);
      const z4 = bias + (e1 + e2 + 0.0625 * e3 + 0.0625 * e4 + 16 * e5 + 16 * e6);
      const z5 = bias + (e1 - e2 + 0.03125 * e3 - 0.03125 * e4 + 32 * e5 - 32 * e6 + e7);
      if (cols === 6) {
        out[d] = relu(z0);
        out[d + 1] = relu(z1);
        out[d + 2] = relu(z2);
        out[d + 3] = relu(z3);
        out[d + 4] = relu(z4);
        out[d + 5] = relu(z5);
      } else {
        out[d] = relu(z0);
        if (cols > 1) out[d + 1] = relu(z1);
        if (cols > 2) out[d + 2] = relu(z2);
        if (cols > 3) out[d + 3] = relu(z3);
        if (cols > 4) out[d + 4] = relu(z4);
        if (cols > 5) out[d + 5] = relu(z5);
      }
    }
  }
}

/** max(z, 0), and 0 for NaN, as the direct convolution's ReLU (conv3x3.ts). */
function relu(z: number): number {
  return z > 0 ? z : 0;
}
