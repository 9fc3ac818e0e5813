/**
 * The mesh file parsers (OBJ; PLY in ASCII, binary little- and big-endian): what they
 * read, and one clear error naming the line or element for every malformed file.
 */
import { describe, expect, it } from 'vitest';
import { parseObj } from '../../../src/core/io/obj.ts';
import { parsePly } from '../../../src/core/io/ply.ts';
import { parseDecimal } from '../../../src/core/io/text-bytes.ts';

const LIMITS = { maxTriangles: 1000, sceneTriangles: 1000 };
const enc = (s: string) => new TextEncoder().encode(s);
const obj = (s: string, limits = LIMITS) => parseObj(enc(s), limits);
const ply = (s: string | Uint8Array, limits = LIMITS) =>
  parsePly(typeof s === 'string' ? enc(s) : s, limits);

describe('decimal numbers from bytes', () => {
  it('parses like Number(), correctly rounded, and refuses what is not a decimal', () => {
    const cases = [
      '0',
      '-0',
      '1',
      '+2.5',
      '.5',
      '5.',
      '0.1',
      '-1e-5',
      '1E+10',
      '3.141592653589793',
      '0.30000000000000004',
      '123456789012345678901234567890',
      '1e-320',
      '2.2250738585072014e-308',
      '1.7976931348623157e308',
      '0.000000000000000000000000001234',
      '9007199254740993',
    ];
    for (const c of cases)
      expect(Object.is(parseDecimal(enc(c), 0, c.length), Number(c))).toBe(true);
    for (const c of ['', '-', 'e5', '1e', '1.2.3', 'inf', 'nan', '0x10', '1,5', '1e+', '--1']) {
      expect(parseDecimal(enc(c), 0, c.length), c).toBeNaN();
    }
    // Random doubles written with 17 digits and with 6.
    let x = 0.123456789;
    for (let i = 0; i < 2000; i++) {
      x = (x * 9301 + 49297) % 233280;
      const v = (x / 233280 - 0.5) * 10 ** ((i % 40) - 20);
      for (const s of [v.toPrecision(17), v.toPrecision(6), String(v)]) {
        expect(parseDecimal(enc(s), 0, s.length)).toBe(Number(s));
      }
    }
  });
});

describe('OBJ', () => {
  it('reads v and f, splits polygons into fans, resolves negative indices, ignores the rest', () => {
    const m = obj(
      [
        '# a comment',
        'mtllib x.mtl',
        'o thing',
        'v 0 0 0',
        'v 1 0 0 1.0', // w is ignored
        'v 1 1 0 0.5 0.5 0.5', // so is a colour
        'v 0 1 0',
        'vt 0 0',
        'g group',
        's off',
        'usemtl red',
        'f 1 2 3 4',
        'f -4 -2 -1',
        'l 1 2',
      ].join('\r\n'),
    );
    expect(Array.from(m.positions)).toEqual([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]);
    expect(Array.from(m.indices)).toEqual([0, 1, 2, 0, 2, 3, 0, 2, 3]);
    expect(m.normals).toBeNull();
  });

  it('gives each distinct (position, normal) pair its own vertex; faces without vn get none', () => {
    const m = obj(
      [
        'v 0 0 0',
        'v 1 0 0',
        'v 0 1 0',
        'v 1 1 0',
        'vn 0 0 1',
        'vn 0 0 2',
        'f 1//1 2//1 3//1',
        'f 2/1/2 4/1/2 3/1/2',
        'f 1 2 4',
      ].join('\n'),
    );
    // Vertices: (1,n1) (2,n1) (3,n1) (2,n2) (4,n2) (3,n2) (1,-) (2,-) (4,-).
    expect(m.indices.length).toBe(9);
    expect(m.positions.length).toBe(27);
    const normalOf = (k: number) => Array.from(m.normals!.slice(3 * k, 3 * k + 3));
    expect(normalOf(m.indices[0])).toEqual([0, 0, 1]);
    expect(normalOf(m.indices[3])).toEqual([0, 0, 2]);
    expect(normalOf(m.indices[6])).toEqual([0, 0, 0]);
    expect(Array.from(m.positions.slice(3 * m.indices[4], 3 * m.indices[4] + 3))).toEqual([
      1, 1, 0,
    ]);
  });

  it('names the line of every problem', () => {
    const bad: [string, RegExp][] = [
      ['v 0 0 0\nv 1 0 0\nf 1 2', /^OBJ: line 3: a face needs at least 3 vertices, got 2$/],
      ['v 0 0 0\nv 1 0\nf 1 1 1', /^OBJ: line 2: v needs 3 numbers, got 2$/],
      ['v 0 0 0\nv 1 zero 0\nf 1 2 1', /^OBJ: line 2: v needs 3 finite numbers, got "zero"$/],
      ['v 0 0 1e999\nf 1 1 1', /^OBJ: line 1: v needs 3 finite numbers, got "1e999"$/],
      [
        'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4',
        /^OBJ: line 4: vertex index 4 is out of range: the file has 3 vertices$/,
      ],
      [
        'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0',
        /^OBJ: line 4: a face needs vertex indices \(1-based integers\), got "0"$/,
      ],
      [
        'v 0 0 0\nf -2 1 1\nv 1 0 0',
        /out of range: the file has 2 vertices, 1 of them before this line/,
      ],
      [
        'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1',
        /^OBJ: line 4: vn has zero length$/,
      ],
      [
        'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//2 2//2 3//2',
        /^OBJ: line 4: normal index 2 is out of range: the file has 0 normals$/,
      ],
      ['v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3', /line 4: a face vertex has more than 3 fields/],
      ['v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\x00', /line 4: .*"3\\x00"/],
      ['v 0 0 0\n', /^OBJ: the file has no faces \(f\)$/],
      ['', /^OBJ: the file has no faces/],
    ];
    for (const [text, message] of bad) expect(() => obj(text), text).toThrow(message);
  });

  it('refuses more triangles than the scene has left before allocating them', () => {
    const text = 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' + 'f 1 2 3\n'.repeat(11);
    expect(obj(text, { maxTriangles: 11, sceneTriangles: 20 }).indices.length).toBe(33);
    expect(() => obj(text, { maxTriangles: 10, sceneTriangles: 20 })).toThrow(
      'OBJ: the faces up to line 14 hold 11 triangles, more than the 10 left of the limit of 20 per scene',
    );
    // A polygon of many vertices counts as many triangles.
    const fan =
      'v 0 0 0\n'.repeat(30) + 'f ' + Array.from({ length: 30 }, (_, i) => i + 1).join(' ');
    expect(() => obj(fan, { maxTriangles: 27, sceneTriangles: 27 })).toThrow(/28 triangles/);
  });
});

const PLY_ASCII = `ply
format ascii 1.0
comment made by hand
element vertex 4
property float x
property float y
property float z
property uchar red
element face 2
property list uchar int vertex_indices
property uchar flags
element edge 1
property int vertex1
property int vertex2
end_header
0 0 0 255
1 0 0 0
1 1 0 0
0 1 0 7
3 0 1 2 9
4 0 1 2 3 0
0 1
`;

/** A binary PLY of the unit square (two faces: a triangle and a quad) with normals. */
function binaryPly(
  little: boolean,
  options: { faces?: number; truncate?: number; index?: number } = {},
) {
  const header = enc(
    `ply\nformat binary_${little ? 'little' : 'big'}_endian 1.0\nelement vertex 4\n` +
      'property double x\nproperty double y\nproperty double z\n' +
      'property float nx\nproperty float ny\nproperty float nz\nproperty short extra\n' +
      `element face ${options.faces ?? 2}\nproperty list uchar uint vertex_indices\nend_header\n`,
  );
  const body = new DataView(new ArrayBuffer(4 * 38 + 2 * 13 + 4 + 4));
  let o = 0;
  const verts = [
    [0, 0, 0],
    [1, 0, 0],
    [1, 1, 0],
    [0, 1, 0],
  ];
  for (const [x, y, z] of verts) {
    body.setFloat64(o, x, little);
    body.setFloat64(o + 8, y, little);
    body.setFloat64(o + 16, z, little);
    body.setFloat32(o + 24, 0, little);
    body.setFloat32(o + 28, 0, little);
    body.setFloat32(o + 32, 1, little);
    body.setInt16(o + 36, -1, little);
    o += 38;
  }
  body.setUint8(o++, 3);
  for (const i of [0, 1, options.index ?? 2]) {
    body.setUint32(o, i, little);
    o += 4;
  }
  body.setUint8(o++, 4);
  for (const i of [0, 1, 2, 3]) {
    body.setUint32(o, i, little);
    o += 4;
  }
  const bytes = new Uint8Array(header.length + o);
  bytes.set(header);
  bytes.set(new Uint8Array(body.buffer, 0, o), header.length);
  return options.truncate ? bytes.subarray(0, bytes.length - options.truncate) : bytes;
}

describe('PLY', () => {
  it('reads an ASCII file past extra properties and elements', () => {
    const m = ply(PLY_ASCII);
    expect(Array.from(m.positions)).toEqual([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]);
    expect(Array.from(m.indices)).toEqual([0, 1, 2, 0, 1, 2, 0, 2, 3]);
    expect(m.normals).toBeNull();
  });

  it.each([true, false])('reads binary (little-endian: %s) with normals', (little) => {
    const m = ply(binaryPly(little));
    expect(Array.from(m.positions)).toEqual([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]);
    expect(Array.from(m.indices)).toEqual([0, 1, 2, 0, 1, 2, 0, 2, 3]);
    expect(Array.from(m.normals!)).toEqual([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1]);
  });

  it('names the element (and the line, in ASCII) of every problem', () => {
    expect(() => ply(binaryPly(true, { truncate: 3 }))).toThrow(
      /^PLY: the file ends in face 1 of the 2 the header declares$/,
    );
    expect(() => ply(binaryPly(false, { index: 4 }))).toThrow(
      /^PLY: face 0: vertex index 4 is out of range \(the file has 4 vertices\)$/,
    );
    // A header that declares far more than the file holds, refused before allocating.
    expect(() => ply(binaryPly(true, { faces: 2_000_000_000 }))).toThrow(
      /^PLY: the header declares 4 vertices and 2000000000 faces, which need at least \d+ bytes, but the body has \d+/,
    );
    const ascii = (body: string) => PLY_ASCII.replace(/end_header\n[^]*$/, 'end_header\n' + body);
    expect(() =>
      ply(ascii('0 0 0 255\n1 0 0 0\n1 x 0 0\n0 1 0 7\n3 0 1 2 9\n4 0 1 2 3 0\n0 1\n')),
    ).toThrow(/^PLY: vertex 2 \(line 18\): expected a number, got "x"$/);
    expect(() =>
      ply(ascii('0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n2 0 1 9\n4 0 1 2 3 0\n0 1\n')),
    ).toThrow(/^PLY: face 0 \(line 20\): needs at least 3 vertices, got 2$/);
    expect(() =>
      ply(ascii('0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n3 0 1 2.5 0\n4 0 1 2 3 0\n0 1\n')),
    ).toThrow(/^PLY: face 0 \(line 20\): expected an integer, got "2.5"$/);
    expect(() => ply(ascii('0 0 0 1\n1 0 0 1\n'))).toThrow(/body has/);
    expect(() =>
      ply(ascii('0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n3 0 1 2 0\n4 0 1 2 3 0\n0        \n')),
    ).toThrow(/^PLY: the file ends in edge 0 of the 1 the header declares$/);
    const header = (h: string) => ply(h + '\nend_header\n');
    expect(() => header('ply\nformat ascii 2.0')).toThrow(
      /header line 2: unsupported PLY version "2.0"/,
    );
    expect(() => header('ply\nformat utf8 1.0')).toThrow(/header line 2: unknown format "utf8"/);
    expect(() => header('ply\nformat ascii 1.0\nelement vertex -1')).toThrow(/header line 3/);
    expect(() => header('ply\nformat ascii 1.0\nproperty float x')).toThrow(
      /header line 3: a property before any element/,
    );
    expect(() => header('ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x')).toThrow(
      /header line 4/,
    );
    expect(() => header('ply\nformat ascii 1.0\nbogus')).toThrow(
      /header line 3: unknown header line "bogus"/,
    );
    expect(() =>
      header('ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y'),
    ).toThrow(/the vertex element has no z property/);
    expect(() =>
      header(
        'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z',
      ),
    ).toThrow(/the header declares no face element/);
    expect(() =>
      header(
        'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n' +
          'property float nx\nelement face 1\nproperty list uchar int vertex_indices',
      ),
    ).toThrow(/some of nx, ny, nz but not all three/);
    expect(() =>
      header(
        'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n' +
          'element face 1\nproperty list uchar float vertex_indices',
      ),
    ).toThrow(/integer item type/);
    expect(() => ply('PLY\n')).toThrow(/not a PLY file/);
    expect(() => ply('ply\nformat ascii 1.0\n')).toThrow(/ends before the end_header line/);
  });

  it('refuses more triangles than the scene has left', () => {
    expect(() => ply(PLY_ASCII, { maxTriangles: 2, sceneTriangles: 5 })).toThrow(
      /^PLY: faces 0 to 1 hold 3 triangles, more than the 2 left of the limit of 5 per scene$/,
    );
  });

  it('refuses a zero or non-finite normal and a non-finite coordinate', () => {
    const withNormals = (n: string, p = '0 0 0') =>
      `ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n` +
      `property float nx\nproperty float ny\nproperty float nz\nelement face 1\n` +
      `property list uchar int vertex_indices\nend_header\n${p} 0 0 1\n1 0 0 ${n}\n0 1 0 0 0 1\n3 0 1 2\n`;
    expect(ply(withNormals('0 0 1')).normals).not.toBeNull();
    expect(() => ply(withNormals('0 0 0'))).toThrow(
      /^PLY: vertex 1 \(line 14\): its normal has zero length$/,
    );
    expect(() => ply(withNormals('0 0 1e39'))).not.toThrow(); // a float64 in ASCII is fine
    expect(() => ply(withNormals('0 0 1', '0 0 1e999'))).toThrow(
      /^PLY: vertex 0 \(line 13\): coordinate z is not finite$/,
    );
  });
});
