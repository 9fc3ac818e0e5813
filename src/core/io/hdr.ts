/**
 * Radiance `.hdr` (RGBE) images (Ward, "Real Pixels", Graphics Gems II, 1991; the
 * format of Radiance's `color.c`): a text header ending in an empty line, a resolution
 * line, then scanlines either flat (4 bytes per texel) or run-length encoded per channel
 * ("new" RLE: 2, 2, width high, width low, then each of r, g, b, e as runs and dumps).
 * As the scene format fixes, a texel (r, g, b, e) decodes to (r, g, b)·2^(e − 136), and
 * to 0 when e = 0; EXPOSURE and other header variables are ignored. Like Mitsuba's
 * reader, a flat texel (1, 1, 1, e) is a colour, not the old-style "repeat" code.
 *
 * Orientation: the standard `-Y H +X W` (rows top to bottom, columns left to right)
 * and the flipped variants `+Y` / `-X` are read; transposed layouts are rejected.
 */
import { FormatError } from './format-error.ts';
import { bytesToString, lineEnd, skipBlanks, tokenEnd } from './text-bytes.ts';

export interface ImageLimits {
  maxWidth: number;
  maxHeight: number;
}

export interface RgbImage {
  width: number;
  height: number;
  /** Linear RGB, row 0 at the top. */
  rgb: Float32Array;
}

/** 2^(e − 136) for e = 1 … 255, 0 for e = 0. */
const EXPONENT = Float64Array.from({ length: 256 }, (_, e) => (e === 0 ? 0 : 2 ** (e - 136)));

const MAX_HEADER = 1 << 16;

export function decodeHdr(bytes: Uint8Array, limits: ImageLimits): RgbImage {
  const { width, height, flipY, flipX, data } = readHeader(bytes, limits);
  // Cheapest possible encoding of a scanline: RLE runs of 127 for each channel (plus
  // its 4-byte marker), or flat texels where RLE is not allowed. A header that claims
  // more than the file can hold is rejected before the image is allocated. Old-style
  // RLE (a texel (1, 1, 1, n) repeating the previous one, Radiance's color.c), which
  // could encode more texels than bytes without this bound, is not read (see above),
  // so the bound is exact for every file this reader accepts; the texel budget is
  // `limits` (the scene format's environment-map size limit).
  const rle = width >= 8 && width <= 0x7fff;
  const minScanline = rle ? 4 + 4 * 2 * Math.ceil(width / 127) : 4 * width;
  const available = bytes.length - data;
  if (available < minScanline * height) {
    throw new FormatError(
      'HDR',
      `the header declares ${width} × ${height} texels, which need at least ` +
        `${minScanline * height} bytes, but only ${available} follow it`,
    );
  }
  const rgb = new Float32Array(width * height * 3);
  const line = new Uint8Array(width * 4);
  let pos = data;
  for (let y = 0; y < height; y++) {
    pos = readScanline(bytes, pos, width, y, height, line);
    const row = flipY ? height - 1 - y : y;
    for (let x = 0; x < width; x++) {
      const col = flipX ? width - 1 - x : x;
      const f = EXPONENT[line[4 * x + 3]];
      const o = (row * width + col) * 3;
      rgb[o] = line[4 * x] * f;
      rgb[o + 1] = line[4 * x + 1] * f;
      rgb[o + 2] = line[4 * x + 2] * f;
    }
  }
  return { width, height, rgb };
}

interface Header {
  width: number;
  height: number;
  flipY: boolean;
  flipX: boolean;
  /** Offset of the first scanline. */
  data: number;
}

function readHeader(bytes: Uint8Array, limits: ImageLimits): Header {
  if (bytes.length < 2 || bytes[0] !== 0x23 || bytes[1] !== 0x3f) {
    throw new FormatError('HDR', 'not a Radiance HDR file: it must start with "#?"');
  }
  let start = lineEnd(bytes, 0) + 1;
  let line = 1;
  // Variables, up to an empty line.
  for (;;) {
    if (start >= bytes.length || start > MAX_HEADER) {
      throw new FormatError(
        'HDR',
        start > MAX_HEADER
          ? 'the header has no empty line within its first 64 KiB'
          : 'the file ends inside its header',
      );
    }
    const end = lineEnd(bytes, start);
    line++;
    const text = bytesToString(bytes, start, Math.min(end, start + 200)).trim();
    start = end + 1;
    if (text === '') break;
    if (text.startsWith('FORMAT=') && text !== 'FORMAT=32-bit_rle_rgbe') {
      throw new FormatError(
        'HDR',
        `header line ${line}: unsupported ${JSON.stringify(text.slice(0, 60))} ` +
          '(only 32-bit_rle_rgbe is read)',
      );
    }
  }
  // Resolution line: "-Y H +X W" and its flipped variants.
  const end = lineEnd(bytes, start);
  line++;
  const words: string[] = [];
  for (let i = skipBlanks(bytes, start, end); i < end && words.length < 5;) {
    const te = tokenEnd(bytes, i, end);
    words.push(bytesToString(bytes, i, Math.min(te, i + 24)));
    i = skipBlanks(bytes, te, end);
  }
  const [ya, hs, xa, ws] = words;
  const height = Number(hs);
  const width = Number(ws);
  if (
    words.length !== 4 ||
    (ya !== '-Y' && ya !== '+Y') ||
    (xa !== '+X' && xa !== '-X') ||
    !/^\d+$/.test(hs) ||
    !/^\d+$/.test(ws)
  ) {
    throw new FormatError(
      'HDR',
      `line ${line}: the resolution line must be like "-Y 512 +X 1024", got ` +
        JSON.stringify(words.join(' ').slice(0, 60)),
    );
  }
  checkSize(width, height, limits);
  return { width, height, flipY: ya === '+Y', flipX: xa === '-X', data: end + 1 };
}

export function checkSize(width: number, height: number, limits: ImageLimits): void {
  if (!(width >= 1 && height >= 1)) {
    throw new FormatError('HDR', `the image must be at least 1 × 1, got ${width} × ${height}`);
  }
  if (width > limits.maxWidth || height > limits.maxHeight) {
    throw new FormatError(
      'HDR',
      `the image is ${width} × ${height}, more than the limit of ` +
        `${limits.maxWidth} × ${limits.maxHeight}`,
    );
  }
}

function truncated(y: number, height: number): never {
  throw new FormatError('HDR', `the file ends in scanline ${y} of ${height}`);
}

/** Decodes scanline y into `line` (r, g, b, e per texel); returns the next offset. */
function readScanline(
  bytes: Uint8Array,
  pos: number,
  width: number,
  y: number,
  height: number,
  line: Uint8Array,
): number {
  const n = bytes.length;
  const isRle =
    width >= 8 &&
    width <= 0x7fff &&
    pos + 4 <= n &&
    bytes[pos] === 2 &&
    bytes[pos + 1] === 2 &&
    (bytes[pos + 2] & 0x80) === 0;
  if (!isRle) {
    if (pos + 4 * width > n) truncated(y, height);
    line.set(bytes.subarray(pos, pos + 4 * width));
    return pos + 4 * width;
  }
  const declared = (bytes[pos + 2] << 8) | bytes[pos + 3];
  if (declared !== width) {
    throw new FormatError(
      'HDR',
      `scanline ${y}: its run-length header says ${declared} texels, the image is ${width} wide`,
    );
  }
  pos += 4;
  for (let c = 0; c < 4; c++) {
    let x = 0;
    while (x < width) {
      if (pos >= n) truncated(y, height);
      let count = bytes[pos++];
      if (count > 128) {
        count -= 128;
        if (x + count > width) {
          throw new FormatError('HDR', `scanline ${y}: a run of ${count} overruns the scanline`);
        }
        if (pos >= n) truncated(y, height);
        const value = bytes[pos++];
        for (let k = 0; k < count; k++) line[4 * (x + k) + c] = value;
        x += count;
      } else {
        if (count === 0) throw new FormatError('HDR', `scanline ${y}: a run of length 0`);
        if (x + count > width) {
          throw new FormatError('HDR', `scanline ${y}: a run of ${count} overruns the scanline`);
        }
        if (pos + count > n) truncated(y, height);
        for (let k = 0; k < count; k++) line[4 * (x + k) + c] = bytes[pos + k];
        pos += count;
        x += count;
      }
    }
  }
  return pos;
}

/** Encodes an RGB float image (row 0 at the top) as RLE RGBE, for the project's own maps. */
export function encodeHdr(width: number, height: number, rgb: Float32Array): Uint8Array {
  const header = `#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y ${height} +X ${width}\n`;
  const out: number[] = Array.from(header, (ch) => ch.charCodeAt(0));
  const texel = new Uint8Array(width * 4);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const o = (y * width + x) * 3;
      toRgbe(rgb[o], rgb[o + 1], rgb[o + 2], texel, 4 * x);
    }
    if (width < 8 || width > 0x7fff) {
      for (const b of texel) out.push(b);
      continue;
    }
    out.push(2, 2, width >> 8, width & 0xff);
    for (let c = 0; c < 4; c++) {
      let x = 0;
      while (x < width) {
        // A run of equal values if at least 3 long, else a dump up to the next run.
        let run = 1;
        while (x + run < width && run < 127 && texel[4 * (x + run) + c] === texel[4 * x + c]) run++;
        if (run >= 3) {
          out.push(128 + run, texel[4 * x + c]);
          x += run;
          continue;
        }
        let dump = 0;
        while (x + dump < width && dump < 128) {
          const v = texel[4 * (x + dump) + c];
          if (
            x + dump + 2 < width &&
            texel[4 * (x + dump + 1) + c] === v &&
            texel[4 * (x + dump + 2) + c] === v
          ) {
            break;
          }
          dump++;
        }
        if (dump === 0) dump = 1;
        out.push(dump);
        for (let k = 0; k < dump; k++) out.push(texel[4 * (x + k) + c]);
        x += dump;
      }
    }
  }
  return Uint8Array.from(out);
}

/**
 * The RGBE texel nearest below (r, g, b) under this file's decoding rule
 * (m · 2^(e − 136)): e is chosen so the largest channel's mantissa lies in [128, 256).
 */
function toRgbe(r: number, g: number, b: number, out: Uint8Array, o: number): void {
  const m = Math.max(r, g, b);
  if (!(m > 0)) {
    out[o] = out[o + 1] = out[o + 2] = out[o + 3] = 0;
    return;
  }
  let e = Math.floor(Math.log2(m)) + 1; // m < 2^e
  let f = 2 ** (8 - e); // mantissa = value · 2^(8 − e) ∈ [128, 256)
  if (Math.floor(m * f) >= 256) {
    e++;
    f /= 2;
  }
  const biased = e + 128;
  if (biased < 1) {
    out[o] = out[o + 1] = out[o + 2] = out[o + 3] = 0;
    return;
  }
  out[o] = Math.min(255, Math.floor(r * f + 0.5));
  out[o + 1] = Math.min(255, Math.floor(g * f + 0.5));
  out[o + 2] = Math.min(255, Math.floor(b * f + 0.5));
  out[o + 3] = Math.min(255, biased);
}
