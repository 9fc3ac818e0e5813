/**
 * Small builders of PNG and JPEG files, valid and hostile, written from the
 * specifications (PNG: chunks of length, type, data, CRC; zlib image data of filtered
 * scanlines; JPEG: marker segments) rather than from the project's readers, so that the
 * tests need no committed binaries. Used by tests/unit/core/image-*.test.ts and by the
 * PNG and JPEG entries of formats.ts.
 */
import { deflateSync } from 'node:zlib';
import jpeg from 'jpeg-js';
import { crc32 } from '../../src/core/io/crc32.ts';

const SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

export function concatBytes(...parts: ArrayLike<number>[]): Uint8Array {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
}

const u32 = (n: number) => [n >>> 24, (n >>> 16) & 255, (n >>> 8) & 255, n & 255];

/** One chunk: length, type, data, CRC over type and data (PNG §5.3). */
export function pngChunk(type: string, data: ArrayLike<number> = [], crc?: number): Uint8Array {
  const body = concatBytes(
    Array.from(type, (c) => c.charCodeAt(0)),
    data,
  );
  return concatBytes(u32(data.length), body, u32(crc ?? crc32(body)));
}

export function ihdr(width: number, height: number, depth = 8, colorType = 6, interlace = 0) {
  return pngChunk('IHDR', [...u32(width), ...u32(height), depth, colorType, 0, 0, interlace]);
}

export const IEND = pngChunk('IEND');

/** The signature followed by the given chunks. */
export function pngFile(...chunks: Uint8Array[]): Uint8Array {
  return concatBytes(SIGNATURE, ...chunks);
}

/** zlib (RFC 1950) of `raw`, as IDAT data. */
export function zlib(raw: ArrayLike<number>): Uint8Array {
  return new Uint8Array(deflateSync(Uint8Array.from(raw as ArrayLike<number>)));
}

/** Filtered scanlines (filter type 0) of an 8-bit image of `channels` samples per pixel. */
export function rawRows(
  width: number,
  height: number,
  channels: number,
  sample: (i: number) => number,
) {
  const rows: number[] = [];
  for (let y = 0; y < height; y++) {
    rows.push(0);
    for (let x = 0; x < width * channels; x++) rows.push(sample(y * width * channels + x) & 255);
  }
  return rows;
}

/** A valid non-interlaced 8-bit PNG; `channels` by colour type (0: 1, 2: 3, 4: 2, 6: 4). */
export function pngImage(width: number, height: number, colorType = 6): Uint8Array {
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[colorType as 0 | 2 | 4 | 6];
  const raw = rawRows(width, height, channels, (i) => i * 37 + 11);
  return pngFile(ihdr(width, height, 8, colorType), pngChunk('IDAT', zlib(raw)), IEND);
}

/** A palette image: 8-bit indices `index(x, y)` into `palette` (RGB triples). */
export function pngIndexed(
  width: number,
  height: number,
  palette: number[],
  index: (x: number, y: number) => number,
  extra: Uint8Array[] = [],
): Uint8Array {
  const raw = rawRows(width, height, 1, (i) => index(i % width, Math.floor(i / width)));
  return pngFile(
    ihdr(width, height, 8, 3),
    pngChunk('PLTE', palette),
    ...extra,
    pngChunk('IDAT', zlib(raw)),
    IEND,
  );
}

/** Adam7 passes (PNG §8.2): x start, y start, x step, y step. */
const ADAM7 = [
  [0, 0, 8, 8],
  [4, 0, 8, 8],
  [0, 4, 4, 8],
  [2, 0, 4, 4],
  [0, 2, 2, 4],
  [1, 0, 2, 2],
  [0, 1, 1, 2],
];

/** An interlaced 8-bit greyscale PNG of grey value `value(x, y)`, each pass filtered with type 0. */
export function pngInterlacedGrey(
  width: number,
  height: number,
  value: (x: number, y: number) => number,
) {
  const raw: number[] = [];
  for (const [xs, ys, dx, dy] of ADAM7) {
    if (width <= xs || height <= ys) continue; // an empty pass has no bytes
    for (let y = ys; y < height; y += dy) {
      raw.push(0);
      for (let x = xs; x < width; x += dx) raw.push(value(x, y) & 255);
    }
  }
  return pngFile(ihdr(width, height, 8, 0, 1), pngChunk('IDAT', zlib(raw)), IEND);
}

/** Offset of the first chunk of `type` in a PNG. */
export function chunkAt(png: Uint8Array, type: string): number {
  for (let at = 8; at + 8 <= png.length;) {
    const length = new DataView(png.buffer, png.byteOffset).getUint32(at);
    if (String.fromCharCode(...png.subarray(at + 4, at + 8)) === type) return at;
    at += 12 + length;
  }
  throw new Error(`no ${type} chunk`);
}

/** A baseline JPEG from jpeg-js's encoder (3 components, 4:4:4 sampling). */
export function jpegImage(width: number, height: number, quality = 90): Uint8Array {
  const rgba = new Uint8Array(width * height * 4);
  for (let i = 0; i < width * height; i++)
    rgba.set([(i * 7) & 255, (i * 3) & 255, 128, 255], 4 * i);
  return new Uint8Array(jpeg.encode({ width, height, data: rgba }, quality).data);
}

/** Offset of the first marker `FF marker` that starts a segment, walking the segments. */
export function markerAt(bytes: Uint8Array, marker: number): number {
  let p = 2;
  while (p + 4 <= bytes.length) {
    if (bytes[p + 1] === marker) return p;
    p += 2 + ((bytes[p + 2] << 8) | bytes[p + 3]);
  }
  throw new Error(`no FF${marker.toString(16)} segment`);
}

/** A copy with the frame header's size set to width × height. */
export function jpegWithSize(bytes: Uint8Array, width: number, height: number): Uint8Array {
  const out = bytes.slice();
  const sof = markerAt(out, 0xc0);
  out.set([height >> 8, height & 255, width >> 8, width & 255], sof + 5);
  return out;
}
