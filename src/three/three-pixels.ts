/**
 * The texels of a three.js texture, as the page holds them: typed-array data
 * (DataTexture, HDRLoader/RGBELoader output, ImageData) read directly, or an image,
 * bitmap or canvas drawn on an OffscreenCanvas. Rows come out in glTF's order (row 0 is
 * where v = 0): three uploads row 0 at v = 0 unless `flipY` is set, so a flipped texture
 * is read bottom-up.
 */
import { halfToFloat } from '../core/math/half.ts';
import type { ThreeTexture } from './three-shapes.ts';

/** three's constants (src/constants.js), stable since r1xx. */
export const FLOAT_TYPE = 1015;
export const HALF_FLOAT_TYPE = 1016;
const RED_FORMAT = 1028;
const RG_FORMAT = 1030;

export interface Texels {
  width: number;
  height: number;
  /** 4 channels per texel, row 0 at v = 0; 0–255 for 8-bit sources, linear values for float ones. */
  rgba: Float32Array | Uint8ClampedArray;
  float: boolean;
}

/** Reads `tex`'s texels; throws an Error saying why when they cannot be read here. */
export function readTexels(tex: ThreeTexture): Texels {
  const image = tex.image as Record<string, unknown> | null;
  if (image === null || typeof image !== 'object') throw new Error('it has no image');
  const width = image.width as number;
  const height = image.height as number;
  if (!(width > 0 && height > 0)) throw new Error('its image has no size (not loaded yet?)');
  const data = image.data as ArrayLike<number> | undefined;
  let texels: Texels;
  if (data !== undefined && typeof data === 'object' && 'length' in data) {
    texels = fromData(tex, data, width, height);
  } else {
    texels = fromDrawable(image, width, height);
  }
  if (tex.flipY) flipRows(texels);
  return texels;
}

function fromData(
  tex: ThreeTexture,
  data: ArrayLike<number>,
  width: number,
  height: number,
): Texels {
  const n = width * height;
  const channels =
    tex.format === RED_FORMAT ? 1 : tex.format === RG_FORMAT ? 2 : Math.round(data.length / n);
  if (![1, 2, 3, 4].includes(channels) || data.length < n * channels) {
    throw new Error(`its data holds ${data.length} values for ${width}×${height} texels`);
  }
  const half = tex.type === HALF_FLOAT_TYPE || data instanceof Uint16Array;
  const float = half || data instanceof Float32Array || tex.type === FLOAT_TYPE;
  const rgba = float ? new Float32Array(n * 4) : new Uint8ClampedArray(n * 4);
  for (let i = 0; i < n; i++) {
    for (let c = 0; c < 4; c++) {
      let v: number;
      if (c < channels) v = data[i * channels + c];
      else if (c === 3) v = float ? 1 : 255;
      else v = data[i * channels + (channels === 1 ? 0 : channels - 1)]; // grey from one channel
      rgba[i * 4 + c] = half ? halfToFloat(v) : v;
    }
  }
  return { width, height, rgba, float };
}

function fromDrawable(image: Record<string, unknown>, width: number, height: number): Texels {
  const Canvas = (globalThis as { OffscreenCanvas?: typeof OffscreenCanvas }).OffscreenCanvas;
  if (Canvas === undefined) throw new Error('its image cannot be read without OffscreenCanvas');
  const ctx = new Canvas(width, height).getContext('2d', { willReadFrequently: true });
  if (ctx === null) throw new Error('no 2D canvas to read its image');
  ctx.drawImage(image as unknown as CanvasImageSource, 0, 0, width, height);
  // Canvas storage is premultiplied: texels with alpha < 1 lose some precision here.
  const rgba = ctx.getImageData(0, 0, width, height).data;
  return { width, height, rgba, float: false };
}

function flipRows(t: Texels): void {
  const row = t.width * 4;
  const tmp = t.rgba.slice(0, row);
  for (let y = 0; y < t.height >> 1; y++) {
    const a = y * row;
    const b = (t.height - 1 - y) * row;
    tmp.set(t.rgba.subarray(a, a + row));
    t.rgba.copyWithin(a, b, b + row);
    t.rgba.set(tmp, b);
  }
}
