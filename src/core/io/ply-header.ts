/**
 * The header of a Stanford PLY file (Turk 1994; Bourke's description of the format):
 * `ply`, `format`, `element`, `property` and `end_header` lines, the element types, and
 * where the mesh's data sits among the elements (ply.ts reads the body).
 */
import { FormatError } from './format-error.ts';
import { bytesToString, lineEnd, skipBlanks, tokenEnd } from './text-bytes.ts';

export const TYPES: Record<string, number> = {
  char: 0,
  int8: 0,
  uchar: 1,
  uint8: 1,
  short: 2,
  int16: 2,
  ushort: 3,
  uint16: 3,
  int: 4,
  int32: 4,
  uint: 5,
  uint32: 5,
  float: 6,
  float32: 6,
  double: 7,
  float64: 7,
};
export const SIZE = [1, 1, 2, 2, 4, 4, 4, 8];
export const FLOAT32 = 6;

export interface Property {
  name: string;
  type: number;
  /** Type of a list's count, or −1 for a scalar property. */
  countType: number;
}

export interface Element {
  name: string;
  count: number;
  properties: Property[];
}

export type Format = 'ascii' | 'binary_little_endian' | 'binary_big_endian';

export interface Header {
  format: Format;
  elements: Element[];
  /** Offset of the first byte of the body. */
  body: number;
}

const MAX_HEADER = 1 << 20;

function headerFail(line: number, message: string): never {
  throw new FormatError('PLY', `header line ${line}: ${message}`);
}

export function parseHeader(bytes: Uint8Array): Header {
  let start = 0;
  let line = 0;
  let format: Format | undefined;
  const elements: Element[] = [];
  for (;;) {
    if (start >= bytes.length || start > MAX_HEADER) {
      throw new FormatError(
        'PLY',
        start > MAX_HEADER
          ? 'the header has no end_header line within its first 1 MiB'
          : 'the file ends before the end_header line',
      );
    }
    const end = lineEnd(bytes, start);
    line++;
    const words: string[] = [];
    for (let i = skipBlanks(bytes, start, end); i < end; i = skipBlanks(bytes, i, end)) {
      const te = tokenEnd(bytes, i, end);
      if (words.length < 8) words.push(bytesToString(bytes, i, Math.min(te, i + 64)));
      i = te;
    }
    const next = end + 1;
    if (line === 1) {
      if (words.length !== 1 || words[0] !== 'ply') {
        throw new FormatError('PLY', `not a PLY file: it must start with the line "ply"`);
      }
    } else if (words[0] === 'end_header') {
      if (format === undefined) headerFail(line, 'no format line before end_header');
      return { format, elements, body: next };
    } else if (words[0] === 'format') {
      const f = words[1];
      if (f !== 'ascii' && f !== 'binary_little_endian' && f !== 'binary_big_endian') {
        headerFail(
          line,
          `unknown format ${quote(f)} (ascii, binary_little_endian or binary_big_endian)`,
        );
      }
      if (words[2] !== '1.0') headerFail(line, `unsupported PLY version ${quote(words[2])}`);
      format = f;
    } else if (words[0] === 'element') {
      const count = Number(words[2]);
      if (words.length !== 3 || !/^\d+$/.test(words[2]) || !Number.isSafeInteger(count)) {
        headerFail(line, 'an element line is "element <name> <count>"');
      }
      elements.push({ name: words[1], count, properties: [] });
    } else if (words[0] === 'property') {
      const element = elements[elements.length - 1];
      if (element === undefined) headerFail(line, 'a property before any element');
      if (words[1] === 'list') {
        const countType = TYPES[words[2]];
        const type = TYPES[words[3]];
        if (words.length !== 5 || countType === undefined || type === undefined) {
          headerFail(line, 'a list property is "property list <count type> <item type> <name>"');
        }
        if (countType >= FLOAT32) headerFail(line, `a list count must have an integer type`);
        element.properties.push({ name: words[4], type, countType });
      } else {
        const type = TYPES[words[1]];
        if (words.length !== 3 || type === undefined) {
          headerFail(line, `a property is "property <type> <name>", got ${quote(words.join(' '))}`);
        }
        element.properties.push({ name: words[2], type, countType: -1 });
      }
    } else if (words[0] !== 'comment' && words[0] !== 'obj_info' && words.length > 0) {
      headerFail(line, `unknown header line ${quote(words[0])}`);
    }
    start = next;
  }
}

function quote(s: string | undefined): string {
  return s === undefined ? 'nothing' : JSON.stringify(s.length > 40 ? s.slice(0, 40) + '...' : s);
}

/** Where the mesh's data sits among the elements. */
export interface Layout {
  vertex: number;
  face: number;
  /** Property indices in the vertex element; nx = −1 when there are no normals. */
  x: number;
  y: number;
  z: number;
  nx: number;
  ny: number;
  nz: number;
  /** Property index of the face's index list. */
  list: number;
}

export function checkLayout(h: Header): Layout {
  const vertex = h.elements.findIndex((e) => e.name === 'vertex');
  const face = h.elements.findIndex((e) => e.name === 'face');
  if (vertex < 0) throw new FormatError('PLY', 'the header declares no vertex element');
  const vp = h.elements[vertex].properties;
  const scalar = (name: string, required: boolean): number => {
    const i = vp.findIndex((p) => p.name === name);
    if (i >= 0 && vp[i].countType >= 0) {
      throw new FormatError('PLY', `vertex property ${name} must be a scalar, not a list`);
    }
    if (i < 0 && required)
      throw new FormatError('PLY', `the vertex element has no ${name} property`);
    return i;
  };
  const [x, y, z] = [scalar('x', true), scalar('y', true), scalar('z', true)];
  const [nx, ny, nz] = [scalar('nx', false), scalar('ny', false), scalar('nz', false)];
  const normals = [nx, ny, nz].filter((i) => i >= 0).length;
  if (normals !== 0 && normals !== 3) {
    throw new FormatError('PLY', 'the vertex element has some of nx, ny, nz but not all three');
  }
  if (face < 0) throw new FormatError('PLY', 'the header declares no face element');
  const fp = h.elements[face].properties;
  let list = fp.findIndex((p) => p.name === 'vertex_indices');
  if (list < 0) list = fp.findIndex((p) => p.name === 'vertex_index');
  if (list < 0) throw new FormatError('PLY', 'the face element has no vertex_indices property');
  if (fp[list].countType < 0) throw new FormatError('PLY', 'face vertex_indices must be a list');
  if (fp[list].type >= FLOAT32) {
    throw new FormatError('PLY', 'face vertex_indices must have an integer item type');
  }
  if (h.elements[face].count === 0) throw new FormatError('PLY', 'the file has no faces');
  return { vertex, face, x, y, z, nx, ny: nx < 0 ? -1 : ny, nz: nx < 0 ? -1 : nz, list };
}

/**
 * Declared counts against the body's size, before anything is allocated: every binary
 * element takes at least the sum of its properties' sizes (a list at least its count),
 * every ASCII value at least two bytes.
 */
export function checkSizes(h: Header, layout: Layout, bodyBytes: number, ascii: boolean): void {
  let need = 0;
  for (const e of h.elements) {
    let per = 0;
    for (const p of e.properties)
      per += ascii ? 2 : p.countType >= 0 ? SIZE[p.countType] : SIZE[p.type];
    need += per * e.count;
  }
  if (need > bodyBytes) {
    const v = h.elements[layout.vertex].count;
    const f = h.elements[layout.face].count;
    throw new FormatError(
      'PLY',
      `the header declares ${v} vertices and ${f} faces, which need at least ${need} bytes, ` +
        `but the body has ${bodyBytes}`,
    );
  }
}

/** Reads values one at a time from an ASCII or binary body. */
export interface Reader {
  /** Before the first value of an instance of an element (an ASCII body: its line). */
  begin(element: Element, index: number): void;
  /** The next value, of PLY type `type`. */
  value(type: number, element: Element, index: number): number;
  /** After the last value of an instance (an ASCII body: nothing more on its line). */
  end(element: Element, index: number): void;
  /** After the last element: nothing but blanks may follow in an ASCII body. */
  finish(): void;
  /** Where the reader is, for messages: "" or " (line 12)". */
  where(): string;
  rewind(): void;
}
