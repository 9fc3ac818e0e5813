/**
 * Environment map files: Radiance HDR (flat and run-length encoded scanlines, the
 * spec's decoding rule) and PFM, with their limits, truncated files and lying headers,
 * and the texel checks (finite, ≥ 0, at most 1e12 times the scale) as scene errors.
 */
import { describe, expect, it } from 'vitest';
import {
  SceneError,
  decodeHdr,
  encodeHdr,
  encodePfm,
  loadScene,
  type SceneFileReader,
} from '../../../src/core/index.ts';
import { decodePfm } from '../../../src/core/io/pfm.ts';

const LIMITS = { maxWidth: 16384, maxHeight: 8192 };
const ascii = (s: string) => Uint8Array.from(s, (c) => c.charCodeAt(0));

function concat(...parts: (Uint8Array | number[])[]): Uint8Array {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let o = 0;
  for (const p of parts) {
    out.set(p, o);
    o += p.length;
  }
  return out;
}

describe('Radiance HDR', () => {
  it('decodes (r, g, b, e) to (r, g, b)·2^(e − 136), and e = 0 to 0, ignoring EXPOSURE', () => {
    const bytes = concat(
      ascii('#?RADIANCE\nEXPOSURE=4.0\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 3\n'),
      [128, 64, 1, 136, 255, 255, 255, 0, 1, 2, 3, 255],
    );
    const img = decodeHdr(bytes, LIMITS);
    expect([img.width, img.height]).toEqual([3, 1]);
    expect(Array.from(img.rgb)).toEqual([
      128,
      64,
      1,
      0,
      0,
      0,
      2 ** 119,
      2 * 2 ** 119,
      3 * 2 ** 119,
    ]);
  });

  it('round-trips run-length encoded and flat scanlines, and reads flipped orientations', () => {
    for (const [w, h] of [
      [64, 32],
      [5, 3], // too narrow for RLE: flat scanlines
      [300, 2], // runs longer than 127
    ]) {
      const rgb = new Float32Array(w * h * 3);
      for (let i = 0; i < rgb.length; i++) {
        // Values representable exactly: 8-bit mantissas sharing the texel's exponent.
        const t = Math.floor(i / 3);
        const e = (t % 7) - 3;
        rgb[i] = t % 5 === 0 ? 0 : ((128 + ((i * 37) % 128)) * 2 ** e) / 256;
        if (t % 11 === 0) rgb[i] = 1.5 * 2 ** e; // runs of equal values
      }
      const bytes = encodeHdr(w, h, rgb);
      const img = decodeHdr(bytes, LIMITS);
      expect(img.width).toBe(w);
      expect(img.height).toBe(h);
      for (let i = 0; i < rgb.length; i++) {
        const t = Math.floor(i / 3);
        const m = Math.max(rgb[3 * t], rgb[3 * t + 1], rgb[3 * t + 2]);
        // Channels smaller than the largest lose the bits below its exponent.
        expect(Math.abs(img.rgb[i] - rgb[i])).toBeLessThanOrEqual(m / 256);
      }
    }
    // A smooth image really is run-length encoded.
    expect(encodeHdr(256, 4, new Float32Array(256 * 4 * 3).fill(0.25)).length).toBeLessThan(
      256 * 4 * 4 * 0.1,
    );
    // +Y stores the bottom row first, −X the right column first.
    const flat = (orient: string) =>
      decodeHdr(concat(ascii(`#?RGBE\n\n${orient}\n`), [1, 0, 0, 137, 2, 0, 0, 137]), LIMITS)
        .rgb[0];
    expect(flat('-Y 2 +X 1')).toBe(2);
    expect(flat('+Y 2 +X 1')).toBe(4);
    expect(flat('-Y 1 -X 2')).toBe(4);
  });

  it('rejects truncated files, lying headers and bad runs with one clear message', () => {
    const good = encodeHdr(
      16,
      4,
      Float32Array.from({ length: 16 * 4 * 3 }, (_, i) => (i % 7) + 1),
    );
    expect(() => decodeHdr(good.subarray(0, good.length - 3), LIMITS)).toThrow(
      /^HDR: the file ends in scanline 3 of 4$/,
    );
    // 16384 × 8192 declared, a few bytes present: refused before allocating 1.6 GB.
    expect(() => decodeHdr(ascii('#?RADIANCE\n\n-Y 8192 +X 16384\n\x02\x02'), LIMITS)).toThrow(
      /^HDR: the header declares 16384 × 8192 texels, which need at least \d+ bytes, but only 2 follow it$/,
    );
    expect(() => decodeHdr(ascii('#?RADIANCE\n\n-Y 8193 +X 16\n'), LIMITS)).toThrow(
      /^HDR: the image is 16 × 8193, more than the limit of 16384 × 8192$/,
    );
    expect(() => decodeHdr(ascii('#?RADIANCE\n\n-Y 0 +X 16\n'), LIMITS)).toThrow(/at least 1 × 1/);
    expect(() => decodeHdr(ascii('#?RADIANCE\n\n+X 16 -Y 4\n'), LIMITS)).toThrow(
      /^HDR: line 3: the resolution line must be like "-Y 512 \+X 1024", got "\+X 16 -Y 4"$/,
    );
    expect(() => decodeHdr(ascii('#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n'), LIMITS)).toThrow(
      /^HDR: header line 2: unsupported "FORMAT=32-bit_rle_xyze"/,
    );
    expect(() => decodeHdr(ascii('P6\n'), LIMITS)).toThrow(/not a Radiance HDR file/);
    expect(() => decodeHdr(ascii('#?RADIANCE\nGAMMA=1\n'), LIMITS)).toThrow(
      /ends inside its header/,
    );
    const rle = (body: number[]) =>
      decodeHdr(
        concat(ascii('#?RADIANCE\n\n-Y 1 +X 8\n'), [2, 2, 0, 8], body, new Array(64).fill(0)),
        LIMITS,
      );
    expect(() => rle([128 + 9, 1])).toThrow(/^HDR: scanline 0: a run of 9 overruns the scanline$/);
    expect(() => rle([0])).toThrow(/^HDR: scanline 0: a run of length 0$/);
    expect(() =>
      decodeHdr(
        concat(ascii('#?RADIANCE\n\n-Y 1 +X 8\n'), [2, 2, 0, 9], new Array(64).fill(0)),
        LIMITS,
      ),
    ).toThrow(/^HDR: scanline 0: its run-length header says 9 texels, the image is 8 wide$/);
  });
});

describe('PFM', () => {
  it('reads colour PFMs, rows bottom to top, and refuses greyscale ones by name', () => {
    const rgb = Float32Array.from([1, 2, 3, 4, 5, 6]);
    const le = decodePfm(encodePfm(1, 2, rgb), LIMITS);
    expect(Array.from(le.rgb)).toEqual([1, 2, 3, 4, 5, 6]);
    expect(() => decodePfm(ascii('Pf\n1 1\n-1\n\0\0\0\0'), LIMITS)).toThrow(
      'PFM: grayscale PFM (Pf) is not supported; only colour (PF)',
    );
  });

  it('rejects a lying header and a size over the limit before allocating', () => {
    expect(() => decodePfm(ascii('PF\n16384 8192\n-1\n\0\0\0\0'), LIMITS)).toThrow(
      'PFM: truncated: the header says 16384 x 8192 pixels (1610612736 data bytes), the file has 4',
    );
    expect(() => decodePfm(ascii('PF\n16385 1\n-1\n'), LIMITS)).toThrow(
      'PFM: the image must be 1 x 1 to 16384 x 8192 pixels, got 16385 x 1',
    );
  });
});

describe('environment maps in scenes', () => {
  const scene = (env: unknown) =>
    JSON.stringify({
      format: 'pathwise-scene/1',
      camera: { position: [0, 0, -4], target: [0, 0, 0], up: [0, 1, 0], fovY: 40 },
      materials: {},
      shapes: [],
      environment: env,
    });
  const files = (bytes: Uint8Array): SceneFileReader => ({ read: async () => bytes });
  const problems = async (p: Promise<unknown>) => {
    try {
      await p;
    } catch (e) {
      if (e instanceof SceneError) return e.problems;
      throw e;
    }
    return [];
  };

  it('load with their defaults, and check every texel', async () => {
    const img = encodePfm(2, 1, Float32Array.from([1, 2, 3, 4, 5, 6]));
    const s = await loadScene(scene({ type: 'map', file: 'sky.pfm' }), files(img));
    expect(s.environment).toEqual([0, 0, 0]);
    expect(s.environmentMap!.scale).toEqual([1, 1, 1]);
    expect(s.environmentMap!.rotationY).toBe(0);
    expect(Array.from(s.environmentMap!.image!.rgb)).toEqual([1, 2, 3, 4, 5, 6]);
    const t = await loadScene(
      scene({ type: 'map', file: 'sky.pfm', scale: [1, 2, 3], rotationY: 90 }),
      files(img),
    );
    expect(t.environmentMap!.scale).toEqual([1, 2, 3]);
    expect(
      await problems(loadScene(scene({ type: 'map', file: 'sky.pfm', scale: 2e11 }), files(img))),
    ).toEqual([
      'environment.file "sky.pfm": texel (1, 0) b times scale (6 * 200000000000 = ' +
        '1200000000000) must be at most 1e12 (the radiance bound, so that sums of samples ' +
        'cannot overflow)',
    ]);
    const bad = encodePfm(2, 1, Float32Array.from([1, 2, 3, 4, -5, 6]));
    expect(await problems(loadScene(scene({ type: 'map', file: 'sky.pfm' }), files(bad)))).toEqual([
      'environment.file "sky.pfm": texel (1, 0) g must be a finite number >= 0, got -5',
    ]);
    const nan = encodePfm(1, 1, Float32Array.from([NaN, 0, 0]));
    expect(
      (await problems(loadScene(scene({ type: 'map', file: 'a.pfm' }), files(nan))))[0],
    ).toMatch(/texel \(0, 0\) r must be a finite number >= 0, got NaN/);
    expect(
      await problems(
        loadScene(
          scene({ type: 'map', file: 'a.hdr' }),
          files(ascii('#?RADIANCE\n\n-Y 8192 +X 16384\n')),
        ),
      ),
    ).toEqual([
      'environment.file "a.hdr": HDR: the header declares 16384 × 8192 texels, which need at least ' +
        '8552448 bytes, but only 0 follow it',
    ]);
  });

  it('reject bad environment objects by path', async () => {
    const p = async (env: unknown) => problems(loadScene(scene(env), files(new Uint8Array())));
    expect(await p({ type: 'map' })).toEqual([
      'environment.file is required but missing (a string)',
    ]);
    expect(await p({ type: 'image', file: 'a.hdr' })).toEqual([
      'environment.type must be "map", got "image"',
    ]);
    expect(await p({ type: 'map', file: 'a.png' })).toEqual([
      'environment.file must name an .hdr or .pfm file, got "a.png"',
    ]);
    expect(await p({ type: 'map', file: 'a.hdr', scale: -1 })).toEqual([
      'environment.scale must be >= 0, got -1',
    ]);
    expect(await p({ type: 'map', file: 'a.hdr', scale: [1, 1] })).toEqual([
      'environment.scale must be an array of 3 numbers, got [1, 1]',
    ]);
    expect(await p({ type: 'map', file: 'a.hdr', rotationY: '90' })).toEqual([
      'environment.rotationY must be a finite number, got the string "90" (numbers must not be quoted)',
    ]);
    expect(await p({ type: 'map', file: 'a.hdr', rotation: 90 })).toEqual([
      'environment.rotation is not a known key (did you mean rotationY?)',
    ]);
    expect(await p('sky')).toEqual([
      'environment must be [r, g, b] or an environment map object, got the string "sky"',
    ]);
  });
});
