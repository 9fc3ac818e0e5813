/**
 * The U-Net's resolution changes (OIDN training/model.py: F.max_pool2d(x, 2, 2) and
 * F.interpolate(x, scale_factor=2, mode='nearest')): a 2×2 max pool with stride 2 on the
 * way down, nearest-neighbour doubling on the way up. Tiles are multiples of 16 pixels
 * (four halvings), so every size here is exact.
 */
import type { Planes } from './planes.ts';

/** dst (h/2 × w/2) ← 2×2 max of src, channel by channel; rows y0 … y1 − 1 of dst. */
export function maxPool2x2(src: Planes, dst: Planes, y0 = 0, y1 = dst.h): void {
  const { h, w } = dst;
  if (src.h !== 2 * h || src.w !== 2 * w)
    throw new RangeError('maxPool2x2: dst must be half of src');
  dst.c = src.c;
  const s = src.data;
  const d = dst.data;
  for (let ch = 0; ch < src.c; ch++) {
    for (let y = y0; y < y1; y++) {
      const i = ch * src.plane + (2 * y + 1) * src.stride + 1;
      const j = i + src.stride;
      const o = ch * dst.plane + (y + 1) * dst.stride + 1;
      for (let x = 0, k = 0; x < w; x++, k += 2) {
        const a = Math.max(s[i + k]!, s[i + k + 1]!);
        const b = Math.max(s[j + k]!, s[j + k + 1]!);
        d[o + x] = Math.max(a, b);
      }
    }
  }
}

/** dst (2h × 2w) ← src, each pixel repeated in a 2×2 block; rows y0 … y1 − 1 of src. */
export function upsample2x(src: Planes, dst: Planes, y0 = 0, y1 = src.h): void {
  const { h, w } = src;
  if (dst.h !== 2 * h || dst.w !== 2 * w) throw new RangeError('upsample2x: dst must be twice src');
  dst.c = src.c;
  const s = src.data;
  const d = dst.data;
  for (let ch = 0; ch < src.c; ch++) {
    for (let y = y0; y < y1; y++) {
      const i = ch * src.plane + (y + 1) * src.stride + 1;
      const o0 = ch * dst.plane + (2 * y + 1) * dst.stride + 1;
      const o1 = o0 + dst.stride;
      for (let x = 0; x < w; x++) {
        const v = s[i + x]!;
        d[o0 + 2 * x] = v;
        d[o0 + 2 * x + 1] = v;
        d[o1 + 2 * x] = v;
        d[o1 + 2 * x + 1] = v;
      }
    }
  }
}
