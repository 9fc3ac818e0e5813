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
import { expect } from 'vitest';
import { decodeHdr, decodePfm, encodeHdr, encodePfm, type PfmImage } from '../../src/core/index.ts';
import type { RawMesh } from '../../src/core/geometry/mesh-data.ts';
import { parseObj } from '../../src/core/io/obj.ts';
import { parsePly } from '../../src/core/io/ply.ts';

export interface FormatEntry {
  /** As the decoder's FormatError names it (error.format), e.g. "PFM". */
  name: string;
  /** Decodes bytes; throws FormatError on bad input. */
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
);
