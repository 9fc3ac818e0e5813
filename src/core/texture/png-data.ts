/**
 * The image data of a PNG (W3C PNG, 3rd edition): how many bytes its filtered
 * scanlines take (§7.2: a filter byte, then the row's samples packed to whole bytes;
 * §8.2: Adam7's seven passes, empty ones without bytes), and its zlib stream (RFC 1950)
 * inflated with a hard limit of exactly that size, each scanline's filter type checked
 * on the way (§7.3). Deflate cannot expand more than about 1032:1 (RFC 1951: a
 * length-258 match costs at least 2 bits, so 258 bytes per 2 bits, plus block
 * headers), which bounds what a header may claim for the compressed bytes it has.
 */
import { Unzlib } from 'fflate';
import { adler32 } from '../util/adler32.ts';
import { FormatError } from '../util/format-error.ts';
import { sanitize } from '../util/message.ts';

/** Samples per pixel by colour type (§11.2.1, Table 11.1). */
export const PNG_CHANNELS: Record<number, number> = { 0: 1, 2: 3, 3: 1, 4: 2, 6: 4 };

function fail(detail: string): never {
  throw new FormatError('PNG', detail);
}

export interface PngHeader {
  width: number;
  height: number;
  depth: number;
  colorType: number;
  interlaced: boolean;
}

/** Adam7 passes (§8.2): x start, y start, x step, y step. */
const ADAM7 = [
  [0, 0, 8, 8],
  [4, 0, 8, 8],
  [0, 4, 4, 8],
  [2, 0, 4, 4],
  [0, 2, 2, 4],
  [1, 0, 2, 2],
  [0, 1, 1, 2],
];

/** Deflate's largest expansion (RFC 1951 §3.2.5: 258 bytes from a 2-bit code at best) is below 1032:1. */
export const DEFLATE_MAX_RATIO = 1032;

/** Input slice per inflate step: its output is at most ~2 MiB, the most inflated past the limit. */
const INFLATE_SLICE = 2048;

/** The scanlines of the image: [bytes per row including its filter byte, row count] per pass. */
export function pngScanlines(h: PngHeader): [number, number][] {
  const bits = PNG_CHANNELS[h.colorType] * h.depth;
  const rowBytes = (w: number) => 1 + Math.ceil((w * bits) / 8);
  if (!h.interlaced) return [[rowBytes(h.width), h.height]];
  const rows: [number, number][] = [];
  for (const [xs, ys, dx, dy] of ADAM7) {
    const w = h.width > xs ? Math.ceil((h.width - xs) / dx) : 0;
    const n = h.height > ys ? Math.ceil((h.height - ys) / dy) : 0;
    // An empty pass has no scanlines, not even filter bytes (§8.2).
    if (w > 0 && n > 0) rows.push([rowBytes(w), n]);
  }
  return rows;
}

/** Bytes the inflated image data must hold exactly. */
export function pngDataSize(h: PngHeader): number {
  return pngScanlines(h).reduce((sum, [bytes, n]) => sum + bytes * n, 0);
}

/**
 * Inflates the image data with a hard limit of what the header needs, checking each
 * scanline's filter type on the way; the inflated bytes are counted, not kept.
 */
export function inflateChecked(idat: Uint8Array[], idatBytes: number, h: PngHeader): void {
  const need = pngDataSize(h);
  const passes = pngScanlines(h);
  let pass = 0;
  let rowsLeft = passes[0][1];
  let nextFilter = 0; // offset of the next scanline's filter byte
  let total = 0;
  // Adler-32 of the inflated bytes (RFC 1950 §8.2): fflate does not check the
  // stream's trailer, and a damaged stream can inflate to the right size.
  let adler = 1;
  const inflater = new Unzlib((chunk) => {
    if (total + chunk.length > need) {
      fail(
        `the image data inflates past the ${need} bytes its ${h.width}×${h.height} header needs`,
      );
    }
    while (nextFilter < total + chunk.length) {
      const f = chunk[nextFilter - total];
      if (f > 4) {
        fail(`scanline filter type ${f} at inflated byte ${nextFilter} is not 0–4 (§7.3)`);
      }
      nextFilter += passes[pass][0];
      if (--rowsLeft === 0 && ++pass < passes.length) rowsLeft = passes[pass][1];
      if (pass === passes.length) nextFilter = Infinity;
    }
    total += chunk.length;
    adler = adler32(chunk, adler);
  });
  try {
    let pushed = 0;
    for (const data of idat) {
      for (let i = 0; i < data.length; i += INFLATE_SLICE) {
        const slice = data.subarray(i, Math.min(data.length, i + INFLATE_SLICE));
        pushed += slice.length;
        inflater.push(slice, pushed === idatBytes);
      }
    }
  } catch (e) {
    if (e instanceof FormatError) throw e;
    // fflate's own messages ("invalid block type", "unexpected EOF", …) name the fault.
    fail(
      `the image data is not a valid zlib stream (${sanitize(e instanceof Error ? e.message : String(e), 60)})`,
    );
  }
  if (total !== need) {
    fail(
      `the image data inflates to ${total} bytes, but the ${h.width}×${h.height} header needs ${need}`,
    );
  }
  // The stream's last four bytes, which may span IDAT chunks.
  const tail = idat.flatMap((d) => [...d.subarray(Math.max(0, d.length - 4))]).slice(-4);
  const stored = ((tail[0] << 24) | (tail[1] << 16) | (tail[2] << 8) | tail[3]) >>> 0;
  if (stored !== adler) {
    fail(
      `the image data's Adler-32 checksum is ${hex(stored)}, but the data gives ${hex(adler)} (the file is damaged)`,
    );
  }
}

function hex(n: number): string {
  return n.toString(16).padStart(8, '0');
}
