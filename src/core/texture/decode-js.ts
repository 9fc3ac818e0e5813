/**
 * Pure-JavaScript image decoding for Node (the CLI, the tests) and for any
 * context without createImageBitmap: PNG by fast-png (every colour type and
 * bit depth, interlaced or not), JPEG by jpeg-js (baseline and progressive).
 * Both are small, dependency-light and DOM-free, so the decode is the same
 * bytes-in, texels-out on every machine.
 */
import { convertIndexedToRgb, decode as decodePng } from 'fast-png';
import jpeg from 'jpeg-js';
import type { DecodedImage } from './decoded-image.ts';
import { readImageInfo } from './image-header.ts';
import { MAX_IMAGE_SIDE } from './texture-store.ts';

/** Unpacks 1-, 2- or 4-bit grey samples (rows padded to whole bytes) to one byte each, scaled to 0–255. */
function unpackLowDepth(
  data: Uint8Array,
  width: number,
  height: number,
  depth: number,
): Uint8Array {
  const out = new Uint8Array(width * height);
  const rowBytes = Math.ceil((width * depth) / 8);
  const max = (1 << depth) - 1;
  const scale = 255 / max;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const bit = x * depth;
      const byte = data[y * rowBytes + (bit >> 3)];
      const shift = 8 - depth - (bit & 7);
      out[y * width + x] = Math.round(((byte >> shift) & max) * scale);
    }
  }
  return out;
}

export function decodePngBytes(bytes: Uint8Array): DecodedImage {
  const png = decodePng(bytes);
  if (png.palette) {
    const data = convertIndexedToRgb(png);
    return {
      width: png.width,
      height: png.height,
      data,
      channels: png.palette[0].length,
      depth: 8,
    };
  }
  if (png.depth < 8) {
    const data = unpackLowDepth(png.data as Uint8Array, png.width, png.height, png.depth);
    return { width: png.width, height: png.height, data, channels: 1, depth: 8 };
  }
  return {
    width: png.width,
    height: png.height,
    data: png.data,
    channels: png.channels,
    depth: png.depth,
  };
}

export function decodeJpegBytes(bytes: Uint8Array): DecodedImage {
  const img = jpeg.decode(bytes, {
    useTArray: true,
    formatAsRGBA: false,
    // Bounds of jpeg-js itself, above what the texture limits allow anyway.
    maxResolutionInMP: (MAX_IMAGE_SIDE * MAX_IMAGE_SIDE) / 1e6,
    maxMemoryUsageInMB: 4096,
  });
  return { width: img.width, height: img.height, data: img.data, channels: 3, depth: 8 };
}

/**
 * The ImageDecoder of Node: the format is taken from the bytes (glTF's
 * mimeType is only a hint). The caller prefixes errors with the image's name.
 */
export async function decodeImageJs(bytes: Uint8Array, _mimeType = ''): Promise<DecodedImage> {
  const { mimeType } = readImageInfo(bytes);
  try {
    return mimeType === 'image/png' ? decodePngBytes(bytes) : decodeJpegBytes(bytes);
  } catch (e) {
    throw new Error(`cannot decode ${mimeType}: ${(e as Error).message}`);
  }
}
