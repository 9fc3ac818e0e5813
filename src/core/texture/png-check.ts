/**
 * Checks a PNG against the specification (W3C PNG, 3rd edition; section numbers below)
 * before any texel is allocated, and hands the decoder a stream it can trust:
 *
 * - the chunk layout (§5.3: length, type, data, CRC; lengths below 2^31, inside the
 *   file; the CRC of every critical chunk, as libpng checks it, so that Node and the
 *   browser agree on a damaged file) and the ordering rules of §5.6: IHDR first, at
 *   most one PLTE and before the image data, IDAT chunks consecutive, IEND last;
 * - IHDR's fields (§11.2.1: colour type and bit depth pairs, methods 0, interlace 0/1);
 * - PLTE (§11.2.2): required for colour type 3 with 1 … 2^depth entries, forbidden for
 *   the grey types; tRNS (§11.3.1.1) sized for its colour type;
 * - the declared size against the bytes present and against a texel budget: deflate
 *   cannot expand more than about 1032:1 (RFC 1951: a length-258 match costs at least
 *   2 bits, so 258 bytes per 2 bits), so image data that needs more than 1032 times its
 *   compressed size plus a little cannot be in the file;
 * - the inflated image data (zlib, RFC 1950) with a hard limit: it must be exactly
 *   the size IHDR implies (§7.2 scanline filter bytes, §8.2 Adam7 passes), and every
 *   scanline's filter type must be 0–4 (§7.3). A stream that inflates past that size is
 *   stopped as soon as it does, so a 4×4 image whose data inflates to 1 GiB costs the
 *   time of a few MB of inflate and no memory beyond a few of its slices.
 *
 * Why check and then let fast-png decode, rather than defilter here: fast-png's
 * defiltering, Adam7 and sample unpacking are tested code; what it lacks is bounds.
 * The second inflate (fast-png's) runs on a stream already proven to hold exactly the
 * needed bytes, so it is bounded by the header, which is bounded by the file.
 */
import { crc32 } from '../util/crc32.ts';
import { FormatError } from '../util/format-error.ts';
import { sanitize } from '../util/message.ts';
import { DEFLATE_MAX_RATIO, inflateChecked, pngDataSize, type PngHeader } from './png-data.ts';

export type { PngHeader } from './png-data.ts';

export interface CheckedPng extends PngHeader {
  /** A minimal PNG of the same image: IHDR, PLTE and tRNS where they apply, one IDAT, IEND. */
  clean: Uint8Array;
  /** Entries of PLTE (0 when absent or ignored). */
  paletteSize: number;
}

const SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

/** Samples per pixel and allowed bit depths by colour type (§11.2.1, Table 11.1). */
const COLOUR_TYPES: Record<number, { channels: number; depths: number[]; name: string }> = {
  0: { channels: 1, depths: [1, 2, 4, 8, 16], name: 'greyscale' },
  2: { channels: 3, depths: [8, 16], name: 'truecolour' },
  3: { channels: 1, depths: [1, 2, 4, 8], name: 'indexed-colour' },
  4: { channels: 2, depths: [8, 16], name: 'greyscale with alpha' },
  6: { channels: 4, depths: [8, 16], name: 'truecolour with alpha' },
};

function fail(detail: string): never {
  throw new FormatError('PNG', detail);
}

function chunkType(bytes: Uint8Array, at: number): string {
  return String.fromCharCode(bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]);
}

function readUint32(bytes: Uint8Array, at: number): number {
  return ((bytes[at] << 24) | (bytes[at + 1] << 16) | (bytes[at + 2] << 8) | bytes[at + 3]) >>> 0;
}

function writeChunk(out: number[], type: string, data: ArrayLike<number>): void {
  const body = new Uint8Array(4 + data.length);
  for (let i = 0; i < 4; i++) body[i] = type.charCodeAt(i);
  body.set(data as ArrayLike<number>, 4);
  const crc = crc32(body);
  const n = data.length;
  out.push(n >>> 24, (n >>> 16) & 255, (n >>> 8) & 255, n & 255);
  for (const b of body) out.push(b);
  out.push(crc >>> 24, (crc >>> 16) & 255, (crc >>> 8) & 255, crc & 255);
}

/** The type of a chunk as printed in a message (its bytes may be anything). */
function shownType(type: string): string {
  return `"${sanitize(type, 16, true)}"`;
}

/** A PNG's chunks as read and checked, before its image data is inflated. */
export interface PngChunks {
  header: PngHeader;
  palette: Uint8Array | null;
  trns: Uint8Array | null;
  idat: Uint8Array[];
  idatBytes: number;
}

/**
 * Checks `bytes` (a PNG) and returns its header and a clean copy for the decoder, or
 * throws FormatError('PNG', …) naming what is wrong and where. `maxTexels` is the
 * decoded-texel budget.
 */
export function checkPng(bytes: Uint8Array, maxTexels: number): CheckedPng {
  const { header, palette, trns, idat, idatBytes } = readPngChunks(bytes, maxTexels);
  inflateChecked(idat, idatBytes, header);
  return {
    ...header,
    clean: rebuild(header, palette, trns, idat, idatBytes),
    paletteSize: palette ? palette.length / 3 : 0,
  };
}

/**
 * The chunk checks alone (everything but the inflate): cheap, linear in the file's
 * chunk count, for a first pass over every image before any memory is committed.
 */
export function readPngChunks(bytes: Uint8Array, maxTexels: number): PngChunks {
  if (bytes.length < 8 || SIGNATURE.some((b, i) => bytes[i] !== b)) {
    fail('not a PNG file (its first 8 bytes are not the PNG signature)');
  }
  let header: PngHeader | null = null;
  let palette: Uint8Array | null = null;
  let trns: Uint8Array | null = null;
  const idat: Uint8Array[] = [];
  let idatBytes = 0;
  let idatEnded = false;
  let ended = false;
  let at = 8;
  while (!ended) {
    if (at + 12 > bytes.length) {
      fail(
        at === 8
          ? 'the file ends before its IHDR chunk'
          : `the file ends at byte ${bytes.length} without an IEND chunk (truncated?)`,
      );
    }
    const length = readUint32(bytes, at);
    const type = chunkType(bytes, at + 4);
    const where = `chunk ${shownType(type)} at byte ${at}`;
    // §5.3: a chunk length is at most 2^31 − 1.
    if (length > 0x7fffffff || at + 12 + length > bytes.length) {
      fail(`${where}: its length ${length} runs past the end of the file (${bytes.length} bytes)`);
    }
    // §5.3: a chunk type is four ASCII letters; anything else is a damaged file.
    for (let k = at + 4; k < at + 8; k++) {
      const c = bytes[k] | 0x20;
      if (c < 0x61 || c > 0x7a) fail(`${where}: a chunk type must be four ASCII letters (§5.3)`);
    }
    const data = bytes.subarray(at + 8, at + 8 + length);
    const critical = (bytes[at + 4] & 0x20) === 0;
    if (
      critical &&
      readUint32(bytes, at + 8 + length) !== crc32(bytes.subarray(at + 4, at + 8 + length))
    ) {
      fail(`${where}: its CRC does not match its data (the file is damaged)`);
    }
    if (header === null && type !== 'IHDR') fail(`${where}: the first chunk must be IHDR`);
    if (idat.length > 0 && type !== 'IDAT') idatEnded = true;
    switch (type) {
      case 'IHDR':
        if (header !== null) fail(`${where}: a second IHDR`);
        header = readIhdr(data, where, bytes.length, maxTexels);
        break;
      case 'PLTE':
        if (palette !== null) fail(`${where}: a second PLTE`);
        if (idat.length > 0) fail(`${where}: PLTE must come before the image data (IDAT)`);
        palette = checkPalette(header!, data, where);
        break;
      case 'tRNS':
        if (idat.length > 0) fail(`${where}: tRNS must come before the image data (IDAT)`);
        trns = checkTransparency(header!, palette, data, where);
        break;
      case 'IDAT':
        if (idatEnded) fail(`${where}: IDAT chunks must be consecutive (§5.6)`);
        idat.push(data);
        idatBytes += length;
        break;
      case 'IEND':
        ended = true;
        break;
      default:
        // §5.4: a decoder that meets a critical chunk it does not know cannot safely
        // interpret the image; ancillary chunks (APNG's too) are skipped.
        if (critical) fail(`${where}: an unknown critical chunk`);
    }
    at += 12 + length;
  }
  const h = header!;
  if (h.colorType === 3 && palette === null) {
    fail(
      'colour type 3 (indexed-colour) needs a PLTE chunk before the image data, and there is none',
    );
  }
  if (idat.length === 0) fail('no image data (no IDAT chunk)');
  const need = pngDataSize(h);
  // Lower bound of the compressed size: zlib's 2-byte header, 4-byte check value, and
  // at most 1032 inflated bytes per deflate byte (a few more for block headers).
  const most = Math.max(0, idatBytes - 6) * DEFLATE_MAX_RATIO + 1024;
  if (need > most) {
    fail(
      `the header claims ${h.width}×${h.height} (${need} bytes of image data) but the file ` +
        `has only ${idatBytes} bytes of IDAT (at least ${Math.ceil((need - 1024) / DEFLATE_MAX_RATIO) + 6} needed)`,
    );
  }
  return { header: h, palette, trns, idat, idatBytes };
}

function readIhdr(
  data: Uint8Array,
  where: string,
  fileBytes: number,
  maxTexels: number,
): PngHeader {
  if (data.length !== 13) fail(`${where}: IHDR must be 13 bytes, not ${data.length}`);
  const width = readUint32(data, 0);
  const height = readUint32(data, 4);
  const [depth, colorType, compression, filter, interlace] = data.subarray(8, 13);
  if (width < 1 || height < 1 || width > 0x7fffffff || height > 0x7fffffff) {
    fail(`${where}: the image size ${width}×${height} is not 1 … 2^31−1 a side`);
  }
  const ct = COLOUR_TYPES[colorType];
  if (ct === undefined) fail(`${where}: colour type ${colorType} is not one of 0, 2, 3, 4, 6`);
  if (!ct.depths.includes(depth)) {
    fail(
      `${where}: bit depth ${depth} is not allowed for colour type ${colorType} (${ct.name}; allowed: ${ct.depths.join(', ')})`,
    );
  }
  if (compression !== 0) fail(`${where}: compression method ${compression} is not 0 (deflate)`);
  if (filter !== 0) fail(`${where}: filter method ${filter} is not 0`);
  if (interlace > 1) fail(`${where}: interlace method ${interlace} is not 0 or 1`);
  if (width * height > maxTexels) {
    fail(
      `the header claims ${width}×${height} texels, over the budget of ${maxTexels} decoded ` +
        `texels (the file has ${fileBytes} bytes)`,
    );
  }
  return { width, height, depth, colorType, interlaced: interlace === 1 };
}

function checkPalette(h: PngHeader, data: Uint8Array, where: string): Uint8Array | null {
  const entries = data.length / 3;
  if (data.length === 0 || data.length % 3 !== 0 || entries > 256) {
    fail(
      `${where}: PLTE must hold 1 to 256 RGB entries (a multiple of 3 bytes), got ${data.length} bytes`,
    );
  }
  if (h.colorType === 0 || h.colorType === 4) {
    fail(`${where}: PLTE must not appear in a greyscale image (colour type ${h.colorType})`);
  }
  if (h.colorType === 3 && entries > 2 ** h.depth) {
    fail(`${where}: PLTE has ${entries} entries, more than bit depth ${h.depth} can index`);
  }
  // For truecolour a PLTE is only a suggested palette for limited displays: not used.
  return h.colorType === 3 ? data : null;
}

function checkTransparency(
  h: PngHeader,
  palette: Uint8Array | null,
  data: Uint8Array,
  where: string,
): Uint8Array | null {
  if (h.colorType === 3) {
    if (palette === null) fail(`${where}: tRNS of an indexed-colour image must follow PLTE`);
    if (data.length > palette.length / 3) {
      fail(
        `${where}: tRNS has ${data.length} alpha values for ${palette.length / 3} palette entries`,
      );
    }
    return data;
  }
  const want = h.colorType === 0 ? 2 : h.colorType === 2 ? 6 : 0;
  if (want === 0) return null; // §11.3.1.1: not for types with alpha; ignored, as libpng does.
  if (data.length !== want)
    fail(`${where}: tRNS must be ${want} bytes for colour type ${h.colorType}, not ${data.length}`);
  return data;
}

function rebuild(
  h: PngHeader,
  palette: Uint8Array | null,
  trns: Uint8Array | null,
  idat: Uint8Array[],
  idatBytes: number,
): Uint8Array {
  const head: number[] = [...SIGNATURE];
  const ihdr = [
    h.width >>> 24,
    (h.width >>> 16) & 255,
    (h.width >>> 8) & 255,
    h.width & 255,
    h.height >>> 24,
    (h.height >>> 16) & 255,
    (h.height >>> 8) & 255,
    h.height & 255,
    h.depth,
    h.colorType,
    0,
    0,
    h.interlaced ? 1 : 0,
  ];
  writeChunk(head, 'IHDR', ihdr);
  if (palette) writeChunk(head, 'PLTE', palette);
  if (trns) writeChunk(head, 'tRNS', trns);
  const out = new Uint8Array(head.length + 12 + idatBytes + 12);
  out.set(head, 0);
  let at = head.length;
  // One IDAT chunk; fast-png does not check CRCs, so this one is left 0 rather than
  // computed over the whole image data again.
  out.set(
    [
      idatBytes >>> 24,
      (idatBytes >>> 16) & 255,
      (idatBytes >>> 8) & 255,
      idatBytes & 255,
      0x49,
      0x44,
      0x41,
      0x54,
    ],
    at,
  );
  at += 8;
  for (const d of idat) {
    out.set(d, at);
    at += d.length;
  }
  at += 4;
  out.set([0, 0, 0, 0, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82], at);
  return out;
}
