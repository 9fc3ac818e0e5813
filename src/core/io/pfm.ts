import { quote } from '../util/message.ts';
import { FormatError } from './format-error.ts';

/**
 * Portable Float Map, the standard layout: header "PF\n{w} {h}\n-1.0\n"
 * (negative scale = little-endian), then float32 RGB rows from the bottom
 * of the image to the top.
 */

/** Encodes an RGB float image (row 0 at the top) as PFM bytes. */
export function encodePfm(width: number, height: number, rgb: Float32Array): Uint8Array {
  if (rgb.length !== width * height * 3) {
    throw new RangeError(`PFM data has ${rgb.length} floats, expected ${width * height * 3}`);
  }
  // ASCII header; TextEncoder is not part of the core's ES2022 lib.
  const header = Uint8Array.from(`PF\n${width} ${height}\n-1.0\n`, (c) => c.charCodeAt(0));
  const out = new Uint8Array(header.length + rgb.length * 4);
  out.set(header, 0);
  const view = new DataView(out.buffer, header.length);
  let k = 0;
  for (let y = height - 1; y >= 0; y--) {
    for (let i = y * width * 3, end = i + width * 3; i < end; i++) {
      view.setFloat32(k, rgb[i], true);
      k += 4;
    }
  }
  return out;
}

export interface PfmImage {
  width: number;
  height: number;
  /** RGB, row 0 at the top. */
  rgb: Float32Array;
}

export interface PfmDecodeOptions {
  /** Largest width and height accepted (checked before anything is allocated). */
  maxWidth?: number;
  maxHeight?: number;
  /** Accept NaN and infinite values in the data (default: rejected, naming the pixel). */
  allowNonFinite?: boolean;
}

/** Default size limit: 65536 pixels a side. */
const MAX_SIDE = 65536;
/** A header is "PF", width, height and scale: a few dozen bytes, never more than this. */
const MAX_HEADER = 256;

/**
 * Decodes a colour PFM (either endianness) into top-to-bottom RGB floats. Every problem is
 * a FormatError naming it: not a PFM, a header that is malformed or claims too many
 * pixels, data shorter or longer than the header says, a non-finite value (by pixel).
 */
export function decodePfm(bytes: Uint8Array, options: PfmDecodeOptions = {}): PfmImage {
  const fail = (detail: string): never => {
    throw new FormatError('PFM', detail);
  };
  // The header is "PF" and three tokens, each ended by one whitespace byte (the last one
  // by exactly one, after which the data starts).
  let pos = 0;
  const tokens: string[] = [];
  while (tokens.length < 4) {
    while (pos < bytes.length && pos < MAX_HEADER && isSpace(bytes[pos])) pos++;
    const start = pos;
    while (pos < bytes.length && pos < MAX_HEADER && !isSpace(bytes[pos])) pos++;
    if (pos >= MAX_HEADER) fail(`the header is longer than ${MAX_HEADER} bytes`);
    if (pos >= bytes.length) {
      fail(`truncated: the file ends inside its header (${bytes.length} bytes)`);
    }
    tokens.push(String.fromCharCode(...bytes.subarray(start, pos)));
  }
  pos++; // the single whitespace byte that ends the header
  const [magic, ws, hs, ss] = tokens;
  if (magic === 'Pf') fail('grayscale PFM (Pf) is not supported; only colour (PF)');
  if (magic !== 'PF') fail(`not a colour PFM: it starts with ${quote(magic)}, not "PF"`);
  if (!/^[0-9]{1,12}$/.test(ws) || !/^[0-9]{1,12}$/.test(hs)) {
    fail(`width and height must be decimal integers, got ${quote(ws)} and ${quote(hs)}`);
  }
  const width = Number(ws);
  const height = Number(hs);
  const maxWidth = options.maxWidth ?? MAX_SIDE;
  const maxHeight = options.maxHeight ?? MAX_SIDE;
  if (width < 1 || height < 1 || width > maxWidth || height > maxHeight) {
    fail(`the image must be 1 x 1 to ${maxWidth} x ${maxHeight} pixels, got ${width} x ${height}`);
  }
  const scale = Number(ss);
  if (!/^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$/.test(ss) || !Number.isFinite(scale) || scale === 0) {
    fail(`the scale must be a non-zero number (its sign gives the byte order), got ${quote(ss)}`);
  }
  // A PFM has no compression: its data is exactly width · height · 3 channels · 4
  // bytes, so the size is checked against the file before anything is allocated.
  const need = width * height * 12;
  const have = bytes.length - pos;
  if (have < need) {
    fail(
      `truncated: the header says ${width} x ${height} pixels (${need} data bytes), the file has ${Math.max(0, have)}`,
    );
  }
  if (have > need) {
    fail(`${have - need} bytes after the ${width} x ${height} pixels the header announces`);
  }
  const little = scale < 0;
  const view = new DataView(bytes.buffer, bytes.byteOffset + pos, need);
  const rgb = new Float32Array(width * height * 3);
  let k = 0;
  for (let y = height - 1; y >= 0; y--) {
    for (let i = y * width * 3, end = i + width * 3; i < end; i++) {
      const v = view.getFloat32(k, little);
      if (!options.allowNonFinite && !Number.isFinite(v)) {
        const p = Math.floor(i / 3);
        fail(
          `pixel (${p % width}, ${Math.floor(p / width)}) ${'rgb'[i % 3]} is ${v} (values must be finite)`,
        );
      }
      rgb[i] = v;
      k += 4;
    }
  }
  return { width, height, rgb };
}

function isSpace(b: number): boolean {
  return b === 0x20 || b === 0x0a || b === 0x0d || b === 0x09;
}
