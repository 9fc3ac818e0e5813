/**
 * PNG cases: a valid PNG (png-encode.ts: every colour type, bit depth, both interlace
 * methods) as the base-colour texture of a glTF model, and mutations of its chunks from the
 * rules of the PNG specification: IHDR lies (§11.2.2), PLTE rules (§11.2.3), chunk order
 * (§5.6), unknown critical chunks (§5.4), CRCs, short or excess image data, zlib bombs.
 */
import { deflateSync } from 'node:zlib';
import { concat } from './bytes.ts';
import { buildModel } from './gltf-doc.ts';
import { modelSample, type ModelEdit } from './gltf-host.ts';
import {
  ihdr,
  pngChunks,
  randomImage,
  rawData,
  serializeChunks,
  type Chunk,
  type PngImage,
} from './png-encode.ts';
import type { Rng } from './rng.ts';
import { zeroBomb } from './zlib-bomb.ts';
import type { Generator, Sample } from './types.ts';

type ChunkEdit = (chunks: Chunk[], img: PngImage, rng: Rng) => Chunk[] | Uint8Array;

function chunkEdits(img: PngImage, base: Chunk[]): ModelEdit[] {
  const e = (name: string, f: ChunkEdit, invalid = false): ModelEdit => ({
    name: `png:${name}`,
    invalid,
    edit: (m, rng) => {
      const out = f(
        base.map((c) => ({ ...c })),
        img,
        rng,
      );
      m.image = {
        mime: 'image/png',
        bytes: out instanceof Uint8Array ? out : serializeChunks(out),
      };
    },
  });
  const idx = (cs: Chunk[], t: string) => cs.findIndex((c) => c.type === t);
  const withIhdr = (cs: Chunk[], c: Chunk) => [c, ...cs.slice(1)];
  const idats = (cs: Chunk[]) => concat(cs.filter((c) => c.type === 'IDAT').map((c) => c.data));
  const replaceIdat = (cs: Chunk[], data: Uint8Array) => {
    const first = idx(cs, 'IDAT');
    return [
      ...cs.slice(0, first).filter((c) => c.type !== 'IDAT'),
      { type: 'IDAT', data },
      ...cs.slice(first).filter((c) => c.type !== 'IDAT'),
    ];
  };
  const { width: W, height: H, depth: D, colourType: CT, interlace: I } = img;
  return [
    e('ihdr-huge', (cs, _i, r) =>
      withIhdr(
        cs,
        ihdr(r.pick([2 ** 31 - 1, 65535, 16384]), r.pick([2 ** 31 - 1, 65535, 16384]), D, CT, I),
      ),
    ),
    e('ihdr-wider', (cs) => withIhdr(cs, ihdr(W + 1, H, D, CT, I))),
    e('ihdr-taller', (cs) => withIhdr(cs, ihdr(W, H + 5, D, CT, I))),
    e(
      'ihdr-zero',
      (cs, _i, r) => withIhdr(cs, r.chance(0.5) ? ihdr(0, H, D, CT, I) : ihdr(W, 0, D, CT, I)),
      true,
    ),
    e('ihdr-over-2^31', (cs) => withIhdr(cs, ihdr(2 ** 31, H, D, CT, I)), true),
    e(
      'ihdr-bad-depth',
      (cs, _i, r) => withIhdr(cs, ihdr(W, H, r.pick([0, 3, 5, 32, CT === 0 ? 7 : 4]), CT, I)),
      true,
    ),
    e(
      'ihdr-bad-colour-type',
      (cs, _i, r) => withIhdr(cs, ihdr(W, H, D, r.pick([1, 5, 7, 255]), I)),
      true,
    ),
    e(
      'ihdr-bad-methods',
      (cs, _i, r) => withIhdr(cs, ihdr(W, H, D, CT, I, r.chance(0.5) ? [1, 0] : [0, 1])),
      true,
    ),
    e('ihdr-bad-interlace', (cs) => withIhdr(cs, ihdr(W, H, D, CT, 2)), true),
    e('ihdr-short', (cs) => withIhdr(cs, { type: 'IHDR', data: cs[0].data.subarray(0, 9) }), true),
    e('ihdr-twice', (cs) => [cs[0], ...cs], true),
    e('ihdr-not-first', (cs) => [cs[1], cs[0], ...cs.slice(2)], true),
    e('interlace-flag-flipped', (cs) => withIhdr(cs, ihdr(W, H, D, CT, I ? 0 : 1))),
    e('plte-missing', (cs) => cs.filter((c) => c.type !== 'PLTE'), CT === 3),
    e(
      'plte-after-idat',
      (cs) => {
        const p = cs.find((c) => c.type === 'PLTE');
        if (!p) return cs;
        const rest = cs.filter((c) => c.type !== 'PLTE');
        rest.splice(rest.length - 1, 0, p);
        return rest;
      },
      CT === 3,
    ),
    e(
      'plte-one-byte-short',
      (cs) =>
        cs.map((c) =>
          c.type === 'PLTE' ? { ...c, data: c.data.subarray(0, c.data.length - 1) } : c,
        ),
      CT === 3,
    ),
    e(
      'plte-empty',
      (cs) => cs.map((c) => (c.type === 'PLTE' ? { ...c, data: new Uint8Array(0) } : c)),
      CT === 3,
    ),
    e(
      'plte-too-long',
      (cs) => cs.map((c) => (c.type === 'PLTE' ? { ...c, data: new Uint8Array(257 * 3) } : c)),
      CT === 3,
    ),
    e(
      'plte-in-grey',
      (cs) =>
        CT === 0 || CT === 4
          ? [cs[0], { type: 'PLTE', data: new Uint8Array(6) }, ...cs.slice(1)]
          : cs,
      CT === 0 || CT === 4,
    ),
    e('plte-two-entries', (cs) =>
      cs.map((c) => (c.type === 'PLTE' ? { ...c, data: c.data.subarray(0, 3) } : c)),
    ),
    e('trns-too-long', (cs) => [
      ...cs.slice(0, idx(cs, 'IDAT')),
      { type: 'tRNS', data: new Uint8Array(300) },
      ...cs.slice(idx(cs, 'IDAT')),
    ]),
    e('no-idat', (cs) => cs.filter((c) => c.type !== 'IDAT'), true),
    e('no-iend', (cs) => cs.filter((c) => c.type !== 'IEND')),
    e('iend-only', (cs) => [cs[0], cs[cs.length - 1]], true),
    e('bad-crc', (cs, _i, r) => {
      const k = r.int(cs.length);
      cs[k] = { ...cs[k], crc: 0xdeadbeef };
      return cs;
    }),
    e('length-huge', (cs, _i, r) => {
      const k = r.int(cs.length);
      cs[k] = { ...cs[k], length: r.pick([0x7fffffff, 0xffffffff, 1 << 30]) };
      return cs;
    }),
    e(
      'unknown-critical',
      (cs) => [...cs.slice(0, -1), { type: 'QXZW', data: new Uint8Array(8) }, cs[cs.length - 1]],
      true,
    ),
    e(
      'chunk-type-garbage',
      (cs) => [
        ...cs.slice(0, -1),
        { type: 'a\0b\x7f', data: new Uint8Array(2) },
        cs[cs.length - 1],
      ],
      true,
    ),
    e('idat-truncated', (cs, _i, r) => {
      const z = idats(cs);
      return replaceIdat(cs, z.subarray(0, r.int(z.length)));
    }),
    e('idat-short-data', (cs, i, r) => {
      const raw = rawData(i, r);
      return replaceIdat(cs, deflateSync(raw.subarray(0, Math.max(0, raw.length - r.range(1, 4)))));
    }),
    e('idat-excess-data', (cs, i, r) =>
      replaceIdat(cs, deflateSync(concat([rawData(i, r), new Uint8Array(r.range(1, 1000))]))),
    ),
    e(
      'filter-type-invalid',
      (cs, i, r) => {
        const raw = rawData(i, r);
        raw[0] = r.pick([5, 6, 127, 255]);
        return replaceIdat(cs, deflateSync(raw));
      },
      true,
    ),
    e('zlib-garbage', (cs, _i, r) =>
      replaceIdat(cs, new Uint8Array(Array.from({ length: r.range(2, 64) }, () => r.int(256)))),
    ),
    e('zlib-bad-adler', (cs) => {
      const z = idats(cs).slice();
      z[z.length - 1] ^= 0xff;
      return replaceIdat(cs, z);
    }),
    e('zlib-bomb', (cs, _i, r) => replaceIdat(cs, zeroBomb(r.pick([64, 256, 1024])))),
    e('huge-and-bomb', (cs, _i, r) => {
      // A header that truly needs the data: 16384 × 16384 grey, 8-bit, all zero (256 MiB).
      const side = r.pick([8192, 16384]);
      return [
        ihdr(side, side, 8, 0, 0),
        { type: 'IDAT', data: zeroBomb(Math.ceil((side * (side + 1)) / 2 ** 20)) },
        cs[cs.length - 1],
      ];
    }),
    e('signature-damaged', (cs, _i, r) => {
      const b = serializeChunks(cs);
      b[r.int(8)] ^= 0x20;
      return b;
    }),
  ];
}

export const pngGenerator: Generator = {
  format: 'png',
  generate(rng: Rng): Sample {
    const img = randomImage(rng);
    const chunks = pngChunks(img, rng);
    const model = buildModel(rng, { bytes: serializeChunks(chunks), mime: 'image/png' });
    const variant = `ct${img.colourType} ${img.depth}-bit${img.interlace ? ' adam7' : ''}`;
    return modelSample(rng, model, chunkEdits(img, chunks), variant);
  },
};
