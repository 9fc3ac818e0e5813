/**
 * A PNG encoder written from the PNG specification (W3C / ISO 15948, 2nd edition):
 * chunks (§5.3, CRC over type and data), IHDR (§11.2.2), PLTE and tRNS, scanlines with a
 * filter byte each and the five filters (§9), Adam7 passes (§8.2), all colour types and bit
 * depths. Deflate is zlib's own (node:zlib), not the project's inflater.
 */
import { deflateSync } from 'node:zlib';
import { ByteWriter, ascii, concat, crc32 } from './bytes.ts';
import type { Rng } from './rng.ts';

export const SIGNATURE = new Uint8Array([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);

/** Allowed bit depths per colour type (§11.2.2, table 11.1). */
export const DEPTHS: Record<number, number[]> = {
  0: [1, 2, 4, 8, 16],
  2: [8, 16],
  3: [1, 2, 4, 8],
  4: [8, 16],
  6: [8, 16],
};
const CHANNELS: Record<number, number> = { 0: 1, 2: 3, 3: 1, 4: 2, 6: 4 };

export interface Chunk {
  type: string;
  data: Uint8Array;
  /** A CRC to write instead of the right one. */
  crc?: number;
  /** A length to write instead of the data's. */
  length?: number;
}

export interface PngImage {
  width: number;
  height: number;
  depth: number;
  colourType: number;
  interlace: 0 | 1;
  /** Samples, row-major, CHANNELS per pixel, each in [0, 2^depth). */
  samples: number[];
  palette?: number[][];
}

export function ihdr(
  w: number,
  h: number,
  depth: number,
  ct: number,
  interlace: number,
  method = [0, 0],
): Chunk {
  const b = new ByteWriter()
    .u32(w, false)
    .u32(h, false)
    .u8(depth)
    .u8(ct)
    .u8(method[0])
    .u8(method[1])
    .u8(interlace);
  return { type: 'IHDR', data: b.done() };
}

export function serializeChunks(chunks: readonly Chunk[]): Uint8Array {
  const w = new ByteWriter().bytes(SIGNATURE);
  for (const c of chunks) {
    const body = concat([ascii(c.type), c.data]);
    w.u32(c.length ?? c.data.length, false)
      .bytes(body)
      .u32(c.crc ?? crc32(body), false);
  }
  return w.done();
}

/** §9.4: the Paeth predictor. */
function paeth(a: number, b: number, c: number): number {
  const p = a + b - c;
  const pa = Math.abs(p - a);
  const pb = Math.abs(p - b);
  const pc = Math.abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/** The packed bytes of one row of samples (§7.2: MSB first, 16-bit big-endian). */
function packRow(samples: number[], depth: number): Uint8Array {
  const bits = samples.length * depth;
  const out = new Uint8Array(Math.ceil(bits / 8));
  samples.forEach((s, i) => {
    if (depth === 16) {
      out[i * 2] = s >> 8;
      out[i * 2 + 1] = s & 0xff;
    } else if (depth === 8) out[i] = s;
    else {
      const bit = i * depth;
      out[bit >> 3] |= s << (8 - depth - (bit & 7));
    }
  });
  return out;
}

/** Filtered scanlines of one (sub)image, filter types chosen by `rng` (§9.2). */
function filterRows(rows: Uint8Array[], bpp: number, rng: Rng, filters?: number[]): Uint8Array {
  const w = new ByteWriter();
  let prior: Uint8Array = new Uint8Array(rows[0]?.length ?? 0);
  for (const row of rows) {
    const type = filters ? filters[rng.int(filters.length)] : rng.int(5);
    w.u8(type);
    for (let i = 0; i < row.length; i++) {
      const a = i >= bpp ? row[i - bpp] : 0;
      const b = prior[i];
      const c = i >= bpp ? prior[i - bpp] : 0;
      const pred = [0, a, b, (a + b) >> 1, paeth(a, b, c)][type];
      w.u8((row[i] - pred) & 0xff);
    }
    prior = row;
  }
  return w.done();
}

const ADAM7 = [
  [0, 0, 8, 8],
  [4, 0, 8, 8],
  [0, 4, 4, 8],
  [2, 0, 4, 4],
  [0, 2, 2, 4],
  [1, 0, 2, 2],
  [0, 1, 1, 2],
];

/** The uncompressed image data (filter bytes included), for either interlace method. */
export function rawData(img: PngImage, rng: Rng): Uint8Array {
  const ch = CHANNELS[img.colourType];
  const bpp = Math.max(1, (ch * img.depth) >> 3);
  const rowOf = (y: number, xs: number[]) =>
    packRow(
      xs.flatMap((x) => img.samples.slice((y * img.width + x) * ch, (y * img.width + x + 1) * ch)),
      img.depth,
    );
  const passes = img.interlace ? ADAM7 : [[0, 0, 1, 1]];
  const parts: Uint8Array[] = [];
  for (const [x0, y0, dx, dy] of passes) {
    const xs: number[] = [];
    for (let x = x0; x < img.width; x += dx) xs.push(x);
    const rows: Uint8Array[] = [];
    for (let y = y0; y < img.height && xs.length > 0; y += dy) rows.push(rowOf(y, xs));
    // §8.2: a pass with no pixels contributes nothing, not even filter bytes.
    if (rows.length > 0) parts.push(filterRows(rows, bpp, rng));
  }
  return concat(parts);
}

export function randomImage(rng: Rng): PngImage {
  const colourType = rng.pick([0, 2, 3, 4, 6]);
  const depth = rng.pick(DEPTHS[colourType]);
  const width = rng.range(1, 19);
  const height = rng.range(1, 19);
  const ch = CHANNELS[colourType];
  const max = 2 ** depth - 1;
  const paletteSize = colourType === 3 ? rng.range(1, Math.min(256, max + 1)) : 0;
  const samples: number[] = [];
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      for (let c = 0; c < ch; c++) {
        samples.push(
          colourType === 3
            ? (x + y) % paletteSize
            : Math.round((((x * 3 + y * 5 + c * 7) % 17) / 16) * max),
        );
      }
    }
  }
  const palette =
    colourType === 3 || (colourType === 2 && rng.chance(0.3))
      ? Array.from({ length: Math.max(paletteSize, 1) }, (_, i) => [
          (i * 37) & 255,
          (i * 91) & 255,
          (i * 13) & 255,
        ])
      : undefined;
  return { width, height, depth, colourType, interlace: rng.chance(0.4) ? 1 : 0, samples, palette };
}

/** A valid file's chunks: IHDR, maybe gAMA/tEXt, PLTE, tRNS, IDAT split at random, IEND. */
export function pngChunks(img: PngImage, rng: Rng): Chunk[] {
  const chunks: Chunk[] = [ihdr(img.width, img.height, img.depth, img.colourType, img.interlace)];
  if (rng.chance(0.3))
    chunks.push({ type: 'gAMA', data: new ByteWriter().u32(45455, false).done() });
  if (rng.chance(0.3)) chunks.push({ type: 'tEXt', data: ascii('Comment\0spec-fuzz') });
  if (img.palette) chunks.push({ type: 'PLTE', data: new Uint8Array(img.palette.flat()) });
  if (img.colourType === 3 && rng.chance(0.4))
    chunks.push({ type: 'tRNS', data: new Uint8Array([128]) });
  if (img.colourType === 0 && rng.chance(0.3))
    chunks.push({ type: 'tRNS', data: new Uint8Array([0, 0]) });
  const z = deflateSync(rawData(img, rng), { level: rng.pick([0, 1, 6, 9]) });
  const cuts = [
    0,
    ...Array.from({ length: rng.int(3) }, () => rng.int(z.length)).sort((a, b) => a - b),
    z.length,
  ];
  for (let i = 0; i + 1 < cuts.length; i++) {
    if (cuts[i + 1] > cuts[i] || i === 0)
      chunks.push({ type: 'IDAT', data: z.subarray(cuts[i], cuts[i + 1]) });
  }
  chunks.push({ type: 'IEND', data: new Uint8Array(0) });
  return chunks;
}
