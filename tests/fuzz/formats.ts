/**
 * The table of file formats under the hostile-input contract (issue 9, point 3). Each
 * entry gives a decoder, a few small valid files, and generators of the three classic
 * attacks: truncated files, headers that lie (claiming 2^31 vertices, 10^9 x 10^9 pixels,
 * a buffer past the end), and NaN/Inf inside binary data. tests/fuzz/formats.test.ts runs
 * every entry through the same checks, plus random byte mutations (fast-check):
 *
 *   decode(bytes) returns a value that passes `check` (finite numbers, consistent sizes),
 *   or throws FormatError with one printable line naming the format; nothing else (no
 *   RangeError from a DataView, no allocation sized by an unchecked header, no hang).
 *
 * To add a format (OBJ, PLY, HDR, glTF/GLB, .film), append one entry: see README.md here.
 */
import { readFileSync } from 'node:fs';
import { expect } from 'vitest';
import {
  Film,
  crc32,
  decodeFilmFile,
  decodeHdr,
  decodePfm,
  encodeFilmFile,
  encodeHdr,
  encodePfm,
  type FilmFile,
  type FilmHeader,
  type PfmImage,
} from '../../src/core/index.ts';
import { GM_ATTENUATION_DISTANCE, GM_STRIDE } from '../../src/core/gltf-material/material-table.ts';
import { type GltfModel, loadGltf } from '../../src/core/gltf/load.ts';
import {
  decodeImageJs,
  decodeJpegBytes,
  decodePngBytes,
} from '../../src/core/texture/decode-js.ts';
import type { DecodedImage } from '../../src/core/texture/decoded-image.ts';
import { readKtx2Info } from '../../src/core/texture/ktx2-header.ts';
import { readWebpInfo } from '../../src/core/texture/webp-header.ts';
import {
  IEND,
  ihdr,
  jpegImage,
  jpegWithSize,
  pngChunk,
  pngFile,
  pngImage,
  pngIndexed,
  pngInterlacedGrey,
  rawRows,
  zlib,
} from './image-samples.ts';
import { POSITION_Y2_OFFSET, quadGlb, quadGltfDataUri } from './gltf-samples.ts';
import type { RawMesh } from '../../src/core/geometry/mesh-data.ts';
import { parseObj } from '../../src/core/io/obj.ts';
import { parsePly } from '../../src/core/io/ply.ts';

export interface FormatEntry {
  /** As the decoder's FormatError names it (error.format), e.g. "PFM". */
  name: string;
  /** Decodes bytes; throws (or rejects with) FormatError on bad input. */
  decode: (bytes: Uint8Array) => unknown;
  /** Asserts that a decoded value is sane: finite numbers, sizes that agree. */
  check: (value: unknown) => void;
  /** Small valid files (a few hundred bytes each keeps the prefix sweep fast). */
  samples: () => Uint8Array[];
  /** Files whose header claims more than the data holds, or absurd sizes. */
  lyingHeaders: () => { name: string; bytes: Uint8Array; message?: RegExp }[];
  /** Valid files with NaN or Inf written into their data. */
  nonFinite: () => { name: string; bytes: Uint8Array; message?: RegExp }[];
  /** Other hostile files with the message they must give. */
  others?: () => { name: string; bytes: Uint8Array; message?: RegExp }[];
  /**
   * For text formats without a terminator (OBJ, ASCII PLY): whether a prefix of a sample
   * is itself a complete file, to be decoded rather than rejected.
   */
  validPrefix?: (prefix: Uint8Array) => boolean;
}

const ascii = (s: string) => Uint8Array.from(s, (c) => c.charCodeAt(0));
const concat = (...parts: Uint8Array[]) => {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
};

/** A small PFM image with distinct values. */
function pfmSample(width: number, height: number): Uint8Array {
  const rgb = Float32Array.from({ length: width * height * 3 }, (_, i) => i * 0.25 - 1);
  return encodePfm(width, height, rgb);
}

/** The same image, big-endian (positive scale). */
function pfmBigEndian(width: number, height: number): Uint8Array {
  const header = ascii(`PF\n${width} ${height}\n1.0\n`);
  const data = new DataView(new ArrayBuffer(width * height * 12));
  for (let i = 0; i < width * height * 3; i++) data.setFloat32(i * 4, i * 0.5, false);
  return concat(header, new Uint8Array(data.buffer));
}

/** The PFM file with float `index` of its data replaced by `value`. */
function pfmWithValue(value: number, index: number): Uint8Array {
  const bytes = pfmSample(3, 2);
  const header = 'PF\n3 2\n-1.0\n'.length;
  new DataView(bytes.buffer).setFloat32(header + index * 4, value, true);
  return bytes;
}

/** A small `.film` (pathwise-film/1): `width`×`height`, samples [2, 5) of a 5-spp render. */
function filmSample(width: number, height: number, spoil?: (f: Film) => void): Uint8Array {
  const film = new Film(width, height);
  for (let s = 2; s < 5; s++)
    for (let y = 0; y < height; y++)
      for (let x = 0; x < width; x++) film.addSample(x, y, 0.25 * s + x, y * 1e-3, 1e4 * s);
  spoil?.(film);
  return encodeFilmFile(filmHeader(width, height), film);
}

/** filmSample as `pathwise-film/2`, with albedo and normal planes. */
function filmSampleAux(width: number, height: number, spoil?: (f: Film) => void): Uint8Array {
  const film = new Film(width, height, undefined, 0, 0, true);
  for (let s = 2; s < 5; s++)
    for (let y = 0; y < height; y++)
      for (let x = 0; x < width; x++)
        film.addSampleAux(
          x,
          y,
          { lr: 0.25 * s + x, lg: y * 1e-3, lb: 1e4 * s },
          { ar: 0.1 * s, ag: 0.5, ab: 1, nx: 0.6, ny: -0.8, nz: 0 },
        );
  spoil?.(film);
  return encodeFilmFile(
    { ...filmHeader(width, height), format: 'pathwise-film/2', aux: ['albedo', 'normal'] },
    film,
  );
}

function filmHeader(width: number, height: number): FilmHeader {
  return {
    format: 'pathwise-film/1',
    renderer: 'pathwise 0.1.0',
    scene_sha256: '0'.repeat(64),
    settings: { width, height, maxBounces: 4, seed: 7, sampler: 'sobol', estimator: 'nee-mis' },
    key: '1'.repeat(64),
    scale_bits: 40,
    spp: 5,
    ranges: [[2, 5]],
    stats: { paths: width * height * 3, segments: 0, rejected: 0 },
  };
}

/**
 * A valid-looking `.film` with another header (an object, or raw text), the checksum
 * recomputed so that only the header lies.
 */
function filmWithHeader(header: unknown, payloadOf = filmSample(2, 1)): Uint8Array {
  const view = new DataView(payloadOf.buffer, payloadOf.byteOffset);
  const oldLength = view.getUint32(16, true);
  const payload = payloadOf.subarray(Math.ceil((20 + oldLength) / 8) * 8, payloadOf.length - 4);
  const json = ascii(typeof header === 'string' ? header : JSON.stringify(header));
  const start = Math.ceil((20 + json.length) / 8) * 8;
  const out = new Uint8Array(start + payload.length + 4);
  out.set(ascii('pathwise-film/1\n'));
  new DataView(out.buffer).setUint32(16, json.length, true);
  out.set(json, 20);
  out.set(payload, start);
  new DataView(out.buffer).setUint32(out.length - 4, crc32(out.subarray(0, out.length - 4)), true);
  return out;
}

export const FORMATS: FormatEntry[] = [
  {
    name: 'PFM',
    decode: (bytes) => decodePfm(bytes),
    check: (value) => {
      const img = value as PfmImage;
      expect(Number.isInteger(img.width) && img.width > 0).toBe(true);
      expect(Number.isInteger(img.height) && img.height > 0).toBe(true);
      expect(img.rgb.length).toBe(img.width * img.height * 3);
      expect(img.rgb.every(Number.isFinite)).toBe(true);
    },
    samples: () => [pfmSample(3, 2), pfmSample(1, 1), pfmBigEndian(2, 3)],
    lyingHeaders: () => [
      {
        name: '10^9 x 10^9 pixels',
        bytes: concat(ascii('PF\n1000000000 1000000000\n-1.0\n'), new Uint8Array(24)),
        message: /must be 1 x 1 to 65536 x 65536 pixels, got 1000000000 x 1000000000/,
      },
      {
        name: 'more pixels than the data holds',
        bytes: concat(ascii('PF\n4000 4000\n-1.0\n'), new Uint8Array(36)),
        message:
          /truncated: the header says 4000 x 4000 pixels \(192000000 data bytes\), the file has 36/,
      },
      {
        name: 'fewer pixels than the data holds',
        bytes: concat(pfmSample(3, 2), new Uint8Array(12)),
        message: /12 bytes after the 3 x 2 pixels/,
      },
      {
        name: 'hexadecimal width',
        bytes: concat(ascii('PF\n0x10 1\n-1.0\n'), new Uint8Array(192)),
        message: /width and height must be decimal integers, got "0x10" and "1"/,
      },
      {
        name: 'zero width',
        bytes: ascii('PF\n0 1\n-1.0\n'),
        message: /must be 1 x 1 to .*got 0 x 1/,
      },
      {
        name: 'negative height',
        bytes: ascii('PF\n1 -2\n-1.0\n'),
        message: /decimal integers, got "1" and "-2"/,
      },
      {
        name: 'scale NaN',
        bytes: concat(ascii('PF\n1 1\nnan\n'), new Uint8Array(12)),
        message: /the scale must be a non-zero number .*got "nan"/,
      },
      {
        name: 'scale 0',
        bytes: concat(ascii('PF\n1 1\n0\n'), new Uint8Array(12)),
        message: /the scale must be a non-zero number/,
      },
      {
        name: 'a header of a million digits',
        bytes: ascii('PF\n' + '9'.repeat(1_000_000)),
        message: /the header is longer than 256 bytes/,
      },
    ],
    nonFinite: () => [
      { name: 'NaN in red', bytes: pfmWithValue(NaN, 0), message: /pixel \(0, 1\) r is NaN/ },
      {
        name: '+Inf in blue',
        bytes: pfmWithValue(Infinity, 5),
        message: /pixel \(1, 1\) b is Infinity/,
      },
      {
        name: '-Inf, top row',
        bytes: pfmWithValue(-Infinity, 10),
        message: /pixel \(0, 0\) g is -Infinity/,
      },
    ],
    others: () => [
      {
        name: 'empty file',
        bytes: new Uint8Array(0),
        message: /truncated: the file ends inside its header/,
      },
      {
        name: 'grayscale',
        bytes: concat(ascii('Pf\n1 1\n-1\n'), new Uint8Array(4)),
        message: /grayscale PFM \(Pf\) is not supported/,
      },
      {
        name: 'not a PFM',
        bytes: ascii('P6\n1 1\n255\n\u0000\u0000\u0000'),
        message: /not a colour PFM: it starts with "P6"/,
      },
      {
        name: 'escape codes in the magic',
        bytes: ascii('\u001b[2J 1 1 -1\n'),
        message: /it starts with "\\u001b\[2J"/,
      },
    ],
  },
  {
    name: 'pathwise-film/1',
    decode: (bytes) => decodeFilmFile(bytes),
    check: (value) => {
      const { header, film } = value as FilmFile;
      expect(film.width).toBe(header.settings.width);
      expect(film.rows).toBe(header.settings.height);
      expect(film.sums.every(Number.isFinite)).toBe(true);
      expect(film.hi.every(Number.isInteger)).toBe(true);
      expect(film.lo.every(Number.isInteger)).toBe(true);
      if (film.auxHi !== null) {
        expect(film.auxHi.every(Number.isInteger)).toBe(true);
        expect(film.auxLo!.every(Number.isInteger)).toBe(true);
      }
    },
    // Version 2 (albedo and normal) is read by the same decoder, under the same contract.
    samples: () => [filmSample(2, 1), filmSample(1, 1), filmSampleAux(1, 1)],
    lyingHeaders: () => {
      const h = filmHeader(2, 1);
      return [
        {
          name: '10^6 x 10^6 pixels',
          bytes: filmWithHeader({ ...h, settings: { ...h.settings, width: 1e6, height: 1e6 } }),
          message: /settings.width \* settings.height must be at most 16777216 pixels/,
        },
        {
          name: 'more pixels than the data holds',
          bytes: filmWithHeader({ ...h, settings: { ...h.settings, width: 4000, height: 4000 } }),
          message: /truncated: \d+ bytes, but a 4000×4000 film needs 1088000\d+/,
        },
        {
          name: 'a header length of 2^32 - 1',
          bytes: (() => {
            const b = filmSample(2, 1);
            new DataView(b.buffer).setUint32(16, 0xffffffff, true);
            return b;
          })(),
          message: /header length 4294967295 is outside \[1, 1048576\]/,
        },
        {
          name: 'more samples in a pixel than its ranges',
          bytes: filmWithHeader({ ...h, ranges: [[4, 5]], stats: { ...h.stats, paths: 2 } }),
          message: /pixel \(0, 0\) has 3 samples, more than the 1 of its ranges/,
        },
        {
          name: 'stats that do not add up',
          bytes: filmWithHeader({ ...h, stats: { ...h.stats, paths: 7 } }),
          message: /stats do not add up/,
        },
        {
          name: 'a range past the total',
          bytes: filmWithHeader({ ...h, ranges: [[2, 9]] }),
          message: /ranges\[0\]\[1\] must be an integer in \[3, 5\], got 9/,
        },
      ];
    },
    nonFinite: () => [
      {
        name: 'NaN in a high limb',
        bytes: filmSample(2, 1, (f) => (f.hi[1] = NaN)),
        message: /pixel \(0, 0\) channel G: invalid exact sum \(NaN/,
      },
      {
        name: '+Inf in a low limb',
        bytes: filmSample(2, 1, (f) => (f.lo[6] = Infinity)),
        message: /pixel \(1, 0\) channel B: invalid exact sum/,
      },
      {
        name: 'NaN in an albedo high limb (pathwise-film/2)',
        bytes: filmSampleAux(1, 1, (f) => (f.auxHi![1] = NaN)),
        message: /pixel \(0, 0\) albedo channel G: invalid exact sum \(NaN/,
      },
      {
        name: '-Inf in a normal low limb (pathwise-film/2)',
        bytes: filmSampleAux(1, 1, (f) => (f.auxLo![5] = -Infinity)),
        message: /pixel \(0, 0\) normal channel Z: invalid exact sum/,
      },
      {
        name: 'NaN in the header',
        bytes: filmWithHeader(JSON.stringify(filmHeader(2, 1)).replace('"seed":7', '"seed":NaN')),
        message: /header is not valid JSON/,
      },
    ],
    others: () => [
      {
        name: 'a flipped payload bit',
        bytes: (() => {
          const b = filmSample(2, 1);
          b[b.length - 20] ^= 1;
          return b;
        })(),
        message: /checksum mismatch .* the file is corrupt/,
      },
      {
        name: 'a PFM named .film',
        bytes: pfmSample(2, 1),
        message: /not a .film file: it does not start with "pathwise-film\/1"/,
      },
      {
        name: 'a fractional limb',
        bytes: filmSample(1, 1, (f) => (f.lo[0] = 0.5)),
        message: /pixel \(0, 0\) channel R: invalid exact sum/,
      },
    ],
  },
  {
    name: 'glTF',
    decode: (bytes) =>
      loadGltf(bytes, 'model.glb', {
        reader: null,
        decodeImage: decodeImageJs,
        generateTangents: null,
      }),
    check: (value) => {
      const m = value as GltfModel;
      const vertices = m.positions.length / 3;
      expect(m.positions.every(Number.isFinite)).toBe(true);
      expect(m.indices.length % 3).toBe(0);
      expect(m.indices.every((i) => i < vertices)).toBe(true);
      expect(m.triangleMaterial.length).toBe(m.indices.length / 3);
      expect(m.triangleMaterial.every((k) => k < m.materials.length / GM_STRIDE)).toBe(true);
      // Every number finite, but KHR_materials_volume's attenuationDistance, whose
      // default (no absorption) is +∞ by the specification; never NaN or −∞.
      expect(
        m.materials.every((x, i) =>
          i % GM_STRIDE === GM_ATTENUATION_DISTANCE ? x > 0 : Number.isFinite(x),
        ),
      ).toBe(true);
      for (const a of [m.normals, m.uv0, m.uv1, m.colors, m.tangents]) {
        if (a !== null) expect(a.every(Number.isFinite)).toBe(true);
      }
    },
    samples: () => [quadGlb(), quadGlb({ texture: true }), quadGltfDataUri()],
    lyingHeaders: () => [
      {
        name: 'GLB length past the end of the file',
        bytes: (() => {
          const b = quadGlb();
          new DataView(b.buffer).setUint32(8, b.length + 100, true);
          return b;
        })(),
        message: /^glTF: GLB header: says \d+ bytes, but the file has \d+/,
      },
      {
        name: 'an accessor past the end of its buffer view',
        bytes: quadGlb({ edit: (j) => ((j.accessors as { count: number }[])[0].count = 1e6) }),
        message: /^glTF: accessors\[0\]: needs 12000000 bytes of bufferViews\[0\]/,
      },
      {
        name: 'a buffer view past the end of its buffer',
        bytes: quadGlb({
          edit: (j) => ((j.bufferViews as { byteLength: number }[])[3].byteLength = 1e9),
        }),
        message: /^glTF: bufferViews\[3\]: ends at byte \d+, past the end of buffers\[0\]/,
      },
      {
        name: 'an index out of range',
        bytes: quadGlb({
          edit: (_, bin) => new DataView(bin.buffer).setUint16(128 + 4, 60000, true),
        }),
        message:
          /^glTF: meshes\[0\]\.primitives\[0\]\.indices: index 60000 at position 2 is out of range/,
      },
      {
        name: '60 million indices (an index bomb)',
        bytes: quadGlb({
          edit: (j) => ((j.accessors as { count: number }[])[3].count = 60_000_000),
        }),
        message: /^glTF: scene: uses meshes of more than 10,000,000 distinct triangles, the limit$/,
      },
      {
        name: 'a texture claiming 16000 x 16000 texels',
        bytes: quadGlb({
          texture: true,
          edit: (_, bin) => {
            // The PNG starts after positions, normals, uvs and indices (48 + 48 + 32 + 12 bytes).
            new DataView(bin.buffer).setUint32(140 + 16, 16000);
            new DataView(bin.buffer).setUint32(140 + 20, 16000);
          },
        }),
        message: /over the texture memory limit of 1\.00 GiB/,
      },
    ],
    nonFinite: () => [
      {
        name: 'NaN in a position',
        bytes: quadGlb({
          edit: (_, bin) => new DataView(bin.buffer).setFloat32(POSITION_Y2_OFFSET, NaN, true),
        }),
        message:
          /^glTF: meshes\[0\]\.primitives\[0\]\.attributes\.POSITION: vertex 2 has a non-finite value$/,
      },
      {
        name: 'Inf in a normal',
        bytes: quadGlb({
          edit: (_, bin) => new DataView(bin.buffer).setFloat32(48 + 8, Infinity, true),
        }),
        message: /attributes\.NORMAL: vertex 0 has a non-finite value$/,
      },
      {
        name: 'NaN in a texture coordinate',
        bytes: quadGlb({
          edit: (_, bin) => new DataView(bin.buffer).setFloat32(96 + 12, NaN, true),
        }),
        message: /attributes\.TEXCOORD_0: vertex 1 has a non-finite value$/,
      },
      {
        name: 'an infinite emission factor (1e400 in the JSON)',
        bytes: quadGlb({ edit: (j) => (j.materials = [{ emissiveFactor: [Infinity, 0, 0] }]) }),
        message: /^glTF: materials\[0\]\.emissiveFactor: must be 3 numbers in \[0, 1\]$/,
      },
    ],
    others: () => [
      { name: 'empty file', bytes: new Uint8Array(0), message: /^glTF: JSON: line 1, column 1: / },
      {
        name: 'glTF 1.0',
        bytes: ascii('{"asset": {"version": "1.0"}}'),
        message: /glTF "1\.0" is not supported, only 2\.x$/,
      },
      {
        name: 'a required extension pathwise lacks',
        bytes: quadGlb({ edit: (j) => (j.extensionsRequired = ['KHR_draco_mesh_compression']) }),
        message: /requires "KHR_draco_mesh_compression", which pathwise does not support$/,
      },
      {
        name: 'a node cycle',
        bytes: quadGlb({
          edit: (j) => (j.nodes = [{ mesh: 0 }, { children: [2] }, { children: [1] }]),
        }),
        message: /is its own ancestor \(the node hierarchy has a cycle\)$/,
      },
      {
        name: 'an external file with no reader',
        bytes: ascii('{"asset":{"version":"2.0"},"buffers":[{"uri":"a.bin","byteLength":4}]}'),
        message:
          /^glTF: buffers\[0\]\.uri: names the file "a\.bin", but no way to read files beside the model was given$/,
      },
    ],
  },
];

const MESH_LIMITS = { maxTriangles: 10_000_000, sceneTriangles: 10_000_000 };

function checkMesh(value: unknown): void {
  const m = value as RawMesh;
  expect(m.positions.length % 3).toBe(0);
  expect(m.indices.length % 3).toBe(0);
  expect(m.positions.every(Number.isFinite)).toBe(true);
  const vertices = m.positions.length / 3;
  expect(m.indices.every((i) => i < vertices)).toBe(true);
  if (m.normals !== null) {
    expect(m.normals.length).toBe(m.positions.length);
    expect(m.normals.every(Number.isFinite)).toBe(true);
  }
}

/** A binary PLY: header, then the body written by `body`. */
function plyBinary(vertices: number, faces: number, body: (v: DataView) => number, size: number) {
  const header = ascii(
    `ply\nformat binary_little_endian 1.0\nelement vertex ${vertices}\n` +
      'property float x\nproperty float y\nproperty float z\n' +
      `element face ${faces}\nproperty list uchar int vertex_indices\nend_header\n`,
  );
  const data = new DataView(new ArrayBuffer(size));
  const n = body(data);
  return concat(header, new Uint8Array(data.buffer, 0, n));
}

/** The unit square as a binary PLY, with float `index` of the positions set to `value`. */
function plySquare(value = 0, index = -1): Uint8Array {
  return plyBinary(
    4,
    1,
    (v) => {
      const p = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0];
      if (index >= 0) p[index] = value;
      p.forEach((x, i) => v.setFloat32(4 * i, x, true));
      v.setUint8(48, 4);
      [0, 1, 2, 3].forEach((x, i) => v.setInt32(49 + 4 * i, x, true));
      return 65;
    },
    65,
  );
}

function hdrSample(width: number, height: number): Uint8Array {
  const rgb = Float32Array.from({ length: width * height * 3 }, (_, i) => (i % 7) * 0.25);
  return encodeHdr(width, height, rgb);
}

FORMATS.push(
  {
    name: 'OBJ',
    decode: (bytes) => parseObj(bytes, MESH_LIMITS),
    check: checkMesh,
    // Prefixes ending after the last face's last vertex (its index, its newline) are
    // whole files; so are the prefixes cut inside a trailing "//1" (a vertex with its
    // normal field cut off is a vertex without one).
    validPrefix: (p) => {
      const text = String.fromCharCode(...p);
      const last = text.lastIndexOf('\nf ');
      if (last < 0) return false;
      const face = text
        .slice(last + 3)
        .trim()
        .split(/\s+/);
      return face.length >= 3 && face.every((v) => /^-?[1-9]\d*(\/\d*(\/\d*)?)?$/.test(v));
    },
    samples: () => [
      ascii('v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n'),
      ascii('# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf -3/1 -2/1 -1/1\n'),
    ],
    lyingHeaders: () => [
      {
        name: 'an index past the vertices',
        bytes: ascii('v 0 0 0\nv 1 0 0\nf 1 2 2147483647\n'),
        message: /vertex index 2147483647 is out of range/,
      },
    ],
    nonFinite: () => [
      { name: 'nan coordinate', bytes: ascii('v 0 nan 0\nf 1 1 1\n'), message: /finite/ },
      { name: 'huge coordinate', bytes: ascii('v 0 1e400 0\nf 1 1 1\n'), message: /finite/ },
    ],
    others: () => [{ name: 'empty file', bytes: new Uint8Array(0), message: /no faces/ }],
  },
  {
    name: 'PLY',
    decode: (bytes) => parsePly(bytes, MESH_LIMITS),
    check: checkMesh,
    // The ASCII sample without its final newline is still whole.
    validPrefix: (p) => String.fromCharCode(...p).endsWith('\n3 0 1 2'),
    samples: () => [
      plySquare(),
      ascii(
        'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n' +
          'property float z\nelement face 1\nproperty list uchar int vertex_indices\n' +
          'end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n',
      ),
    ],
    lyingHeaders: () => [
      {
        name: '2^31 vertices',
        bytes: plyBinary(2 ** 31, 1, () => 0, 0),
        message: /declares 2147483648 vertices and 1 faces, which need at least/,
      },
      {
        name: 'a face list of 255 vertices in a short file',
        bytes: plyBinary(
          3,
          1,
          (v) => {
            v.setUint8(36, 255);
            return 40;
          },
          40,
        ),
        message: /the file ends in face 0/,
      },
    ],
    nonFinite: () => [
      { name: 'NaN x', bytes: plySquare(NaN, 3), message: /vertex 1: coordinate x is not finite/ },
      {
        name: 'Inf z',
        bytes: plySquare(Infinity, 8),
        message: /vertex 2: coordinate z is not finite/,
      },
    ],
    others: () => [{ name: 'not a PLY', bytes: ascii('PLY\n'), message: /not a PLY file/ }],
  },
  {
    name: 'HDR',
    decode: (bytes) => decodeHdr(bytes, { maxWidth: 16384, maxHeight: 8192 }),
    check: (value) => {
      const img = value as PfmImage;
      expect(img.rgb.length).toBe(img.width * img.height * 3);
      expect(img.rgb.every((x) => Number.isFinite(x) && x >= 0)).toBe(true);
    },
    samples: () => [hdrSample(9, 3), hdrSample(3, 2)],
    lyingHeaders: () => [
      {
        name: '16384 x 8192 texels in a few bytes',
        bytes: ascii('#?RADIANCE\n\n-Y 8192 +X 16384\n\u0002\u0002'),
        message: /declares 16384 × 8192 texels, which need at least/,
      },
      {
        name: '10^9 x 10^9 texels',
        bytes: ascii('#?RADIANCE\n\n-Y 1000000000 +X 1000000000\n'),
        message: /more than the limit of 16384 × 8192/,
      },
    ],
    // RGBE cannot encode NaN or Inf: every texel decodes to m · 2^(e − 136) < 2^127.
    nonFinite: () => [],
    others: () => [{ name: 'not an HDR', bytes: ascii('P6\n'), message: /not a Radiance HDR/ }],
  },

  {
    name: 'PNG',
    decode: (bytes) => decodePngBytes(bytes),
    check: checkImage,
    samples: () => [
      pngImage(3, 2, 6),
      pngImage(2, 2, 0),
      pngIndexed(3, 1, [255, 0, 0, 0, 255, 0, 0, 0, 255], (x) => x, [pngChunk('tRNS', [0, 128])]),
      pngInterlacedGrey(5, 3, (x, y) => 40 * y + x),
    ],
    lyingHeaders: () => [
      {
        name: 'a 4×4 image whose data inflates to 16 MiB (a deflate bomb)',
        bytes: pngFile(ihdr(4, 4), pngChunk('IDAT', zlib(new Uint8Array(16 << 20))), IEND),
        message: /^PNG: the image data inflates past the 68 bytes its 4×4 header needs$/,
      },
      {
        name: '60000 × 60000 texels in a few bytes',
        bytes: pngFile(ihdr(60000, 60000, 8, 0), pngChunk('IDAT', zlib([0])), IEND),
        message: /over the budget of \d+ decoded texels/,
      },
      {
        name: '10000 × 10000 texels in a few bytes',
        bytes: pngFile(ihdr(10000, 10000, 1, 0), pngChunk('IDAT', zlib([0])), IEND),
        message: /^PNG: the header claims 10000×10000 .* but the file has only 9 bytes of IDAT/,
      },
      {
        name: 'image data shorter than the header needs',
        bytes: pngFile(ihdr(4, 4), pngChunk('IDAT', zlib(rawRows(4, 2, 4, () => 0))), IEND),
        message: /inflates to 34 bytes, but the 4×4 header needs 68$/,
      },
      {
        name: 'a chunk length of 2^31',
        bytes: pngFile(ihdr(4, 4), Uint8Array.of(0x80, 0, 0, 0, 0x49, 0x44, 0x41, 0x54), IEND),
        message: /its length 2147483648 runs past the end of the file/,
      },
    ],
    // PNG samples are integers: nothing to make non-finite.
    nonFinite: () => [],
    others: () => [
      {
        name: 'colour type 3 without PLTE',
        bytes: pngFile(ihdr(2, 1, 8, 3), pngChunk('IDAT', zlib([0, 0, 0])), IEND),
        message: /colour type 3 \(indexed-colour\) needs a PLTE chunk/,
      },
      {
        name: 'an empty PLTE',
        bytes: pngFile(ihdr(2, 1, 8, 3), pngChunk('PLTE'), pngChunk('IDAT', zlib([0, 0, 0])), IEND),
        message: /PLTE must hold 1 to 256 RGB entries/,
      },
      { name: 'not a PNG', bytes: ascii('GIF89a'), message: /not a PNG file/ },
    ],
  },
  {
    name: 'JPEG',
    decode: (bytes) => decodeJpegBytes(bytes),
    check: checkImage,
    samples: () => [jpegImage(16, 8, 90), jpegImage(9, 3, 50)],
    lyingHeaders: () => [
      {
        name: '16384 × 8192 in a few hundred bytes',
        bytes: jpegWithSize(jpegImage(16, 8, 90), 16384, 8192),
        message:
          /^JPEG: the frame header claims 16384×8192 but the file has only \d+ bytes \(at least 1572864 needed\)$/,
      },
      {
        name: '9000 × 9000 in a few hundred bytes',
        bytes: jpegWithSize(jpegImage(16, 8, 90), 9000, 9000),
        message: /claims 9000×9000 but the file has only \d+ bytes \(at least 949219 needed\)$/,
      },
      {
        name: '65535 × 65535, over the texel budget',
        bytes: jpegWithSize(jpegImage(16, 8, 90), 65535, 65535),
        message: /over the budget of \d+ decoded texels/,
      },
    ],
    nonFinite: () => [],
    others: () => [{ name: 'not a JPEG', bytes: ascii('\xff\xd9'), message: /no SOI marker/ }],
  },
);

/** A decoded image: samples for every texel, each within its bit depth. */
function checkImage(value: unknown): void {
  const img = value as DecodedImage;
  expect(img.width >= 1 && img.height >= 1).toBe(true);
  expect(img.data.length).toBe(img.width * img.height * img.channels);
  const max = img.depth === 16 ? 65535 : 255;
  expect(img.data.every((v) => Number.isInteger(v) && v >= 0 && v <= max)).toBe(true);
}

/** A fixture of tests/fixtures/compressed-textures/ (read once). */
const compressed = (name: string) =>
  new Uint8Array(readFileSync(new URL(`../fixtures/compressed-textures/${name}`, import.meta.url)));

/**
 * A WebP or KTX2 header's size: positive integers the format can hold (24 bits in WebP,
 * 32 in KTX2; an ETC1S level's length does not bound its size). The texture side and
 * memory limits are TextureLayout's, applied to this size before any decoder runs.
 */
function checkSize(value: unknown): void {
  const { width, height } = value as { width: number; height: number };
  expect(Number.isInteger(width) && Number.isInteger(height)).toBe(true);
  expect(width >= 1 && height >= 1 && width < 2 ** 32 && height < 2 ** 32).toBe(true);
}

/** The fixture with u32 `value` (little-endian) written at each of `at`. */
function withU32(name: string, value: number, ...at: number[]): Uint8Array {
  const b = compressed(name);
  for (const a of at) new DataView(b.buffer).setUint32(a, value, true);
  return b;
}

// The headers of EXT_texture_webp's and KHR_texture_basisu's images, read before any
// decoder is loaded (src/core/texture/webp-header.ts, ktx2-header.ts).
FORMATS.push(
  {
    name: 'WebP',
    decode: (bytes) => readWebpInfo(bytes),
    check: checkSize,
    samples: () => [compressed('pattern-lossless.webp'), compressed('pattern-lossy.webp')],
    lyingHeaders: () => [
      {
        name: 'a RIFF size past the end',
        bytes: withU32('pattern-lossless.webp', 1 << 30, 4),
        message: /truncated: the RIFF header says 1073741832 bytes/,
      },
      {
        name: 'a VP8X canvas of 2^24 × 2^24 over a 24×16 frame',
        bytes: (() => {
          const b = compressed('pattern-lossy.webp');
          b.fill(0xff, 24, 30);
          return b;
        })(),
        message: /the frame at byte \d+ is 24×16, the canvas 16777216×16777216/,
      },
    ],
    nonFinite: () => [],
    others: () => [
      {
        name: 'an animation',
        bytes: (() => {
          const b = compressed('pattern-lossy.webp');
          b[20] |= 0x02;
          return b;
        })(),
        message: /animated WebP/,
      },
    ],
  },
  {
    name: 'KTX2',
    decode: (bytes) => readKtx2Info(bytes),
    check: checkSize,
    samples: () => [compressed('2d_etc1s.ktx2'), compressed('2d_uastc.ktx2')],
    lyingHeaders: () => [
      {
        name: '2^31 × 2^31 texels over 40×40 of UASTC blocks',
        bytes: withU32('2d_uastc.ktx2', 2 ** 31, 20, 24),
        message: /^KTX2: 6 levels, more than|declares 1600 bytes of UASTC blocks/,
      },
      {
        name: 'a level count of 2^32 − 1',
        bytes: withU32('2d_uastc.ktx2', 2 ** 32 - 1, 40),
        message: /4294967295 levels, more than the 6 of a full chain for 40×40/,
      },
      {
        name: 'a level byteLength of 2^32 − 1',
        bytes: withU32('2d_uastc.ktx2', 2 ** 32 - 1, 80 + 8),
        message: /level 0 byteLength 4294967295 \(byte 88\) is past the end/,
      },
      {
        name: 'BasisLZ global data longer than the file',
        bytes: withU32('2d_etc1s.ktx2', 1 << 30, 72),
        message:
          /the BasisLZ global data \(1073741824 bytes at \d+\) is missing, short or past the end/,
      },
    ],
    nonFinite: () => [],
    others: () => [
      {
        name: 'plain RGBA8, not Basis Universal',
        bytes: compressed('2d_rgba8.ktx2'),
        message: /vkFormat 43 is not Basis Universal/,
      },
      {
        name: 'a cube map',
        bytes: withU32('2d_uastc.ktx2', 6, 36),
        message: /faces 6\); glTF takes 2D/,
      },
    ],
  },
);
