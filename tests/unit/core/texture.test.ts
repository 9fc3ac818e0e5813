/**
 * Textures in the core: decoding (fast-png, jpeg-js), sRGB → linear once at
 * decode, the flat shared store and its limits, and bilinear lookup with
 * glTF's wrap modes.
 */
import { encode as encodePng } from 'fast-png';
import jpeg from 'jpeg-js';
import { describe, expect, it } from 'vitest';
import { decodeImageJs } from '../../../src/core/texture/decode-js.ts';
import { type DecodedImage, writeDecodedImage } from '../../../src/core/texture/decoded-image.ts';
import { readImageInfo } from '../../../src/core/texture/image-header.ts';
import {
  Texel,
  textureBilinear,
  WRAP_CLAMP,
  WRAP_MIRROR,
  WRAP_REPEAT,
} from '../../../src/core/texture/bilinear.ts';
import { srgb8ToLinear16Table, srgbToLinear, TEXEL_MAX } from '../../../src/core/texture/srgb.ts';
import { TextureLayout, type TextureStore } from '../../../src/core/texture/texture-store.ts';

function storeOf(images: DecodedImage[], srgb = false): TextureStore {
  const layout = new TextureLayout();
  for (const img of images) layout.add(img.width, img.height, 'test');
  const store = layout.allocate(true);
  images.forEach((img, i) => writeDecodedImage(store, i, img, srgb, 'test'));
  return store;
}

describe('sRGB → linear', () => {
  it('is the IEC 61966-2-1 curve, monotonic, exact at the ends', () => {
    const lut = srgb8ToLinear16Table();
    expect(lut[0]).toBe(0);
    expect(lut[255]).toBe(TEXEL_MAX);
    for (let i = 1; i < 256; i++) {
      expect(lut[i]).toBeGreaterThan(lut[i - 1]);
      expect(Math.abs(lut[i] / TEXEL_MAX - srgbToLinear(i / 255))).toBeLessThanOrEqual(
        0.5 / TEXEL_MAX,
      );
    }
    expect(srgbToLinear(0.5)).toBeCloseTo(0.214041, 6);
  });
});

describe('decoded images into the store', () => {
  it('expands grey, grey+alpha, RGB and RGBA; converts colour from sRGB, never alpha', () => {
    const images: DecodedImage[] = [
      { width: 1, height: 1, data: Uint8Array.of(128), channels: 1, depth: 8 },
      { width: 1, height: 1, data: Uint8Array.of(128, 64), channels: 2, depth: 8 },
      { width: 1, height: 1, data: Uint8Array.of(255, 128, 0), channels: 3, depth: 8 },
      { width: 1, height: 1, data: Uint8Array.of(255, 128, 0, 128), channels: 4, depth: 8 },
      { width: 1, height: 1, data: Uint16Array.of(65535, 32768, 0, 32768), channels: 4, depth: 16 },
    ];
    const lin = storeOf(images, false);
    const srgb = storeOf(images, true);
    const t = (s: TextureStore, i: number): number[] =>
      Array.from(s.texels.subarray(4 * i, 4 * i + 4));
    expect(t(lin, 0)).toEqual([128 * 257, 128 * 257, 128 * 257, 65535]);
    expect(t(lin, 1)).toEqual([128 * 257, 128 * 257, 128 * 257, 64 * 257]);
    expect(t(lin, 2)).toEqual([65535, 128 * 257, 0, 65535]);
    expect(t(lin, 4)).toEqual([65535, 32768, 0, 32768]);
    const half = Math.round(srgbToLinear(128 / 255) * 65535);
    expect(t(srgb, 1)).toEqual([half, half, half, 64 * 257]);
    expect(t(srgb, 3)).toEqual([65535, half, 0, 128 * 257]);
    expect(t(srgb, 4)[1]).toBe(Math.round(srgbToLinear(32768 / 65535) * 65535));
    expect(t(srgb, 4)[3]).toBe(32768);
  });

  it('rejects an image whose decoded size differs from its header', () => {
    const layout = new TextureLayout();
    layout.add(2, 2, 'images[0]');
    const store = layout.allocate(false);
    const img = { width: 3, height: 2, data: new Uint8Array(24), channels: 4, depth: 8 };
    expect(() => writeDecodedImage(store, 0, img, false, 'images[0]')).toThrow(
      /images\[0\]: decoded as 3×2, but its header said 2×2/,
    );
  });
});

describe('texture store limits', () => {
  it('checks the memory limit and the side limit before allocating', () => {
    const layout = new TextureLayout(1024 * 1024);
    layout.add(256, 256, 'images[0]'); // 512 KiB
    expect(() => layout.add(256, 257, 'images[1]')).toThrow(
      /images\[1\]: decoded textures would need 1\.0 MiB, over the texture memory limit of 1\.0 MiB/,
    );
    expect(() => new TextureLayout().add(20000, 4, 'images[2]')).toThrow(
      /images\[2\]: image 20000×4 is larger than the limit of 16384/,
    );
    expect(() => new TextureLayout().add(0, 4, 'images[3]')).toThrow(/not a positive integer/);
  });

  it('lives in a SharedArrayBuffer when asked, an ArrayBuffer otherwise', () => {
    const layout = new TextureLayout();
    layout.add(3, 2, 'a');
    layout.add(1, 5, 'b');
    const shared = layout.allocate(true);
    expect(shared.texels.buffer).toBeInstanceOf(SharedArrayBuffer);
    expect(shared.texels.length).toBe((6 + 5) * 4);
    expect(Array.from(shared.info)).toEqual([0, 3, 2, 6, 1, 5]);
    expect(layout.allocate(false).texels.buffer).toBeInstanceOf(ArrayBuffer);
  });
});

describe('bilinear lookup', () => {
  // 4×2 RGBA: red channel = 10·x + y·100 (linear 8-bit codes), alpha 255.
  const W = 4;
  const H = 2;
  const data = new Uint8Array(W * H * 4);
  for (let y = 0; y < H; y++) {
    for (let x = 0; x < W; x++) {
      const o = (y * W + x) * 4;
      data[o] = 10 * x + 100 * y;
      data[o + 1] = 200;
      data[o + 2] = x === 0 ? 255 : 0;
      data[o + 3] = 255;
    }
  }
  const store = storeOf([{ width: W, height: H, data, channels: 4, depth: 8 }]);
  const out = new Texel();
  const red = (u: number, v: number, s = WRAP_REPEAT, t = WRAP_REPEAT): number => {
    textureBilinear(store, 0, u, v, s, t, out);
    return out.r * 255;
  };

  it('returns texels at their centres and interpolates between them', () => {
    for (let y = 0; y < H; y++) {
      for (let x = 0; x < W; x++) {
        expect(red((x + 0.5) / W, (y + 0.5) / H)).toBeCloseTo(10 * x + 100 * y, 9);
      }
    }
    // Halfway between texels (1, 0) and (2, 1): mean of 10, 20, 110, 120.
    expect(red(2 / W, 1 / H)).toBeCloseTo(65, 9);
    textureBilinear(store, 0, 0.3, 0.3, WRAP_REPEAT, WRAP_REPEAT, out);
    expect(out.g).toBeCloseTo(200 / 255, 12);
    expect(out.a).toBeCloseTo(1, 12);
  });

  it('wraps: repeat, clamp to edge, mirrored repeat', () => {
    // u = 0: halfway between the last and the first column (repeat), the first (clamp, mirror).
    expect(red(0, 0.25)).toBeCloseTo(15, 9);
    expect(red(0, 0.25, WRAP_CLAMP)).toBeCloseTo(0, 9);
    expect(red(0, 0.25, WRAP_MIRROR)).toBeCloseTo(0, 9);
    // Periodicity and mirroring far from [0, 1].
    expect(red(7.375, 0.25)).toBeCloseTo(red(0.375, 0.25), 9);
    expect(red(-3.375, 0.25)).toBeCloseTo(red(0.625, 0.25), 9);
    expect(red(1e9 + 0.375, 0.25)).toBeCloseTo(red(0.375, 0.25), 6);
    expect(red(1.375, 0.25, WRAP_MIRROR)).toBeCloseTo(red(0.625, 0.25, WRAP_MIRROR), 9);
    expect(red(-0.375, 0.25, WRAP_MIRROR)).toBeCloseTo(red(0.375, 0.25, WRAP_MIRROR), 9);
    expect(red(5, 0.25, WRAP_CLAMP)).toBeCloseTo(30, 9);
    expect(red(0.375, -7, WRAP_REPEAT, WRAP_CLAMP)).toBeCloseTo(
      red(0.375, 0, WRAP_REPEAT, WRAP_CLAMP),
      9,
    );
  });

  it('reads non-finite coordinates as 0 instead of producing NaN', () => {
    for (const u of [NaN, Infinity, -Infinity]) {
      expect(Number.isFinite(red(u, u))).toBe(true);
      expect(red(u, 0.25)).toBe(red(0, 0.25));
    }
  });
});

describe('decoding PNG and JPEG in Node', () => {
  it('round-trips 8- and 16-bit PNGs, grey, palette and low bit depths', async () => {
    const rgba = Uint8Array.from({ length: 3 * 2 * 4 }, (_, i) => (i * 37) % 256);
    const a = await decodeImageJs(
      encodePng({ width: 3, height: 2, data: rgba, channels: 4, depth: 8 }),
    );
    expect([a.width, a.height, a.channels, a.depth]).toEqual([3, 2, 4, 8]);
    expect(Array.from(a.data)).toEqual(Array.from(rgba));
    const wide = Uint16Array.from({ length: 2 * 2 * 3 }, (_, i) => i * 5000);
    const b = await decodeImageJs(
      encodePng({ width: 2, height: 2, data: wide, channels: 3, depth: 16 }),
    );
    expect([b.channels, b.depth]).toEqual([3, 16]);
    expect(Array.from(b.data)).toEqual(Array.from(wide));
    // 1-bit grey, 3 wide (rows padded to a byte): 1 0 1 / 0 1 0.
    const bits = Uint8Array.of(0b10100000, 0b01000000);
    const c = await decodeImageJs(
      encodePng({ width: 3, height: 2, data: bits, channels: 1, depth: 1 }),
    );
    expect(Array.from(c.data)).toEqual([255, 0, 255, 0, 255, 0]);
    const d = await decodeImageJs(
      encodePng({
        width: 2,
        height: 1,
        data: Uint8Array.of(1, 0),
        channels: 1,
        depth: 8,
        palette: [
          [10, 20, 30],
          [40, 50, 60],
        ],
      }),
    );
    expect([d.channels, ...Array.from(d.data)]).toEqual([3, 40, 50, 60, 10, 20, 30]);
  });

  it('decodes JPEG (lossy: within a few codes)', async () => {
    const w = 16;
    const h = 8;
    const rgba = new Uint8Array(w * h * 4);
    for (let i = 0; i < w * h; i++) rgba.set([200, 100, 50, 255], 4 * i);
    const bytes = new Uint8Array(jpeg.encode({ width: w, height: h, data: rgba }, 95).data);
    expect(readImageInfo(bytes, 'x')).toEqual({ mimeType: 'image/jpeg', width: w, height: h });
    const img = await decodeImageJs(bytes);
    expect([img.width, img.height, img.channels]).toEqual([w, h, 3]);
    for (let i = 0; i < w * h; i++) {
      expect(Math.abs(img.data[3 * i] - 200)).toBeLessThan(4);
      expect(Math.abs(img.data[3 * i + 2] - 50)).toBeLessThan(4);
    }
  });

  it('names the image and the problem for broken data', async () => {
    const png = encodePng({ width: 2, height: 2, data: new Uint8Array(16), channels: 4, depth: 8 });
    await expect(decodeImageJs(png.subarray(0, 20))).rejects.toThrow(
      /^cannot decode PNG: chunk "IHDR" at byte 8: its length 13 runs past the end of the file/,
    );
    await expect(decodeImageJs(png.subarray(0, png.length - 20))).rejects.toThrow(
      /^cannot decode PNG: /,
    );
    await expect(decodeImageJs(Uint8Array.of(1, 2, 3, 4))).rejects.toThrow(
      /^not a PNG or JPEG image/,
    );
    // A tiny PNG claiming a huge size: its header is read before any decoding.
    const huge = png.slice();
    new DataView(huge.buffer).setUint32(16, 100_000);
    expect(readImageInfo(huge, 'images[3]')).toMatchObject({ width: 100_000, height: 2 });
    expect(() => new TextureLayout().add(100_000, 2, 'images[3]')).toThrow(/larger than the limit/);
  });
});
