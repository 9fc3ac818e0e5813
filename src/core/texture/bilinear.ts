/**
 * Bilinear texture lookup with the wrap modes of glTF samplers (the OpenGL
 * ones: REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT). Texel centres sit at
 * ((i + ½)/W, (j + ½)/H), row 0 at v = 0 (the image's top, as in glTF).
 * Allocation-free: the result goes into a caller-owned record.
 */
import { TEXEL_MAX } from './srgb.ts';
import { I_HEIGHT, I_OFFSET, I_WIDTH, INFO_STRIDE, type TextureStore } from './texture-store.ts';

export const WRAP_REPEAT = 10497;
export const WRAP_CLAMP = 33071;
export const WRAP_MIRROR = 33648;

export class Texel {
  r = 0;
  g = 0;
  b = 0;
  a = 1;
}

/** Texel index i wrapped into [0, n). */
function wrap(i: number, n: number, mode: number): number {
  if (mode === WRAP_CLAMP) return i < 0 ? 0 : i >= n ? n - 1 : i;
  if (mode === WRAP_MIRROR) {
    const p = 2 * n;
    let k = i % p;
    if (k < 0) k += p;
    return k < n ? k : p - 1 - k;
  }
  let k = i % n;
  if (k < 0) k += n;
  return k;
}

const INV = 1 / TEXEL_MAX;

/**
 * A coordinate reduced to one period of its wrap mode (exact: it subtracts
 * an integer), or clamped: keeps texel indices small whatever the input.
 */
function reduce(u: number, mode: number): number {
  if (mode === WRAP_CLAMP) return u < -1 ? -1 : u > 2 ? 2 : u;
  if (mode === WRAP_MIRROR) return u - 2 * Math.floor(u / 2);
  return u - Math.floor(u);
}

/**
 * The bilinearly filtered texel of image `image` at (u, v), in [0, 1] per
 * channel. Non-finite coordinates read as 0.
 */
export function textureBilinear(
  store: TextureStore,
  image: number,
  u: number,
  v: number,
  wrapS: number,
  wrapT: number,
  out: Texel,
): void {
  const info = store.info;
  const o = image * INFO_STRIDE;
  const base = info[o + I_OFFSET];
  const w = info[o + I_WIDTH];
  const h = info[o + I_HEIGHT];
  if (!Number.isFinite(u)) u = 0;
  if (!Number.isFinite(v)) v = 0;
  u = reduce(u, wrapS);
  v = reduce(v, wrapT);
  const x = u * w - 0.5;
  const y = v * h - 0.5;
  const x0 = Math.floor(x);
  const y0 = Math.floor(y);
  const fx = x - x0;
  const fy = y - y0;
  const xa = wrap(x0, w, wrapS);
  const xb = wrap(x0 + 1, w, wrapS);
  const ya = wrap(y0, h, wrapT);
  const yb = wrap(y0 + 1, h, wrapT);
  const t = store.texels;
  const p00 = (base + ya * w + xa) * 4;
  const p10 = (base + ya * w + xb) * 4;
  const p01 = (base + yb * w + xa) * 4;
  const p11 = (base + yb * w + xb) * 4;
  const w00 = (1 - fx) * (1 - fy) * INV;
  const w10 = fx * (1 - fy) * INV;
  const w01 = (1 - fx) * fy * INV;
  const w11 = fx * fy * INV;
  out.r = t[p00] * w00 + t[p10] * w10 + t[p01] * w01 + t[p11] * w11;
  out.g = t[p00 + 1] * w00 + t[p10 + 1] * w10 + t[p01 + 1] * w01 + t[p11 + 1] * w11;
  out.b = t[p00 + 2] * w00 + t[p10 + 2] * w10 + t[p01 + 2] * w01 + t[p11 + 2] * w11;
  out.a = t[p00 + 3] * w00 + t[p10 + 3] * w10 + t[p01 + 3] * w01 + t[p11 + 3] * w11;
}
