/**
 * Writes TZA files (OIDN's tensor archive, src/core/denoise/tza.ts describes the format)
 * for the denoiser's tests: malformed ones for the parser's refusals, and a tiny "RT"
 * U-Net with random weights, whose every layer has a few channels, so that tiling and
 * worker-count tests run in milliseconds with the real network's wiring.
 */
import { UNET_LAYER_NAMES } from '../../src/core/denoise/unet-weights.ts';

export interface TzaEntry {
  name: string;
  shape: number[];
  layout: string;
  dtype?: 'f' | 'h';
  values: ArrayLike<number>;
}

/** float32 → binary16, round to nearest even; below half's normal range flushes to ±0. */
function floatToHalf(v: number): number {
  const f = new Float32Array([v]);
  const u = new Uint32Array(f.buffer)[0]!;
  const sign = (u >>> 16) & 0x8000;
  const exp = ((u >>> 23) & 0xff) - 127 + 15;
  if (v === 0 || exp <= 0) return sign;
  if (exp >= 31) throw new RangeError(`floatToHalf: ${v} is outside the normal half range`);
  const mant = u & 0x7fffff;
  let h = sign | (exp << 10) | (mant >> 13);
  if (mant & 0x1000 && (mant & 0x2fff) !== 0) h++;
  return h;
}

export function writeTza(entries: TzaEntry[]): Uint8Array {
  const chunks: number[] = [];
  const u8 = (v: number) => chunks.push(v & 0xff);
  const u16 = (v: number) => (u8(v), u8(v >> 8));
  const u32 = (v: number) => (u16(v & 0xffff), u16(v >>> 16));
  const u64 = (v: number) => (u32(v), u32(Math.floor(v / 2 ** 32)));
  u16(0x41d7);
  u8(2);
  u8(0);
  u64(0); // table offset, patched below
  const offsets: number[] = [];
  for (const e of entries) {
    while (chunks.length % 64) u8(0);
    offsets.push(chunks.length);
    const dv = new DataView(new ArrayBuffer(4));
    for (let i = 0; i < e.values.length; i++) {
      if ((e.dtype ?? 'h') === 'h') u16(floatToHalf(e.values[i]!));
      else {
        dv.setFloat32(0, e.values[i]!, true);
        for (let b = 0; b < 4; b++) u8(dv.getUint8(b));
      }
    }
  }
  const table = chunks.length;
  u32(entries.length);
  entries.forEach((e, k) => {
    u16(e.name.length);
    for (const ch of e.name) u8(ch.charCodeAt(0));
    u8(e.shape.length);
    for (const n of e.shape) u32(n);
    for (const ch of e.layout) u8(ch.charCodeAt(0));
    u8((e.dtype ?? 'h').charCodeAt(0));
    u64(offsets[k]!);
  });
  const bytes = Uint8Array.from(chunks);
  new DataView(bytes.buffer).setUint32(4, table, true);
  return bytes;
}

/** A deterministic pseudo-random stream in [-1, 1) (xorshift32). */
export function randomStream(seed: number): () => number {
  let s = seed >>> 0 || 1;
  return () => {
    s ^= s << 13;
    s >>>= 0;
    s ^= s >>> 17;
    s ^= s << 5;
    s >>>= 0;
    return s / 2 ** 31 - 1;
  };
}

/** The RT U-Net's tensors with `width` channels in every hidden layer and random weights. */
export function tinyUNetTza(inputChannels: number, width: number, seed: number): Uint8Array {
  const next = randomStream(seed);
  const inOf: Record<string, number> = {
    enc_conv0: inputChannels,
    dec_conv4a: 2 * width,
    dec_conv3a: 2 * width,
    dec_conv2a: 2 * width,
    dec_conv1a: width + inputChannels,
  };
  const entries: TzaEntry[] = [];
  for (const name of UNET_LAYER_NAMES) {
    const o = name === 'dec_conv0' ? 3 : width;
    const i = inOf[name] ?? width;
    // He-like scale keeps activations of order one through sixteen layers.
    const scale = Math.sqrt(2 / (9 * i));
    entries.push({
      name: `${name}.weight`,
      shape: [o, i, 3, 3],
      layout: 'oihw',
      values: Array.from({ length: o * i * 9 }, () => next() * scale * 1.5),
    });
    entries.push({
      name: `${name}.bias`,
      shape: [o],
      layout: 'x',
      values: Array.from({ length: o }, () => next() * 0.05 + 0.02),
    });
  }
  return writeTza(entries);
}
