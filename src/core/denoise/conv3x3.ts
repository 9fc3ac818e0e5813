/**
 * The U-Net's only heavy operation: a 3×3 convolution, stride 1, zero padding 1, with
 * bias and ReLU (OIDN core/unet_filter.cpp: every conv is Activation::ReLU), over the
 * concatenation of one or two feature maps (OIDN's concat-conv: the decoder's "a" layers
 * read [upsampled, skip] without copying them into one tensor).
 *
 * Direct convolution over channel planes, register-blocked on four output channels and
 * one kernel row: for each output row the four output rows stay in L1 while every input
 * channel's three rows stream past once per block, and the inner loop keeps its twelve
 * weights and a sliding window of three inputs in registers (one load, four
 * read-modify-writes, twelve multiply-adds per pixel). The order of additions is fixed
 * (bias, then input channel by channel, kernel row by row), so a pixel's value depends
 * only on its inputs, never on the tile or thread that computes it.
 */
import type { ConvLayer } from './unet-weights.ts';
import type { Planes } from './planes.ts';

/** dst ← ReLU(conv3x3([a, b], layer)). a, b and dst have one size; b may be null. */
export function conv3x3Relu(a: Planes, b: Planes | null, layer: ConvLayer, dst: Planes): void {
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
  for (; oc + 4 <= cout; oc += 4) block4(a, b, layer, dst, oc);
  for (; oc < cout; oc++) single(a, b, layer, dst, oc);
}

function block4(a: Planes, b: Planes | null, layer: ConvLayer, dst: Planes, oc: number): void {
  const { h, w, stride, plane } = dst;
  const out = dst.data;
  const wt = layer.weight;
  const cin = layer.inChannels;
  const k0 = oc * cin * 9;
  const k1 = k0 + cin * 9;
  const k2 = k1 + cin * 9;
  const k3 = k2 + cin * 9;
  const b0 = layer.bias[oc]!;
  const b1 = layer.bias[oc + 1]!;
  const b2 = layer.bias[oc + 2]!;
  const b3 = layer.bias[oc + 3]!;
  for (let y = 0; y < h; y++) {
    const d0 = oc * plane + (y + 1) * stride + 1;
    const d1 = d0 + plane;
    const d2 = d1 + plane;
    const d3 = d2 + plane;
    out.fill(b0, d0, d0 + w);
    out.fill(b1, d1, d1 + w);
    out.fill(b2, d2, d2 + w);
    out.fill(b3, d3, d3 + w);
    for (let ic = 0; ic < cin; ic++) {
      const fromA = ic < a.c;
      const src = fromA ? a.data : b!.data;
      const base = (fromA ? ic : ic - a.c) * plane + y * stride;
      for (let ky = 0; ky < 3; ky++) {
        const r = base + ky * stride;
        const q = ic * 9 + ky * 3;
        const w00 = wt[k0 + q]!,
          w01 = wt[k0 + q + 1]!,
          w02 = wt[k0 + q + 2]!;
        const w10 = wt[k1 + q]!,
          w11 = wt[k1 + q + 1]!,
          w12 = wt[k1 + q + 2]!;
        const w20 = wt[k2 + q]!,
          w21 = wt[k2 + q + 1]!,
          w22 = wt[k2 + q + 2]!;
        const w30 = wt[k3 + q]!,
          w31 = wt[k3 + q + 1]!,
          w32 = wt[k3 + q + 2]!;
        let i0 = src[r]!;
        let i1 = src[r + 1]!;
        for (let x = 0; x < w; x++) {
          const i2 = src[r + x + 2]!;
          out[d0 + x] = out[d0 + x]! + (w00 * i0 + w01 * i1 + w02 * i2);
          out[d1 + x] = out[d1 + x]! + (w10 * i0 + w11 * i1 + w12 * i2);
          out[d2 + x] = out[d2 + x]! + (w20 * i0 + w21 * i1 + w22 * i2);
          out[d3 + x] = out[d3 + x]! + (w30 * i0 + w31 * i1 + w32 * i2);
          i0 = i1;
          i1 = i2;
        }
      }
    }
    relu(out, d0, w);
    relu(out, d1, w);
    relu(out, d2, w);
    relu(out, d3, w);
  }
}

function single(a: Planes, b: Planes | null, layer: ConvLayer, dst: Planes, oc: number): void {
  const { h, w, stride, plane } = dst;
  const out = dst.data;
  const wt = layer.weight;
  const cin = layer.inChannels;
  const k0 = oc * cin * 9;
  for (let y = 0; y < h; y++) {
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
