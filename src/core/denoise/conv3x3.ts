/**
 * The U-Net's heavy operation, computed directly: a 3×3 convolution, stride 1, zero padding 1, with
 * bias and ReLU (OIDN core/unet_filter.cpp: every conv is Activation::ReLU), over the
 * concatenation of one or two feature maps (OIDN's concat-conv: the decoder's "a" layers
 * read [upsampled, skip] without copying them into one tensor).
 *
 * Direct convolution over channel planes, blocked on four output channels and the whole
 * 3×3 kernel: for each output row the four output rows stay in L1 while every input
 * channel's three rows stream past once per block; the inner loop slides a 3×3 window
 * of inputs (three loads a pixel) over 36 weights and does one read-modify-write per
 * output and input channel, the nine products summed in double first. (Per kernel row,
 * as before, it was three read-modify-writes: 15 % slower on the small network.) The
 * order of additions is fixed (bias, then input channel by channel), so a pixel's value
 * depends only on its inputs, never on the tile or thread that computes it. The network
 * runs it for dec_conv0 (3 outputs) only; every other layer goes through winograd.ts,
 * whose tests take this one as their reference.
 */
import type { ConvLayer } from './unet-weights.ts';
import type { Planes } from './planes.ts';

/**
 * dst ← ReLU(conv3x3([a, b], layer)), rows y0 … y1 − 1 of dst. a, b and dst have one
 * size; b may be null.
 */
export function conv3x3Relu(
  a: Planes,
  b: Planes | null,
  layer: ConvLayer,
  dst: Planes,
  y0 = 0,
  y1 = dst.h,
): void {
  const cin = a.c + (b ? b.c : 0);
  if (cin !== layer.inChannels)
    throw new RangeError(`${layer.name}: ${cin} input channels, expected ${layer.inChannels}`);
  if (layer.outChannels > dst.capacity)
    throw new RangeError(`${layer.name}: output has room for ${dst.capacity} channels`);
  if (a.h !== dst.h || a.w !== dst.w || (b && (b.h !== dst.h || b.w !== dst.w)))
    throw new RangeError(`${layer.name}: inputs and output differ in size`);
  dst.c = layer.outChannels;
  const cout = layer.outChannels;
  let oc = 0;
  for (; oc + 4 <= cout; oc += 4) fused4(a, b, layer, dst, oc, y0, y1);
  for (; oc < cout; oc++) single(a, b, layer, dst, oc, y0, y1);
}

function single(
  a: Planes,
  b: Planes | null,
  layer: ConvLayer,
  dst: Planes,
  oc: number,
  y0: number,
  y1: number,
): void {
  const { w, stride, plane } = dst;
  const out = dst.data;
  const wt = layer.weight;
  const cin = layer.inChannels;
  const k0 = oc * cin * 9;
  for (let y = y0; y < y1; y++) {
    const d0 = oc * plane + (y + 1) * stride + 1;
    out.fill(layer.bias[oc]!, d0, d0 + w);
    for (let ic = 0; ic < cin; ic++) {
      const fromA = ic < a.c;
      const src = fromA ? a.data : b!.data;
      const base = (fromA ? ic : ic - a.c) * plane + y * stride;
      for (let ky = 0; ky < 3; ky++) {
        const r = base + ky * stride;
        const q = k0 + ic * 9 + ky * 3;
        const w00 = wt[q]!,
          w01 = wt[q + 1]!,
          w02 = wt[q + 2]!;
        let i0 = src[r]!;
        let i1 = src[r + 1]!;
        for (let x = 0; x < w; x++) {
          const i2 = src[r + x + 2]!;
          out[d0 + x] = out[d0 + x]! + (w00 * i0 + w01 * i1 + w02 * i2);
          i0 = i1;
          i1 = i2;
        }
      }
    }
    relu(out, d0, w);
  }
}

function relu(out: Float32Array, i: number, n: number): void {
  for (let e = i + n; i < e; i++) if (!(out[i]! > 0)) out[i] = 0;
}

function fused4(
  a: Planes,
  b: Planes | null,
  layer: ConvLayer,
  dst: Planes,
  oc: number,
  y0: number,
  y1: number,
): void {
  const { w, stride, plane } = dst;
  const out = dst.data;
  const wt = layer.weight;
  const cin = layer.inChannels;
  const k0 = oc * cin * 9;
  for (let y = y0; y < y1; y++) {
    const d0 = oc * plane + (y + 1) * stride + 1;
    const d1 = d0 + plane,
      d2 = d1 + plane,
      d3 = d2 + plane;
    out.fill(layer.bias[oc]!, d0, d0 + w);
    out.fill(layer.bias[oc + 1]!, d1, d1 + w);
    out.fill(layer.bias[oc + 2]!, d2, d2 + w);
    out.fill(layer.bias[oc + 3]!, d3, d3 + w);
    for (let ic = 0; ic < cin; ic++) {
      const fromA = ic < a.c;
      const src = fromA ? a.data : b!.data;
      const r0 = (fromA ? ic : ic - a.c) * plane + y * stride;
      const r1 = r0 + stride;
      const r2 = r1 + stride;
      const q0 = k0 + ic * 9,
        q1 = q0 + cin * 9,
        q2 = q1 + cin * 9,
        q3 = q2 + cin * 9;
      const p00 = wt[q0]!,
        p01 = wt[q0 + 1]!,
        p02 = wt[q0 + 2]!,
        p10 = wt[q0 + 3]!,
        p11 = wt[q0 + 4]!,
        p12 = wt[q0 + 5]!,
        p20 = wt[q0 + 6]!,
        p21 = wt[q0 + 7]!,
        p22 = wt[q0 + 8]!;
      const q00 = wt[q1]!,
        q01 = wt[q1 + 1]!,
        q02 = wt[q1 + 2]!,
        q10 = wt[q1 + 3]!,
        q11 = wt[q1 + 4]!,
        q12 = wt[q1 + 5]!,
        q20 = wt[q1 + 6]!,
        q21 = wt[q1 + 7]!,
        q22 = wt[q1 + 8]!;
      const s00 = wt[q2]!,
        s01 = wt[q2 + 1]!,
        s02 = wt[q2 + 2]!,
        s10 = wt[q2 + 3]!,
        s11 = wt[q2 + 4]!,
        s12 = wt[q2 + 5]!,
        s20 = wt[q2 + 6]!,
        s21 = wt[q2 + 7]!,
        s22 = wt[q2 + 8]!;
      const t00 = wt[q3]!,
        t01 = wt[q3 + 1]!,
        t02 = wt[q3 + 2]!,
        t10 = wt[q3 + 3]!,
        t11 = wt[q3 + 4]!,
        t12 = wt[q3 + 5]!,
        t20 = wt[q3 + 6]!,
        t21 = wt[q3 + 7]!,
        t22 = wt[q3 + 8]!;
      let a0 = src[r0]!,
        a1 = src[r0 + 1]!;
      let c0 = src[r1]!,
        c1 = src[r1 + 1]!;
      let e0 = src[r2]!,
        e1 = src[r2 + 1]!;
      for (let x = 0; x < w; x++) {
        const a2 = src[r0 + x + 2]!;
        const c2 = src[r1 + x + 2]!;
        const e2 = src[r2 + x + 2]!;
        out[d0 + x] =
          out[d0 + x]! +
          (p00 * a0 +
            p01 * a1 +
            p02 * a2 +
            (p10 * c0 + p11 * c1 + p12 * c2) +
            (p20 * e0 + p21 * e1 + p22 * e2));
        out[d1 + x] =
          out[d1 + x]! +
          (q00 * a0 +
            q01 * a1 +
            q02 * a2 +
            (q10 * c0 + q11 * c1 + q12 * c2) +
            (q20 * e0 + q21 * e1 + q22 * e2));
        out[d2 + x] =
          out[d2 + x]! +
          (s00 * a0 +
            s01 * a1 +
            s02 * a2 +
            (s10 * c0 + s11 * c1 + s12 * c2) +
            (s20 * e0 + s21 * e1 + s22 * e2));
        out[d3 + x] =
          out[d3 + x]! +
          (t00 * a0 +
            t01 * a1 +
            t02 * a2 +
            (t10 * c0 + t11 * c1 + t12 * c2) +
            (t20 * e0 + t21 * e1 + t22 * e2));
        a0 = a1;
        a1 = a2;
        c0 = c1;
        c1 = c2;
        e0 = e1;
        e1 = e2;
      }
    }
    relu(out, d0, w);
    relu(out, d1, w);
    relu(out, d2, w);
    relu(out, d3, w);
  }
}
