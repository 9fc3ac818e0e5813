/**
 * Stanford PLY (Turk 1994), the subset the scene format reads (docs/scene-format.md,
 * Meshes): ASCII, binary little-endian and binary big-endian bodies; element `vertex`
 * with scalar properties `x y z` and optionally `nx ny nz`; element `face` with the list
 * property `vertex_indices` (`vertex_index`, which some exporters write, is accepted
 * too). Polygons become fans (v0, vi, vi+1). Other elements and properties are read past
 * and ignored.
 *
 * Two passes over the body: the first checks its structure and counts triangles, so
 * that every limit is checked before the arrays are allocated, once, at their final
 * size; the second fills them. Problems name the header line, or the element and its
 * index (and, in an ASCII body, the line).
 */
import { checkCancel } from '../util/cancel.ts';
import type { RawMesh } from '../geometry/mesh-data.ts';
import type { MeshLimits } from './obj.ts';
import { FormatError } from './format-error.ts';
import {
  bytesToString,
  isBlank,
  lineEnd,
  parseDecimal,
  quoteBytes,
  skipBlanks,
  tokenEnd,
} from './text-bytes.ts';

const TYPES: Record<string, number> = {
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
const SIZE = [1, 1, 2, 2, 4, 4, 4, 8];
const FLOAT32 = 6;

interface Property {
  name: string;
  type: number;
  /** Type of a list's count, or −1 for a scalar property. */
  countType: number;
}

interface Element {
  name: string;
  count: number;
  properties: Property[];
}

type Format = 'ascii' | 'binary_little_endian' | 'binary_big_endian';

interface Header {
  format: Format;
  elements: Element[];
  /** Offset of the first byte of the body. */
  body: number;
}

const MAX_HEADER = 1 << 20;

export function parsePly(bytes: Uint8Array, limits: MeshLimits): RawMesh {
  const header = parseHeader(bytes);
  const layout = checkLayout(header);
  const body = header.format === 'ascii' ? new AsciiBody(bytes, header.body) : null;
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const little = header.format === 'binary_little_endian';
  const reader: Reader =
    body !== null ? body : new BinaryBody(view, header.body, little, bytes.length);
  checkSizes(header, layout, bytes.length - header.body, body !== null);
  const triangles = countPass(header, layout, reader, limits);
  reader.rewind();
  return fillPass(header, layout, reader, triangles);
}

function headerFail(line: number, message: string): never {
  throw new FormatError('PLY', `header line ${line}: ${message}`);
}

function parseHeader(bytes: Uint8Array): Header {
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
interface Layout {
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

function checkLayout(h: Header): Layout {
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
function checkSizes(h: Header, layout: Layout, bodyBytes: number, ascii: boolean): void {
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
interface Reader {
  /** The next value, of PLY type `type`. */
  value(type: number, element: Element, index: number): number;
  /** Where the reader is, for messages: "" or " (line 12)". */
  where(): string;
  rewind(): void;
}

class BinaryBody implements Reader {
  private pos: number;
  constructor(
    private readonly view: DataView,
    private readonly start: number,
    private readonly little: boolean,
    private readonly end: number,
  ) {
    this.pos = start;
  }

  rewind(): void {
    this.pos = this.start;
  }

  where(): string {
    return '';
  }

  value(type: number, element: Element, index: number): number {
    const p = this.pos;
    const size = SIZE[type];
    if (p + size > this.end) {
      throw new FormatError(
        'PLY',
        `the file ends in ${element.name} ${index} of the ${element.count} the header declares`,
      );
    }
    this.pos = p + size;
    const v = this.view;
    switch (type) {
      case 0:
        return v.getInt8(p);
      case 1:
        return v.getUint8(p);
      case 2:
        return v.getInt16(p, this.little);
      case 3:
        return v.getUint16(p, this.little);
      case 4:
        return v.getInt32(p, this.little);
      case 5:
        return v.getUint32(p, this.little);
      case 6:
        return v.getFloat32(p, this.little);
      default:
        return v.getFloat64(p, this.little);
    }
  }
}

class AsciiBody implements Reader {
  private pos: number;
  private line: number;
  private readonly firstLine: number;

  constructor(
    private readonly bytes: Uint8Array,
    private readonly start: number,
  ) {
    this.pos = start;
    // The body starts on the line after end_header.
    let lines = 1;
    for (let i = 0; i < start; i++) if (bytes[i] === 10) lines++;
    this.firstLine = lines;
    this.line = lines;
  }

  rewind(): void {
    this.pos = this.start;
    this.line = this.firstLine;
  }

  where(): string {
    return ` (line ${this.line})`;
  }

  value(type: number, element: Element, index: number): number {
    const b = this.bytes;
    let i = this.pos;
    while (i < b.length && (isBlank(b[i]) || b[i] === 10)) {
      if (b[i] === 10) this.line++;
      i++;
    }
    if (i >= b.length) {
      throw new FormatError(
        'PLY',
        `the file ends in ${element.name} ${index} of the ${element.count} the header declares`,
      );
    }
    let e = i;
    while (e < b.length && !isBlank(b[e]) && b[e] !== 10) e++;
    this.pos = e;
    const x = parseDecimal(b, i, e);
    if (Number.isNaN(x) || (type < FLOAT32 && !Number.isInteger(x))) {
      throw new FormatError(
        'PLY',
        `${element.name} ${index}${this.where()}: expected ${type < FLOAT32 ? 'an integer' : 'a number'}, ` +
          `got ${quoteBytes(b, i, e)}`,
      );
    }
    return x;
  }
}

/** Reads past one instance of an element; returns the length of list `list` (or −1). */
function skipInstance(reader: Reader, element: Element, index: number, list: number): number {
  let length = -1;
  const props = element.properties;
  for (let k = 0; k < props.length; k++) {
    const p = props[k];
    if (p.countType < 0) {
      reader.value(p.type, element, index);
      continue;
    }
    const n = reader.value(p.countType, element, index);
    if (n < 0) {
      throw new FormatError(
        'PLY',
        `${element.name} ${index}${reader.where()}: list ${p.name} has a negative length ${n}`,
      );
    }
    for (let j = 0; j < n; j++) reader.value(p.type, element, index);
    if (k === list) length = n;
  }
  return length;
}

function countPass(h: Header, layout: Layout, reader: Reader, limits: MeshLimits): number {
  let triangles = 0;
  h.elements.forEach((e, ei) => {
    if (e.properties.length === 0) return;
    const list = ei === layout.face ? layout.list : -1;
    for (let i = 0; i < e.count; i++) {
      if ((i & 16383) === 16383) checkCancel();
      const n = skipInstance(reader, e, i, list);
      if (list < 0) continue;
      if (n < 3) {
        throw new FormatError(
          'PLY',
          `face ${i}${reader.where()}: needs at least 3 vertices, got ${n}`,
        );
      }
      triangles += n - 2;
      if (triangles > limits.maxTriangles) {
        throw new FormatError(
          'PLY',
          `faces 0 to ${i} hold ${triangles} triangles, more than the ${limits.maxTriangles} ` +
            `left of the limit of ${limits.sceneTriangles} per scene`,
        );
      }
    }
  });
  const vertices = h.elements[layout.vertex].count;
  if (vertices > 3 * limits.sceneTriangles) {
    throw new FormatError(
      'PLY',
      `the file has ${vertices} vertices, more than 3 per triangle of the scene limit`,
    );
  }
  return triangles;
}

function fillPass(h: Header, layout: Layout, reader: Reader, triangles: number): RawMesh {
  const ve = h.elements[layout.vertex];
  const vertexCount = ve.count;
  const positions = new Float64Array(vertexCount * 3);
  const normals = layout.nx >= 0 ? new Float64Array(vertexCount * 3) : null;
  const indices = new Uint32Array(triangles * 3);
  // Where each vertex property goes: 0..2 position, 3..5 normal, −1 nowhere.
  const slot = ve.properties.map((_, k) =>
    [layout.x, layout.y, layout.z, layout.nx, layout.ny, layout.nz].indexOf(k),
  );
  const row = new Float64Array(6);
  let t = 0;
  h.elements.forEach((e, ei) => {
    if (e.properties.length === 0) return;
    if (ei === layout.vertex) {
      for (let i = 0; i < e.count; i++) {
        if ((i & 16383) === 16383) checkCancel();
        for (let k = 0; k < e.properties.length; k++) {
          const p = e.properties[k];
          if (p.countType >= 0) {
            const n = reader.value(p.countType, e, i);
            for (let j = 0; j < n; j++) reader.value(p.type, e, i);
          } else {
            const x = reader.value(p.type, e, i);
            if (slot[k] >= 0) row[slot[k]] = x;
          }
        }
        for (let a = 0; a < 3; a++) {
          if (!Number.isFinite(row[a])) {
            throw new FormatError(
              'PLY',
              `vertex ${i}${reader.where()}: coordinate ${'xyz'[a]} is not finite`,
            );
          }
          positions[3 * i + a] = row[a];
        }
        if (normals !== null) {
          if (!Number.isFinite(row[3]) || !Number.isFinite(row[4]) || !Number.isFinite(row[5])) {
            throw new FormatError('PLY', `vertex ${i}${reader.where()}: its normal is not finite`);
          }
          if (row[3] === 0 && row[4] === 0 && row[5] === 0) {
            throw new FormatError(
              'PLY',
              `vertex ${i}${reader.where()}: its normal has zero length`,
            );
          }
          normals[3 * i] = row[3];
          normals[3 * i + 1] = row[4];
          normals[3 * i + 2] = row[5];
        }
      }
    } else if (ei === layout.face) {
      for (let i = 0; i < e.count; i++) {
        for (let k = 0; k < e.properties.length; k++) {
          const p = e.properties[k];
          if (p.countType < 0) {
            reader.value(p.type, e, i);
            continue;
          }
          const n = reader.value(p.countType, e, i);
          if (k !== layout.list) {
            for (let j = 0; j < n; j++) reader.value(p.type, e, i);
            continue;
          }
          let first = 0;
          let previous = 0;
          for (let j = 0; j < n; j++) {
            const v = reader.value(p.type, e, i);
            if (!(v >= 0 && v < vertexCount)) {
              throw new FormatError(
                'PLY',
                `face ${i}${reader.where()}: vertex index ${v} is out of range ` +
                  `(the file has ${vertexCount} vertices)`,
              );
            }
            if (j === 0) first = v;
            else if (j >= 2) {
              indices[t++] = first;
              indices[t++] = previous;
              indices[t++] = v;
            }
            previous = v;
          }
        }
      }
    } else {
      for (let i = 0; i < e.count; i++) skipInstance(reader, e, i, -1);
    }
  });
  return { positions, indices, normals };
}
