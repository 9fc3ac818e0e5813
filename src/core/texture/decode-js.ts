/**
 * Pure-JavaScript image decoding for Node (the CLI, the tests) and for any
 * context without createImageBitmap: PNG by fast-png (every colour type and
 * bit depth, interlaced or not), JPEG by jpeg-js (baseline and progressive).
 * Both are small, dependency-light and DOM-free, so the decode is the same
 * bytes-in, texels-out on every machine. Neither bounds its work by the file
 * (fast-png inflates whatever the stream holds; jpeg-js allocates what the frame
 * header claims), so png-check.ts and jpeg-check.ts run first.
 */
import { convertIndexedToRgb, decode as decodePng } from 'fast-png';
import jpeg from 'jpeg-js';
import { FormatError } from '../util/format-error.ts';
import { DEFAULT_MAX_TEXELS, type DecodedImage } from './decoded-image.ts';
import { imageDecodeError, libraryMessage } from './image-error.ts';
import { notPngOrJpeg, sniffImageType } from './image-header.ts';
import { checkJpeg } from './jpeg-check.ts';
import { checkPng } from './png-check.ts';

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

/**
 * Decodes a PNG after png-check.ts has checked its chunks, its declared size against
 * the file and the budget, and its image data against a hard inflate limit. Throws
 * FormatError('PNG', …) naming what is wrong.
 */
export function decodePngBytes(bytes: Uint8Array, maxTexels = DEFAULT_MAX_TEXELS): DecodedImage {
  const checked = checkPng(bytes, maxTexels);
  // fast-png 8 de-interlaces Adam7 assuming whole bytes per pixel, so a valid interlaced
  // image of 1, 2 or 4 bits per sample fails inside it: say so, not "corrupt".
  if (checked.interlaced && checked.depth < 8) {
    throw new FormatError(
      'PNG',
      `interlaced (Adam7) images of ${checked.depth} bits per sample are not supported; save it non-interlaced or at 8 bits`,
    );
  }
  let png;
  try {
    png = decodePng(checked.clean);
  } catch (e) {
    throw new FormatError('PNG', `corrupt image data (${libraryMessage(e)})`);
  }
  if (png.palette) {
    let data;
    try {
      data = convertIndexedToRgb(png);
    } catch {
      // §11.2.2: a pixel whose index is past the palette's entries is an error.
      throw new FormatError(
        'PNG',
        `a pixel's palette index is past the ${checked.paletteSize} entries of PLTE`,
      );
    }
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

/**
 * Decodes a JPEG after jpeg-check.ts has checked its segments and its declared size
 * against the file and the budget. Throws FormatError('JPEG', …).
 */
export function decodeJpegBytes(bytes: Uint8Array, maxTexels = DEFAULT_MAX_TEXELS): DecodedImage {
  const frame = checkJpeg(bytes, maxTexels);
  let img;
  try {
    img = jpeg.decode(bytes, {
      useTArray: true,
      formatAsRGBA: false,
      // jpeg-js's own bounds, above the budget checked already.
      maxResolutionInMP: Math.ceil(maxTexels / 1e6),
      maxMemoryUsageInMB: 4096,
    });
  } catch (e) {
    throw new FormatError('JPEG', `corrupt JPEG data (${libraryMessage(e)})`);
  }
  if (img.width !== frame.width || img.height !== frame.height) {
    throw new FormatError(
      'JPEG',
      'corrupt JPEG data (the decoded size differs from the frame header)',
    );
  }
  return { width: img.width, height: img.height, data: img.data, channels: 3, depth: 8 };
}

/**
 * The ImageDecoder of Node: the format is taken from the bytes (glTF's
 * mimeType is only a hint). The caller prefixes errors with the image's name.
 */
export async function decodeImageJs(
  bytes: Uint8Array,
  mimeType = '',
  maxTexels = DEFAULT_MAX_TEXELS,
): Promise<DecodedImage> {
  const type = sniffImageType(bytes);
  if (type === null) throw new Error(notPngOrJpeg(bytes, mimeType));
  try {
    return type === 'image/png'
      ? decodePngBytes(bytes, maxTexels)
      : decodeJpegBytes(bytes, maxTexels);
  } catch (e) {
    throw imageDecodeError(e);
  }
}
