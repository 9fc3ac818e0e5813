/**
 * A decoded image as the decoders hand it over, and its one conversion into
 * a TextureStore slot: channels expanded to RGBA, colour channels of colour
 * textures converted from sRGB to linear, everything 16-bit.
 */
import { srgb16ToLinear16, srgb8ToLinear16Table, TEXEL_MAX } from './srgb.ts';
import {
  DEFAULT_TEXTURE_LIMIT_BYTES,
  I_HEIGHT,
  I_OFFSET,
  I_WIDTH,
  INFO_STRIDE,
  TEXEL_BYTES,
  type TextureStore,
} from './texture-store.ts';

/** Decoded-texel budget of one image by default: what the default texture memory limit holds. */
export const DEFAULT_MAX_TEXELS = DEFAULT_TEXTURE_LIMIT_BYTES / TEXEL_BYTES;

export interface DecodedImage {
  width: number;
  height: number;
  /** Interleaved samples, `channels` per texel, row 0 the top of the image. */
  data: Uint8Array | Uint8ClampedArray | Uint16Array;
  /** 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA. */
  channels: number;
  /** Bits per sample: 8 or 16. */
  depth: number;
}

/**
 * Decodes image bytes of the given MIME type (`image/png`, `image/jpeg`, …).
 * Node uses the pure-JS decoders of decode-js.ts; the browser may decode with
 * createImageBitmap instead. Rejects with a clear message on bad data
 * ("cannot decode PNG: …"), and before allocating anything when the image would
 * hold more than `maxTexels` texels (default DEFAULT_MAX_TEXELS) or more than its
 * bytes can encode.
 */
export type ImageDecoder = (
  bytes: Uint8Array,
  mimeType: string,
  maxTexels?: number,
) => Promise<DecodedImage>;

/**
 * Writes `img` into image slot `index` of `store`. `srgb` marks a colour
 * texture (base colour, emissive, specular colour): its RGB is sRGB-encoded
 * and converted to linear here, once; alpha and data textures are linear.
 */
export function writeDecodedImage(
  store: TextureStore,
  index: number,
  img: DecodedImage,
  srgb: boolean,
  what: string,
): void {
  const o = index * INFO_STRIDE;
  const width = store.info[o + I_WIDTH];
  const height = store.info[o + I_HEIGHT];
  if (img.width !== width || img.height !== height) {
    throw new Error(
      `${what}: decoded as ${img.width}×${img.height}, but its header said ${width}×${height}`,
    );
  }
  const c = img.channels;
  if (!(c >= 1 && c <= 4) || (img.depth !== 8 && img.depth !== 16)) {
    throw new Error(`${what}: unsupported image layout (${c} channels of ${img.depth} bits)`);
  }
  const n = width * height;
  if (img.data.length < n * c) {
    throw new Error(`${what}: decoder returned ${img.data.length} samples, expected ${n * c}`);
  }
  const data = img.data;
  const out = store.texels;
  let t = store.info[o + I_OFFSET] * 4;
  const lut = srgb8ToLinear16Table();
  const wide = img.depth === 16;
  // Scale of a linear sample to the 16-bit store (257 · 255 = 65535).
  const scale = wide ? 1 : 257;
  const color = (v: number): number => (srgb ? (wide ? srgb16ToLinear16(v) : lut[v]) : v * scale);
  const grey = c <= 2;
  const hasAlpha = c === 2 || c === 4;
  for (let i = 0, s = 0; i < n; i++, s += c, t += 4) {
    if (grey) {
      const v = color(data[s]);
      out[t] = v;
      out[t + 1] = v;
      out[t + 2] = v;
    } else {
      out[t] = color(data[s]);
      out[t + 1] = color(data[s + 1]);
      out[t + 2] = color(data[s + 2]);
    }
    out[t + 3] = hasAlpha ? data[s + c - 1] * scale : TEXEL_MAX;
  }
}
