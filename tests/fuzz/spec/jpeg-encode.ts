/**
 * A baseline JPEG encoder written from ITU-T T.81: markers and segments (B.1–B.2), SOF0
 * with any sampling factors 1–2, DQT, DHT (B.2.4.2) with the luminance DC table of K.3,
 * restart intervals (B.2.4.4, RSTm with predictors reset, F.1.2.1.3), byte stuffing
 * (F.1.2.3). It codes DC-only blocks: each 8×8 block a flat colour whose DC coefficient is
 * 8·(v − 128) (A.3.3, the FDCT of a constant block), quantized by 8, followed by EOB. That
 * exercises every structure of a baseline decoder while staying a few dozen lines.
 */
import { ByteWriter } from './bytes.ts';

export interface Segment {
  marker: number; // the byte after 0xFF
  payload: Uint8Array;
  /** A length to write instead of payload + 2. */
  length?: number;
}

export interface JpegImage {
  width: number;
  height: number;
  /** Per component: id, sampling factors, quant and Huffman table ids. */
  comps: { id: number; h: number; v: number; tq: number; td: number; ta: number }[];
  /** The flat value (0–255) of block (bx, by) of component c, in that component's blocks. */
  value(c: number, bx: number, by: number): number;
  restart: number; // 0: none
}

/** K.3, table K.3: the luminance DC code lengths; symbols are the categories 0–11. */
export const DC_COUNTS = [0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0];
export const DC_SYMBOLS = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11];
/** An AC table holding only EOB (0x00): one code of length 1 ("0"). */
export const AC_COUNTS = [1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0];
export const AC_SYMBOLS = [0];

/** C.2: canonical codes from the count of each length. */
function huffCodes(counts: number[], symbols: number[]): Map<number, [number, number]> {
  const out = new Map<number, [number, number]>();
  let code = 0;
  let k = 0;
  for (let len = 1; len <= 16; len++) {
    for (let i = 0; i < counts[len - 1]; i++) out.set(symbols[k++], [code++, len]);
    code <<= 1;
  }
  return out;
}

export function segment(marker: number, bytes: number[] | Uint8Array): Segment {
  return { marker, payload: Uint8Array.from(bytes) };
}

export function dht(
  tc: number,
  th: number,
  counts = tc ? AC_COUNTS : DC_COUNTS,
  symbols = tc ? AC_SYMBOLS : DC_SYMBOLS,
): Segment {
  return segment(0xc4, [(tc << 4) | th, ...counts, ...symbols]);
}

export function sof(marker: number, img: JpegImage, precision = 8): Segment {
  const b = [
    precision,
    img.height >> 8,
    img.height & 255,
    img.width >> 8,
    img.width & 255,
    img.comps.length,
  ];
  for (const c of img.comps) b.push(c.id, (c.h << 4) | c.v, c.tq);
  return segment(marker, b);
}

export function sos(img: JpegImage): Segment {
  const b = [img.comps.length];
  for (const c of img.comps) b.push(c.id, (c.td << 4) | c.ta);
  b.push(0, 63, 0);
  return segment(0xda, b);
}

/** The entropy-coded segment(s) of the scan, RST markers included. */
export function scanData(img: JpegImage): Uint8Array {
  const dc = huffCodes(DC_COUNTS, DC_SYMBOLS);
  const eob = huffCodes(AC_COUNTS, AC_SYMBOLS).get(0)!;
  const out = new ByteWriter();
  let acc = 0;
  let nbits = 0;
  const put = (code: number, len: number) => {
    for (let i = len - 1; i >= 0; i--) {
      acc = (acc << 1) | ((code >> i) & 1);
      if (++nbits === 8) {
        out.u8(acc);
        if (acc === 0xff) out.u8(0); // F.1.2.3 byte stuffing
        acc = 0;
        nbits = 0;
      }
    }
  };
  const flush = () => {
    while (nbits !== 0) put(1, 1); // pad with 1-bits (F.1.2.3)
  };
  const hmax = Math.max(...img.comps.map((c) => c.h));
  const vmax = Math.max(...img.comps.map((c) => c.v));
  const mcusX = Math.ceil(img.width / (8 * hmax));
  const mcusY = Math.ceil(img.height / (8 * vmax));
  const pred = img.comps.map(() => 0);
  let mcu = 0;
  for (let my = 0; my < mcusY; my++) {
    for (let mx = 0; mx < mcusX; mx++) {
      if (img.restart && mcu > 0 && mcu % img.restart === 0) {
        flush();
        out.u8(0xff).u8(0xd0 + ((mcu / img.restart - 1) % 8));
        pred.fill(0);
      }
      img.comps.forEach((c, ci) => {
        for (let v = 0; v < c.v; v++) {
          for (let h = 0; h < c.h; h++) {
            const q = Math.round(img.value(ci, mx * c.h + h, my * c.v + v)) - 128; // 8(v−128)/8
            const diff = q - pred[ci];
            pred[ci] = q;
            const s = diff === 0 ? 0 : Math.floor(Math.log2(Math.abs(diff))) + 1;
            const [code, len] = dc.get(s)!;
            put(code, len);
            if (s > 0) put(diff > 0 ? diff : diff + (1 << s) - 1, s); // F.1.2.1.1
            put(eob[0], eob[1]);
          }
        }
      });
      mcu++;
    }
  }
  flush();
  return out.done();
}

export function serializeJpeg(segs: readonly Segment[], scan: Uint8Array, eoi = true): Uint8Array {
  const w = new ByteWriter().u8(0xff).u8(0xd8);
  for (const s of segs) {
    w.u8(0xff)
      .u8(s.marker)
      .u16(s.length ?? s.payload.length + 2, false)
      .bytes(s.payload);
    if (s.marker === 0xda) w.bytes(scan);
  }
  if (eoi) w.u8(0xff).u8(0xd9);
  return w.done();
}

/** The segments of a valid file, in the usual order: APP0, DQT, SOF0, DHT ×2–4, DRI, SOS. */
export function jpegSegments(img: JpegImage, jfif: boolean): Segment[] {
  const segs: Segment[] = [];
  if (jfif) segs.push(segment(0xe0, [0x4a, 0x46, 0x49, 0x46, 0, 1, 1, 0, 0, 1, 0, 1, 0, 0]));
  const tqs = [...new Set(img.comps.map((c) => c.tq))];
  for (const t of tqs) segs.push(segment(0xdb, [t, ...new Array(64).fill(8)]));
  segs.push(sof(0xc0, img));
  for (const t of [...new Set(img.comps.map((c) => c.td))]) segs.push(dht(0, t));
  for (const t of [...new Set(img.comps.map((c) => c.ta))]) segs.push(dht(1, t));
  if (img.restart) segs.push(segment(0xdd, [img.restart >> 8, img.restart & 255]));
  segs.push(sos(img));
  return segs;
}
