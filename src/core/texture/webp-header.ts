/**
 * A WebP image's size from its RIFF container, without decoding it (RFC 9649, "WebP
 * Image Format"), so that the texture budget is checked before libwebp or the
 * browser allocates width × height × 4 bytes: libwebp allocates its output from the
 * header, before it reads the frame, so a 7 KB file that claims 16383 × 16383 costs
 * a gigabyte unless refused here.
 *
 * Three layouts (RFC 9649 §2.5–2.7): a lossy frame ('VP8 '), a lossless one ('VP8L'),
 * or the extended header ('VP8X') with the canvas size followed by optional chunks
 * and one of the two frames. Errors are FormatError('WebP', …) naming the byte.
 */
import { FormatError } from '../util/format-error.ts';

export interface WebpInfo {
  width: number;
  height: number;
}

const fourcc = (b: Uint8Array, at: number): string =>
  String.fromCharCode(...b.subarray(at, at + 4));
const u16 = (b: Uint8Array, at: number): number => b[at] | (b[at + 1] << 8);
const u24 = (b: Uint8Array, at: number): number => b[at] | (b[at + 1] << 8) | (b[at + 2] << 16);
const u32 = (b: Uint8Array, at: number): number => (u24(b, at) + b[at + 3] * 0x1000000) >>> 0;

/** Bytes 0–11: "RIFF", the RIFF size, "WEBP". */
export function isWebp(b: Uint8Array): boolean {
  return b.length >= 12 && fourcc(b, 0) === 'RIFF' && fourcc(b, 8) === 'WEBP';
}

/** The size of the frame in the chunk at `at` ('VP8 ' or 'VP8L'), or null for another chunk. */
function frameSize(b: Uint8Array, at: number, fail: (m: string) => never): WebpInfo | null {
  const tag = fourcc(b, at);
  const d = at + 8;
  if (tag === 'VP8 ') {
    // RFC 6386 §9.1: a 3-byte frame tag (bit 0 clear on a key frame), the start code
    // 9d 01 2a, then 14-bit width and height, each with 2 bits of scaling above.
    if (d + 10 > b.length) fail(`VP8 frame header truncated at byte ${d}`);
    if ((b[d] & 1) !== 0) fail(`the VP8 frame at byte ${d} is not a key frame`);
    if (b[d + 3] !== 0x9d || b[d + 4] !== 0x01 || b[d + 5] !== 0x2a)
      fail(`VP8 start code missing at byte ${d + 3}`);
    const size = { width: u16(b, d + 6) & 0x3fff, height: u16(b, d + 8) & 0x3fff };
    if (size.width === 0 || size.height === 0)
      fail(`VP8 frame size ${size.width}×${size.height} at byte ${d + 6}`);
    return size;
  }
  if (tag === 'VP8L') {
    // RFC 9649 §3.2.1: the signature 0x2f, then 14 bits width − 1, 14 bits height − 1,
    // one alpha hint and a 3-bit version that must be 0.
    if (d + 5 > b.length) fail(`VP8L header truncated at byte ${d}`);
    if (b[d] !== 0x2f) fail(`VP8L signature missing at byte ${d}`);
    const bits = u32(b, d + 1);
    if (bits >>> 29 !== 0) fail(`VP8L version ${bits >>> 29} at byte ${d + 4} is not 0`);
    return { width: (bits & 0x3fff) + 1, height: ((bits >>> 14) & 0x3fff) + 1 };
  }
  return null;
}

/**
 * Width and height of a WebP image (the canvas of an extended file, which must equal
 * its frame's). Refuses animations (a texture has one image) and truncated headers.
 */
export function readWebpInfo(b: Uint8Array): WebpInfo {
  const fail = (m: string): never => {
    throw new FormatError('WebP', m);
  };
  if (!isWebp(b)) fail('no RIFF/WEBP signature');
  if (b.length < 20) fail(`truncated: ${b.length} bytes, no first chunk`);
  // The RIFF size counts from byte 8; a file shorter than it says was cut.
  const riffEnd = u32(b, 4) + 8;
  if (riffEnd > b.length)
    fail(`truncated: the RIFF header says ${riffEnd} bytes, the file has ${b.length}`);
  const first = fourcc(b, 12);
  if (first !== 'VP8X') {
    const size = frameSize(b, 12, fail);
    if (size === null) fail(`unknown first chunk "${first.replace(/[^ -~]/g, '?')}" at byte 12`);
    return size!;
  }
  // RFC 9649 §2.7: flags (animation 0x02), 3 reserved bytes, 24-bit canvas width − 1
  // and height − 1.
  if (b.length < 30) fail('VP8X header truncated at byte 20');
  if ((b[20] & 0x02) !== 0) fail('animated WebP: a texture holds one image');
  const canvas = { width: u24(b, 24) + 1, height: u24(b, 27) + 1 };
  // Walk the chunks (each padded to an even size) to the frame; the walk only advances.
  let at = 12 + 8 + u32(b, 16);
  at += at & 1;
  while (at + 8 <= riffEnd) {
    const frame = frameSize(b, at, fail);
    if (frame !== null) {
      if (frame.width !== canvas.width || frame.height !== canvas.height)
        fail(
          `the frame at byte ${at} is ${frame.width}×${frame.height}, the canvas ${canvas.width}×${canvas.height}`,
        );
      return canvas;
    }
    const size = u32(b, at + 4);
    at += 8 + size + (size & 1);
  }
  return fail('no VP8 or VP8L frame after the VP8X header (truncated?)');
}
