/**
 * EXT_texture_webp and KHR_texture_basisu: headers read and budgeted before any
 * decoder is loaded; WebP decoded by libwebp (@jsquash/webp) and KTX2 transcoded by the
 * vendored Basis Universal transcoder, as the CLI does (src/cli/gltf-node.ts); the
 * fallback `source`, the warnings and the errors when a platform has no decoder; and
 * hostile headers as one error naming the image. Fixtures: tests/fixtures/compressed-textures/.
 */
import { readFileSync } from 'node:fs';
import { Document } from '@gltf-transform/core';
import { decode as decodePng } from 'fast-png';
import { describe, expect, it } from 'vitest';
import {
  nodeKtx2Transcoder,
  nodeWebpDecoder,
  nodeGltfDecoders,
} from '../../../src/cli/gltf-node.ts';
import { loadGltf, type GltfLoadOptions } from '../../../src/core/gltf/load.ts';
import type { GltfDecoders } from '../../../src/core/scene/format/gltf-model.ts';
import { readImageInfo } from '../../../src/core/texture/image-header.ts';
import { I_HEIGHT, I_WIDTH } from '../../../src/core/texture/texture-store.ts';
import { docWith, memoryOptions, png, quadPrimitive, toGltfFiles } from '../../helpers/gltf.ts';
import { ROOT } from '../../helpers/render.ts';

const fixture = (name: string): Uint8Array =>
  new Uint8Array(readFileSync(`${ROOT}tests/fixtures/compressed-textures/${name}`));

/** Getters that fail the test if called: what a file that needs no decoder must leave alone. */
const THROWING: GltfDecoders = {
  webp: () => {
    throw new Error('the WebP getter was called');
  },
  ktx2: () => {
    throw new Error('the KTX2 getter was called');
  },
};

/** Mean and largest absolute difference of two sample arrays of one length. */
function difference(a: ArrayLike<number>, b: ArrayLike<number>): { mean: number; max: number } {
  expect(a.length).toBe(b.length);
  let sum = 0;
  let max = 0;
  for (let i = 0; i < a.length; i++) {
    const d = Math.abs(a[i] - b[i]);
    sum += d;
    max = Math.max(max, d);
  }
  return { mean: sum / a.length, max };
}

const channelOf = (d: ArrayLike<number>, c: number): number[] =>
  Array.from(d).filter((_, i) => i % 4 === c);

/** A 2×2 box filter of RGBA8 w×h (w, h even): the level below, as a mip chain makes it. */
function halve(data: ArrayLike<number>, w: number, h: number): number[] {
  const out: number[] = [];
  for (let y = 0; y < h; y += 2)
    for (let x = 0; x < w; x += 2)
      for (let c = 0; c < 4; c++) {
        const at = (dx: number, dy: number) => data[4 * ((y + dy) * w + x + dx) + c];
        out.push((at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)) / 4);
      }
  return out;
}

describe('WebP and KTX2 headers (image-header.ts)', () => {
  it('reads the size of each layout without decoding', () => {
    const cases: [string, string, number, number][] = [
      ['pattern-lossless.webp', 'image/webp', 24, 16], // VP8L
      ['pattern-lossy.webp', 'image/webp', 24, 16], // VP8X + ALPH + VP8
      ['test-lossy.webp', 'image/webp', 256, 256], // VP8
      ['2d_uastc.ktx2', 'image/ktx2', 40, 40],
      ['2d_etc1s.ktx2', 'image/ktx2', 40, 40],
    ];
    for (const [name, mimeType, width, height] of cases)
      expect(readImageInfo(fixture(name), name)).toEqual({ mimeType, width, height });
  });

  it('refuses KTX2 that is not Basis Universal, naming the image', () => {
    expect(() => readImageInfo(fixture('2d_rgba8.ktx2'), 'images[2]')).toThrow(
      'images[2]: cannot decode KTX2: vkFormat 43 is not Basis Universal',
    );
  });
});

describe('WebP in Node (libwebp through @jsquash/webp)', () => {
  it('a lossless WebP decodes to exactly its PNG', async () => {
    const webp = await nodeWebpDecoder();
    const img = await webp(fixture('pattern-lossless.webp'));
    const ref = decodePng(fixture('pattern.png'));
    expect([img.width, img.height, img.channels, img.depth]).toEqual([24, 16, 4, 8]);
    expect(Array.from(img.data)).toEqual(Array.from(ref.data));
  });

  it('a lossy WebP (quality 90) stays close to its PNG', async () => {
    const img = await (await nodeWebpDecoder())(fixture('pattern-lossy.webp'));
    const ref = decodePng(fixture('pattern.png'));
    expect([img.width, img.height]).toEqual([24, 16]);
    const mean = (c: number) => difference(channelOf(img.data, c), channelOf(ref.data, c)).mean;
    // libwebp is deterministic, so these are the errors of this file, not a spread:
    // observed 4.3 (R) and 4.0 (G) on the gradients; 26.8 on B, whose 4×4 checker VP8's
    // 4:2:0 chroma blurs; alpha is coded losslessly (alpha_quality 100): 0. The same
    // decode flipped upside down is off by 136 (G) and 135 (B), so the bounds (about
    // twice and 1.5 times the observed) tell a right decode from a wrong one.
    expect(mean(0)).toBeLessThan(8);
    expect(mean(1)).toBeLessThan(8);
    expect(mean(2)).toBeLessThan(40);
    expect(mean(3)).toBe(0);
  });
});

describe('KTX2 in Node (the vendored Basis Universal transcoder)', () => {
  it('UASTC and ETC1S of one image agree; a mip level is the box-filtered level above', async () => {
    const ktx2 = await nodeKtx2Transcoder();
    const uastc = await ktx2(fixture('2d_uastc.ktx2'), 0);
    const etc1s = await ktx2(fixture('2d_etc1s.ktx2'), 0);
    expect([uastc.width, uastc.height, etc1s.width, etc1s.height]).toEqual([40, 40, 40, 40]);
    // Not blank: a gold ground (186, 151, 0) with white shapes, opaque.
    const red = channelOf(uastc.data, 0);
    expect(Math.min(...red)).toBeLessThan(200);
    expect(Math.max(...red)).toBe(255);
    expect(Math.min(...channelOf(uastc.data, 3))).toBe(255);
    // Two codecs of one source, deterministic: UASTC is near-lossless, ETC1S coarse.
    // Observed mean difference 7.8; ETC1S flipped upside down 21.7, transposed 18.2.
    expect(difference(uastc.data, etc1s.data).mean).toBeLessThan(12);
    // Level 1 against level 0 box-filtered (the encoder's own mip filter is not a box):
    // observed 3.8; from level 0 flipped 20.3, transposed 14.8.
    const level1 = await ktx2(fixture('2d_uastc.ktx2'), 1);
    expect([level1.width, level1.height]).toEqual([20, 20]);
    expect(difference(level1.data, halve(uastc.data, 40, 40)).mean).toBeLessThan(8);
  });
});

const EXTENSION = { webp: 'EXT_texture_webp', ktx2: 'KHR_texture_basisu' } as const;

/**
 * A quad whose base colour is `image`, a .gltf and its files. With `extension`, the
 * texture names the image through that extension alone (no fallback `source`), and the
 * file requires it.
 */
async function quadFiles(image: Uint8Array, mime: string, extension?: 'webp' | 'ktx2') {
  const doc = new Document();
  const tex = doc.createTexture().setImage(image).setMimeType(mime).setURI('image.bin');
  const mat = doc.createMaterial().setBaseColorTexture(tex);
  const files = await toGltfFiles(docWith(doc, quadPrimitive(doc).setMaterial(mat)), 'model');
  const json = JSON.parse(new TextDecoder().decode(files.get('model.gltf')!));
  json.images[0].mimeType = mime;
  if (extension !== undefined) {
    const name = EXTENSION[extension];
    json.textures[0] = { extensions: { [name]: { source: 0 } } };
    json.extensionsUsed = [name];
    json.extensionsRequired = [name];
  }
  return { files, json };
}

async function load(
  files: Map<string, Uint8Array>,
  json: Record<string, unknown>,
  decoders: GltfDecoders | undefined,
  extra: Partial<GltfLoadOptions> = {},
) {
  const bytes = new TextEncoder().encode(JSON.stringify(json));
  return loadGltf(bytes, 'model.gltf', { ...(await memoryOptions(files)), decoders, ...extra });
}

describe('glTF files with compressed textures', () => {
  it('a file without them calls no decoder getter', async () => {
    const { files, json } = await quadFiles(
      png(2, 2, () => [9, 9, 9, 255]),
      'image/png',
    );
    const model = await load(files, json, THROWING);
    expect(Array.from(model.textures.info)).toEqual([0, 2, 2]);
  });

  it('EXT_texture_webp required: decoded with a decoder, one error without', async () => {
    const { files, json } = await quadFiles(fixture('pattern-lossless.webp'), 'image/webp', 'webp');
    expect(json.extensionsRequired).toEqual(['EXT_texture_webp']);
    // Only the WebP getter is called.
    const model = await load(files, json, { webp: nodeWebpDecoder, ktx2: THROWING.ktx2 });
    expect(model.warnings).toEqual([]);
    expect([model.textures.info[I_WIDTH], model.textures.info[I_HEIGHT]]).toEqual([24, 16]);
    // Texel (0, 0) is red 0, green 0, alpha 255: linear 16-bit.
    expect(Array.from(model.textures.texels.subarray(0, 4))).toEqual([
      0,
      0,
      expect.any(Number),
      65535,
    ]);
    await expect(load(files, json, {})).rejects.toThrow(
      'extensionsRequired: the file requires "EXT_texture_webp", and this platform has no WebP decoder',
    );
  });

  it('only used, with a PNG fallback: the fallback and one warning without a decoder', async () => {
    const { files, json } = await quadFiles(fixture('2d_uastc.ktx2'), 'image/ktx2', 'ktx2');
    json.extensionsRequired = [];
    json.images.push({ uri: 'fallback.png' });
    files.set(
      'fallback.png',
      png(3, 3, () => [200, 100, 50, 255]),
    );
    json.textures[0].source = 1;
    const withDecoder = await load(files, json, nodeGltfDecoders());
    expect(Array.from(withDecoder.textures.info)).toEqual([0, 40, 40]);
    const without = await load(files, json, { webp: nodeGltfDecoders().webp });
    expect(Array.from(without.textures.info)).toEqual([0, 3, 3]);
    expect(without.warnings).toEqual([
      'textures[0]: its KTX2 (Basis Universal) image (KHR_texture_basisu) needs a decoder this platform lacks; its fallback source is used',
    ]);
    delete json.textures[0].source;
    const none = await load(files, json, undefined);
    expect(none.textures.info.length).toBe(0);
    expect(none.warnings).toEqual([
      'textures[0]: its KTX2 (Basis Universal) image (KHR_texture_basisu) needs a decoder this platform lacks, and it has no fallback source; the materials that use it use their factors alone',
    ]);
  });

  it('KTX2 over the texture memory left: the largest level that fits, with a warning', async () => {
    const { files, json } = await quadFiles(fixture('2d_etc1s.ktx2'), 'image/ktx2', 'ktx2');
    // 40² × 8 bytes = 12800 do not fit in 5000; 20² × 8 = 3200 do.
    const model = await load(files, json, nodeGltfDecoders(), { textureLimitBytes: 5000 });
    expect(Array.from(model.textures.info)).toEqual([0, 20, 20]);
    expect(model.warnings).toEqual([
      'images[0] (materials[0].baseColorTexture): KTX2 level 0 (40×40) does not fit the texture memory limit; level 1 (20×20) is used',
    ]);
    await expect(load(files, json, nodeGltfDecoders(), { textureLimitBytes: 4 })).rejects.toThrow(
      'images[0] (materials[0].baseColorTexture): decoded textures would need',
    );
  });
});

describe('hostile compressed textures: one error naming the image, no decoder loaded', () => {
  const what = 'images[0] (materials[0].baseColorTexture)';
  /** The fixture with `edit` applied, in a file that requires its extension. */
  async function hostile(
    name: string,
    ext: 'webp' | 'ktx2',
    edit: (b: Uint8Array) => Uint8Array,
    decoders = THROWING,
  ) {
    const bytes = edit(fixture(name).slice());
    const { files, json } = await quadFiles(bytes, `image/${ext}`, ext);
    return load(files, json, decoders);
  }
  const setU32 = (b: Uint8Array, at: number, v: number) =>
    new DataView(b.buffer).setUint32(at, v, true);

  it('WebP: a VP8 frame claiming 16383 × 16383 (1 GiB of RGBA8)', async () => {
    await expect(
      hostile('test-lossy.webp', 'webp', (b) => {
        const at = b.findIndex((v, i) => v === 0x9d && b[i + 1] === 0x01 && b[i + 2] === 0x2a);
        b[at + 3] = b[at + 5] = 0xff;
        b[at + 4] = b[at + 6] = 0x3f;
        return b;
      }),
    ).rejects.toThrow(
      `${what}: decoded textures would need 2.00 GiB, over the texture memory limit`,
    );
  });

  it('WebP: truncated, and a VP8X canvas that is not its frame', async () => {
    await expect(hostile('test-lossy.webp', 'webp', (b) => b.subarray(0, 300))).rejects.toThrow(
      `${what}: cannot decode WebP: truncated: the RIFF header says 6848 bytes, the file has 300`,
    );
    await expect(
      hostile('pattern-lossy.webp', 'webp', (b) => {
        b[24] = 99; // canvas width − 1
        return b;
      }),
    ).rejects.toThrow(/cannot decode WebP: the frame at byte \d+ is 24×16, the canvas 100×16/);
  });

  it('KTX2: a size that lies, level lengths that lie, a level past the end', async () => {
    await expect(
      hostile('2d_uastc.ktx2', 'ktx2', (b) => {
        setU32(b, 20, 16384);
        setU32(b, 24, 16384);
        return b;
      }),
    ).rejects.toThrow(
      `${what}: cannot decode KTX2: level 0 (16384×16384) declares 1600 bytes of UASTC blocks; 4096×4096 blocks need 268435456`,
    );
    await expect(
      hostile('2d_uastc.ktx2', 'ktx2', (b) => {
        setU32(b, 80 + 24 + 8, 300); // level 1 byteLength
        return b;
      }),
    ).rejects.toThrow(`${what}: cannot decode KTX2: level 1 (20×20) declares 300 bytes`);
    await expect(hostile('2d_uastc.ktx2', 'ktx2', (b) => b.subarray(0, 2000))).rejects.toThrow(
      `${what}: cannot decode KTX2: level 0 (1600 bytes at 960) ends past the end of the 2000-byte file`,
    );
    await expect(
      hostile('2d_etc1s.ktx2', 'ktx2', (b) => {
        setU32(b, 80 + 8, 20); // level 0 byteLength, shorter than its slices
        return b;
      }),
    ).rejects.toThrow(`${what}: cannot decode KTX2: level 0's slices`);
  });

  it('damaged data behind a sound header: the decoder error, naming the image', async () => {
    const wipe = (from: number) => (b: Uint8Array) => b.fill(0xff, from);
    await expect(
      hostile('pattern-lossless.webp', 'webp', wipe(30), nodeGltfDecoders()),
    ).rejects.toThrow(`${what}: cannot decode WebP: the decoder stopped (Decoding error)`);
    await expect(
      hostile(
        '2d_etc1s.ktx2',
        'ktx2',
        (b) => b.map((v, i) => (i >= 895 ? v ^ 0xa5 : v)),
        nodeGltfDecoders(),
      ),
    ).rejects.toThrow(
      `${what}: cannot decode KTX2: level 0 does not transcode (damaged ETC1S data)`,
    );
  });
});
