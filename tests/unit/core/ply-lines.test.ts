/**
 * An ASCII PLY body is read line by line (issue 27, finding 7): each instance of an
 * element is one line holding exactly the values its properties declare, list counts
 * included. A face line with one index more than its count used to be accepted, and
 * every value after it shifted into the next instance. OBJ is line-based already; its
 * `vn` lines are held to their three numbers.
 */
import { describe, expect, it } from 'vitest';
import { parseObj } from '../../../src/core/io/obj.ts';
import { parsePly } from '../../../src/core/io/ply.ts';

const LIMITS = { maxTriangles: 1000, sceneTriangles: 1000 };
const enc = (s: string) => new TextEncoder().encode(s);
const ply = (body: string) => parsePly(enc(HEADER + body), LIMITS);

// Lines 1–10 are the header; the body starts on line 11.
const HEADER = `ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 2
property list uchar int vertex_indices
property uchar flags
end_header
`;
const VERTICES = '0 0 0\n1 0 0\n1 1 0\n0 1 0\n';

describe('ASCII PLY: one line per instance', () => {
  it('reads a well-formed body, blank lines between instances and CRLF included', () => {
    const m = ply(VERTICES + '3 0 1 2 9\n\n4 0 1 2 3 0\n');
    expect(Array.from(m.indices)).toEqual([0, 1, 2, 0, 1, 2, 0, 2, 3]);
    const crlf = parsePly(
      enc((HEADER + VERTICES + '3 0 1 2 9\n4 0 1 2 3 0\n').replace(/\n/g, '\r\n')),
      LIMITS,
    );
    expect(Array.from(crlf.indices)).toEqual([0, 1, 2, 0, 1, 2, 0, 2, 3]);
  });

  it('refuses a face line with one index more than its count, naming the line', () => {
    // 3 indices declared, 4 written: the 4th used to become the flags, the flags the
    // next face's count, and so on.
    expect(() => ply(VERTICES + '3 0 1 2 3 9\n3 0 2 3 0\n')).toThrow(
      'PLY: face 0 (line 15): the line holds more than the 5 values its properties declare (list counts included), starting at "9"',
    );
  });

  it('refuses a line with a value missing, naming the line', () => {
    expect(() => ply(VERTICES + '3 0 1 2\n4 0 1 2 3 0\n')).toThrow(
      'PLY: face 0 (line 15): the line ends after 4 values, fewer than its properties declare (list counts included)',
    );
    expect(() => ply('0 0\n0 1 0 0\n1 1 0\n0 1 0\n3 0 1 2 9\n4 0 1 2 3 0\n')).toThrow(
      'PLY: vertex 0 (line 11): the line ends after 2 values, fewer than its properties declare (list counts included)',
    );
  });

  it('refuses a vertex split over two lines, and two vertices on one', () => {
    expect(() => ply('0 0\n0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 9\n4 0 1 2 3 0\n')).toThrow(
      /^PLY: vertex 0 \(line 11\): the line ends after 2 values/,
    );
    expect(() => ply('0 0 0 1 0 0\n1 1 0\n0 1 0\n3 0 1 2 9\n4 0 1 2 3 0\n')).toThrow(
      /^PLY: vertex 0 \(line 11\): the line holds more than the 3 values .* starting at "1"$/,
    );
  });

  it('refuses data after the last element', () => {
    expect(() => ply(VERTICES + '3 0 1 2 9\n4 0 1 2 3 0\n7 7 7\n')).toThrow(
      'PLY: line 17: more data after the last element the header declares, starting at "7"',
    );
    // Trailing blank lines are not data.
    expect(ply(VERTICES + '3 0 1 2 9\n4 0 1 2 3 0\n\n  \n').indices.length).toBe(9);
  });
});

describe('OBJ: vn holds three numbers', () => {
  it('refuses a fourth number on a vn line, naming the line', () => {
    const base = 'v 0 0 0\nv 1 0 0\nv 0 1 0\n';
    expect(parseObj(enc(base + 'vn 0 0 1\nf 1//1 2//1 3//1\n'), LIMITS).indices.length).toBe(3);
    expect(() => parseObj(enc(base + 'vn 0 0 1 1\nf 1//1 2//1 3//1\n'), LIMITS)).toThrow(
      'OBJ: line 4: vn has 3 numbers, but the line goes on with "1"',
    );
    // v may carry w or a colour: documented as ignored.
    expect(parseObj(enc('v 0 0 0 1\nv 1 0 0 1 0 0\nv 0 1 0\nf 1 2 3\n'), LIMITS).positions[3]).toBe(
      1,
    );
  });
});
