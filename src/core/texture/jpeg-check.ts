/**
 * Checks a JPEG's marker segments (ITU-T T.81, Annex B) before jpeg-js allocates
 * anything, so that a header cannot make the decoder work on what it claims rather
 * than on what the file holds, and so that a malformed segment is named instead of
 * surfacing as one of jpeg-js's internal TypeErrors:
 *
 * - every segment's length lies inside the file (B.1.1.4), and the file ends with EOI;
 * - exactly one frame, of a process jpeg-js decodes: baseline, extended (8-bit) or
 *   progressive Huffman (SOF0, SOF1, SOF2; B.2.2), with 1–4 components, sampling
 *   factors 1–4, and a height given in the frame header (not by a DNL marker);
 * - every scan (SOS, B.2.3) comes after the frame and names components of the frame
 *   and Huffman tables defined before it; every component's quantization table (DQT,
 *   B.2.4.1) is defined by the end;
 * - the declared size against the bytes present: each 8×8 block of each component
 *   (A.2, component sizes by A.1.1) costs at least 2 bits in a sequential scan, its DC
 *   difference code and the end-of-block code (F.1.2: a Huffman code is at least one
 *   bit long), and at least 1 bit in progressive mode, whose first DC scan codes every
 *   block's DC difference (G.1.2.1) while AC scans may skip runs of blocks with one
 *   EOBRUN code. A frame that needs more than the whole file holds is rejected at
 *   once, and one that needs more than its scans hold once they are walked (so that
 *   COM or APPn padding cannot stand in for image data);
 * - the frame's texels against the decoded-texel budget.
 */
import { FormatError } from '../util/format-error.ts';

export interface JpegFrame {
  width: number;
  height: number;
  components: number;
  progressive: boolean;
}

function fail(detail: string): never {
  throw new FormatError('JPEG', detail);
}

const hex = (m: number) => `FF${m.toString(16).toUpperCase().padStart(2, '0')}`;

/** Names of the frame types jpeg-js cannot decode (B.1.1.3, Table B.1). */
function unsupportedFrame(marker: number): string {
  if (marker === 0xc3) return 'lossless';
  if (marker >= 0xc5 && marker <= 0xc7) return 'hierarchical';
  return 'arithmetic-coded';
}

/** Least entropy-coded bytes a frame of these components can have (see above). */
export function jpegMinimumBytes(
  width: number,
  height: number,
  sampling: [number, number][],
  progressive: boolean,
): number {
  const hMax = Math.max(...sampling.map(([h]) => h));
  const vMax = Math.max(...sampling.map(([, v]) => v));
  let blocks = 0;
  for (const [h, v] of sampling) {
    // A.1.1: a component has ceil(X·H/Hmax) × ceil(Y·V/Vmax) samples.
    blocks +=
      Math.ceil(Math.ceil((width * h) / hMax) / 8) * Math.ceil(Math.ceil((height * v) / vMax) / 8);
  }
  return Math.ceil((blocks * (progressive ? 1 : 2)) / 8);
}

/** Checks the JPEG in `bytes` (see above); returns its frame or throws FormatError('JPEG', …). */
export function checkJpeg(bytes: Uint8Array, maxTexels: number): JpegFrame {
  const n = bytes.length;
  if (n < 3 || bytes[0] !== 0xff || bytes[1] !== 0xd8) fail('not a JPEG file (no SOI marker)');
  let frame: JpegFrame | null = null;
  let componentIds: number[] = [];
  let quantIds: number[] = [];
  const dc = new Set<number>();
  const ac = new Set<number>();
  const quant = new Set<number>();
  let scans = 0;
  /** Bytes of entropy-coded data in all scans; `least` of them are needed. */
  let entropyBytes = 0;
  let least = 0;
  let p = 2;
  for (;;) {
    // A file cut short is damaged: reported, rather than decoded in part as a browser
    // would, so that Node and the browser agree (the browser runs this check too).
    if (p >= n) fail(`the file ends at byte ${n} without an EOI marker (truncated?)`);
    if (bytes[p] !== 0xff) fail(`byte ${p}: expected a marker (FF xx), found ${bytes[p]}`);
    while (p + 1 < n && bytes[p + 1] === 0xff) p++; // fill bytes (B.1.1.2)
    if (p + 1 >= n) fail(`the file ends at byte ${n} without an EOI marker (truncated?)`);
    const marker = bytes[p + 1];
    const at = p;
    p += 2;
    if (marker === 0xd9) break; // EOI; anything after it is not part of the image
    if (marker === 0x01 || (marker >= 0xd0 && marker <= 0xd7)) continue; // TEM, RSTn: no length
    if (marker === 0xd8 || marker === 0x00)
      fail(`marker ${hex(marker)} at byte ${at} is out of place`);
    if (p + 2 > n) fail(`the file ends inside the ${hex(marker)} segment at byte ${at}`);
    const length = (bytes[p] << 8) | bytes[p + 1];
    if (length < 2 || p + length > n) {
      fail(
        `the ${hex(marker)} segment at byte ${at} has length ${length}, past the end of the file (${n} bytes)`,
      );
    }
    const seg = bytes.subarray(p + 2, p + length);
    const where = `the ${hex(marker)} segment at byte ${at}`;
    p += length;
    if (marker >= 0xc0 && marker <= 0xcf && marker !== 0xc4 && marker !== 0xc8 && marker !== 0xcc) {
      if (frame !== null) fail(`${where}: a second frame header (only one frame is read)`);
      if (marker > 0xc2) fail(`${where}: ${unsupportedFrame(marker)} JPEG is not supported`);
      const nf = seg[5];
      if (seg.length < 6 || seg.length !== 6 + 3 * nf) {
        fail(`${where}: the frame header's length does not match its ${nf ?? 0} components`);
      }
      if (seg[0] !== 8) fail(`${where}: ${seg[0]}-bit samples are not supported (only 8-bit)`);
      const height = (seg[1] << 8) | seg[2];
      const width = (seg[3] << 8) | seg[4];
      if (height === 0) fail(`${where}: height 0 (set by a later DNL marker) is not supported`);
      if (width === 0) fail(`${where}: width 0`);
      if (nf < 1 || nf > 4) fail(`${where}: ${nf} components (1 to 4 are decoded)`);
      const sampling: [number, number][] = [];
      componentIds = [];
      quantIds = [];
      for (let i = 0; i < nf; i++) {
        const h = seg[7 + 3 * i] >> 4;
        const v = seg[7 + 3 * i] & 15;
        if (h < 1 || h > 4 || v < 1 || v > 4) {
          fail(`${where}: component ${i} has sampling factors ${h}×${v} (each must be 1–4)`);
        }
        if (componentIds.includes(seg[6 + 3 * i]))
          fail(`${where}: component id ${seg[6 + 3 * i]} appears twice`);
        if (seg[8 + 3 * i] > 3)
          fail(`${where}: component ${i} uses quantization table ${seg[8 + 3 * i]} (0–3)`);
        componentIds.push(seg[6 + 3 * i]);
        quantIds.push(seg[8 + 3 * i]);
        sampling.push([h, v]);
      }
      const progressive = marker === 0xc2;
      if (width * height > maxTexels) {
        fail(
          `the frame header claims ${width}×${height}, over the budget of ${maxTexels} decoded texels`,
        );
      }
      least = jpegMinimumBytes(width, height, sampling, progressive);
      if (least > n) {
        fail(
          `the frame header claims ${width}×${height} but the file has only ${n} bytes (at least ${least} needed)`,
        );
      }
      frame = { width, height, components: nf, progressive };
    } else if (marker === 0xc4) {
      // DHT (B.2.4.2): class and id, 16 code counts, then the values.
      for (let i = 0; i < seg.length;) {
        const tc = seg[i] >> 4;
        const th = seg[i] & 15;
        if (tc > 1 || th > 3)
          fail(`${where}: Huffman table class ${tc} id ${th} (class 0–1, id 0–3)`);
        if (i + 17 > seg.length) fail(`${where}: a Huffman table is cut short`);
        let count = 0;
        for (let k = 1; k <= 16; k++) count += seg[i + k];
        if (count > 256 || i + 17 + count > seg.length) {
          fail(`${where}: a Huffman table lists ${count} codes, more than the segment holds`);
        }
        (tc === 0 ? dc : ac).add(th);
        i += 17 + count;
      }
    } else if (marker === 0xdb) {
      // DQT (B.2.4.1): precision and id, then 64 entries of 1 or 2 bytes.
      for (let i = 0; i < seg.length;) {
        const pq = seg[i] >> 4;
        const tq = seg[i] & 15;
        if (pq > 1 || tq > 3)
          fail(`${where}: quantization table precision ${pq} id ${tq} (0–1, 0–3)`);
        const size = 1 + 64 * (pq + 1);
        if (i + size > seg.length) fail(`${where}: a quantization table is cut short`);
        quant.add(tq);
        i += size;
      }
    } else if (marker === 0xda) {
      if (frame === null) fail(`${where}: a scan before the frame header`);
      const ns = seg[0];
      if (ns < 1 || ns > 4 || seg.length !== 4 + 2 * ns) {
        fail(`${where}: the scan header's length does not match its ${ns ?? 0} components`);
      }
      for (let i = 0; i < ns; i++) {
        const id = seg[1 + 2 * i];
        const td = seg[2 + 2 * i] >> 4;
        const ta = seg[2 + 2 * i] & 15;
        if (!componentIds.includes(id))
          fail(`${where}: the scan names component ${id}, which the frame lacks`);
        const ss = seg[1 + 2 * ns];
        const ah = seg[3 + 2 * ns] >> 4;
        // A first DC scan (Ss = 0, Ah = 0) needs a DC table (a DC refinement scan reads
        // raw bits, G.1.2.1); a scan with AC coefficients needs an AC table.
        if (ss === 0 && ah === 0 && !dc.has(td))
          fail(`${where}: the scan uses DC Huffman table ${td}, which is not defined`);
        if ((!frame.progressive || ss > 0) && !ac.has(ta)) {
          fail(`${where}: the scan uses AC Huffman table ${ta}, which is not defined`);
        }
      }
      scans++;
      const start = p;
      // Skip the entropy-coded data: up to the next marker that is not a stuffed
      // zero (FF00) or a restart (FFD0–FFD7) (B.1.1.5).
      while (
        p + 1 < n &&
        !(
          bytes[p] === 0xff &&
          bytes[p + 1] !== 0 &&
          !(bytes[p + 1] >= 0xd0 && bytes[p + 1] <= 0xd7)
        )
      )
        p++;
      if (p + 1 >= n) p = n;
      entropyBytes += p - start;
    }
    // APPn, COM, DRI, DNL and the rest: skipped by their length.
  }
  if (frame === null) fail('no frame header (SOF marker)');
  if (scans === 0) fail('no image data (no SOS segment)');
  // The same bound against the scans alone, so that padding (COM or APPn segments)
  // cannot stand in for image data.
  if (entropyBytes < least) {
    fail(
      `the frame header claims ${frame.width}×${frame.height} but its scans hold only ` +
        `${entropyBytes} bytes of entropy-coded data (at least ${least} needed)`,
    );
  }
  for (let i = 0; i < quantIds.length; i++) {
    if (!quant.has(quantIds[i])) {
      fail(`component ${i} uses quantization table ${quantIds[i]}, which no DQT segment defines`);
    }
  }
  return frame;
}
