/**
 * Wavefront OBJ, the subset the scene format reads (docs/scene-format.md, Meshes):
 * `v x y z` (further numbers, such as w or a colour, are ignored), `vn x y z` (exactly
 * three), and
 * `f` with vertices written `v`, `v/vt`, `v//vn` or `v/vt/vn` (1-based; negative
 * indices count back from the last vertex defined so far). Polygons become fans
 * (v0, vi, vi+1). Every other statement (vt, o, g, s, usemtl, mtllib, l, p, comments)
 * is ignored.
 *
 * OBJ indexes positions and normals separately, the tracer per vertex: a face whose
 * vertices all carry `vn` gets one output vertex per distinct (position, normal) pair,
 * a face with any vertex lacking `vn` uses the geometric normal (its vertices get the
 * normal (0, 0, 0)).
 *
 * Two passes over the bytes: the first counts vertices and triangles, so the limits are
 * checked and every array is allocated once at its final size; the second fills them.
 */
import { checkCancel } from '../util/cancel.ts';
import type { RawMesh } from '../geometry/mesh-data.ts';
import { FormatError } from './format-error.ts';
import {
  Byte,
  bytesEqual,
  lineEnd,
  parseDecimal,
  parseInteger,
  quoteBytes,
  skipBlanks,
  tokenEnd,
} from './text-bytes.ts';

export interface MeshLimits {
  /** Triangles this file may still add to the scene. */
  maxTriangles: number;
  /** The scene's limit, for the message. */
  sceneTriangles: number;
}

interface Counts {
  vertices: number;
  normals: number;
  triangles: number;
  faces: number;
  faceNormals: boolean;
  maxPolygon: number;
}

export function parseObj(bytes: Uint8Array, limits: MeshLimits): RawMesh {
  const counts = countObj(bytes, limits);
  return fillObj(bytes, counts);
}

function fail(line: number, message: string): never {
  throw new FormatError('OBJ', `line ${line}: ${message}`);
}

function countObj(bytes: Uint8Array, limits: MeshLimits): Counts {
  const c: Counts = {
    vertices: 0,
    normals: 0,
    triangles: 0,
    faces: 0,
    faceNormals: false,
    maxPolygon: 0,
  };
  let line = 0;
  for (let start = 0; start < bytes.length;) {
    const end = lineEnd(bytes, start);
    if ((++line & 16383) === 0) checkCancel();
    const k = skipBlanks(bytes, start, end);
    const ke = tokenEnd(bytes, k, end);
    if (bytesEqual(bytes, k, ke, 'v')) c.vertices++;
    else if (bytesEqual(bytes, k, ke, 'vn')) c.normals++;
    else if (bytesEqual(bytes, k, ke, 'f')) {
      let n = 0;
      let withNormal = 0;
      for (let i = skipBlanks(bytes, ke, end); i < end; i = skipBlanks(bytes, i, end)) {
        const te = tokenEnd(bytes, i, end);
        if (hasNormalField(bytes, i, te)) withNormal++;
        n++;
        i = te;
      }
      if (n < 3) fail(line, `a face needs at least 3 vertices, got ${n}`);
      if (withNormal === n) c.faceNormals = true;
      c.faces++;
      c.triangles += n - 2;
      if (n > c.maxPolygon) c.maxPolygon = n;
      if (c.triangles > limits.maxTriangles) {
        throw new FormatError(
          'OBJ',
          `the faces up to line ${line} hold ${c.triangles} triangles, more than the ` +
            `${limits.maxTriangles} left of the limit of ${limits.sceneTriangles} per scene`,
        );
      }
    }
    start = end + 1;
  }
  if (c.faces === 0) throw new FormatError('OBJ', 'the file has no faces (f)');
  // Every vertex a triangle can use is one of its three corners: more vertices than
  // that can only be unused, and would only cost memory.
  if (c.vertices > 3 * limits.sceneTriangles) {
    throw new FormatError(
      'OBJ',
      `the file has ${c.vertices} vertices, more than 3 per triangle of the scene limit`,
    );
  }
  return c;
}

/** Whether a face vertex token `v/vt/vn` or `v//vn` has a non-empty normal field. */
function hasNormalField(bytes: Uint8Array, start: number, end: number): boolean {
  let slashes = 0;
  let last = -1;
  for (let i = start; i < end; i++) {
    if (bytes[i] === Byte.Slash) {
      slashes++;
      last = i;
    }
  }
  return slashes === 2 && last < end - 1;
}

function fillObj(bytes: Uint8Array, c: Counts): RawMesh {
  const positions = new Float64Array(c.vertices * 3);
  const normalsIn = c.faceNormals ? new Float64Array(c.normals * 3) : null;
  const indices = new Uint32Array(c.triangles * 3);
  const polygon = new Int32Array(c.maxPolygon);
  const polygonNormal = new Int32Array(c.maxPolygon);
  const scratch = new Float64Array(3);
  const remap = c.faceNormals ? new VertexRemap(c.vertices, c.normals, c.triangles) : null;
  let v = 0;
  let vn = 0;
  let t = 0;
  let line = 0;
  for (let start = 0; start < bytes.length;) {
    const end = lineEnd(bytes, start);
    if ((++line & 16383) === 0) checkCancel();
    const k = skipBlanks(bytes, start, end);
    const ke = tokenEnd(bytes, k, end);
    if (bytesEqual(bytes, k, ke, 'v')) {
      readVector(bytes, ke, end, line, 'v', positions, v * 3, false);
      v++;
    } else if (bytesEqual(bytes, k, ke, 'vn')) {
      // Checked even when no face uses them: a zero-length normal is an error anyway.
      if (normalsIn !== null) readVector(bytes, ke, end, line, 'vn', normalsIn, vn * 3, true);
      else readVector(bytes, ke, end, line, 'vn', scratch, 0, true);
      vn++;
    } else if (bytesEqual(bytes, k, ke, 'f')) {
      let n = 0;
      let allNormals = true;
      for (let i = skipBlanks(bytes, ke, end); i < end; i = skipBlanks(bytes, i, end)) {
        const te = tokenEnd(bytes, i, end);
        const ni = readFaceVertex(bytes, i, te, line, v, vn, c, polygon, n);
        polygonNormal[n] = ni;
        if (ni < 0) allNormals = false;
        n++;
        i = te;
      }
      if (remap !== null) {
        for (let j = 0; j < n; j++) {
          polygon[j] = remap.vertex(polygon[j], allNormals ? polygonNormal[j] : -1);
        }
      }
      for (let j = 1; j + 1 < n; j++) {
        indices[t++] = polygon[0];
        indices[t++] = polygon[j];
        indices[t++] = polygon[j + 1];
      }
    }
    start = end + 1;
  }
  if (remap === null) return { positions, indices, normals: null };
  return remap.finish(positions, normalsIn!, indices);
}

/** Reads three finite numbers after the keyword into out[o..o+2]. */
function readVector(
  bytes: Uint8Array,
  from: number,
  end: number,
  line: number,
  keyword: string,
  out: Float64Array,
  o: number,
  isNormal: boolean,
): void {
  let i = from;
  for (let a = 0; a < 3; a++) {
    i = skipBlanks(bytes, i, end);
    const te = tokenEnd(bytes, i, end);
    if (i === te) fail(line, `${keyword} needs 3 numbers, got ${a}`);
    const x = parseDecimal(bytes, i, te);
    if (!Number.isFinite(x)) {
      fail(line, `${keyword} needs 3 finite numbers, got ${quoteBytes(bytes, i, te)}`);
    }
    out[o + a] = x;
    i = te;
  }
  // `vn i j k` has exactly three (Wavefront's OBJ specification, "vn"); a fourth number is
  // a line that means something else, not one to read in part. (`v` may carry w or a
  // colour after x y z, which are ignored: see the top of this file.)
  if (isNormal) {
    const extra = skipBlanks(bytes, i, end);
    if (extra < end) {
      fail(
        line,
        `vn has 3 numbers, but the line goes on with ${quoteBytes(bytes, extra, tokenEnd(bytes, extra, end))}`,
      );
    }
  }
  if (isNormal && out[o] === 0 && out[o + 1] === 0 && out[o + 2] === 0) {
    fail(line, 'vn has zero length');
  }
}

/**
 * Parses one face vertex into polygon[n] (0-based position index) and returns its
 * 0-based normal index, or −1 when it has none.
 */
function readFaceVertex(
  bytes: Uint8Array,
  start: number,
  end: number,
  line: number,
  vSoFar: number,
  vnSoFar: number,
  c: Counts,
  polygon: Int32Array,
  n: number,
): number {
  let s1 = -1;
  let s2 = -1;
  for (let i = start; i < end; i++) {
    if (bytes[i] !== Byte.Slash) continue;
    if (s1 < 0) s1 = i;
    else if (s2 < 0) s2 = i;
    else fail(line, `a face vertex has more than 3 fields: ${quoteBytes(bytes, start, end)}`);
  }
  const vEnd = s1 < 0 ? end : s1;
  polygon[n] = resolveIndex(bytes, start, vEnd, line, vSoFar, c.vertices, 'vertex');
  if (s2 < 0 || s2 === end - 1) return -1;
  return resolveIndex(bytes, s2 + 1, end, line, vnSoFar, c.normals, 'normal');
}

function resolveIndex(
  bytes: Uint8Array,
  start: number,
  end: number,
  line: number,
  soFar: number,
  total: number,
  what: string,
): number {
  const x = parseInteger(bytes, start, end);
  if (!Number.isFinite(x) || x === 0) {
    fail(
      line,
      `a face needs ${what} indices (1-based integers), got ${quoteBytes(bytes, start, end)}`,
    );
  }
  const i = x > 0 ? x - 1 : soFar + x;
  if (i < 0 || i >= total) {
    fail(
      line,
      `${what} index ${x} is out of range: the file has ${total} ` +
        (what === 'vertex'
          ? total === 1
            ? 'vertex'
            : 'vertices'
          : total === 1
            ? 'normal'
            : 'normals') +
        (x < 0 ? `, ${soFar} of them before this line` : ''),
    );
  }
  return i;
}

/** Output vertices for distinct (position, normal) pairs; normal −1 is "none". */
class VertexRemap {
  private readonly firstNormal: Int32Array;
  private readonly firstOut: Int32Array;
  private readonly more = new Map<number, number>();
  private readonly normalCount: number;
  private outPosition: Int32Array;
  private outNormal: Int32Array;
  count = 0;

  constructor(vertices: number, normals: number, triangles: number) {
    this.firstNormal = new Int32Array(vertices).fill(-2);
    this.firstOut = new Int32Array(vertices);
    this.normalCount = normals;
    const capacity = Math.min(vertices + 16, 3 * triangles);
    this.outPosition = new Int32Array(capacity);
    this.outNormal = new Int32Array(capacity);
  }

  vertex(p: number, n: number): number {
    const first = this.firstNormal[p];
    if (first === n) return this.firstOut[p];
    if (first === -2) {
      this.firstNormal[p] = n;
      return (this.firstOut[p] = this.add(p, n));
    }
    // Below 2^53: a file of at most 1 GiB has fewer than 2^27 of each.
    const key = p * (this.normalCount + 1) + (n + 1);
    let out = this.more.get(key);
    if (out === undefined) {
      out = this.add(p, n);
      this.more.set(key, out);
    }
    return out;
  }

  private add(p: number, n: number): number {
    if (this.count === this.outPosition.length) {
      const grow = (a: Int32Array) => {
        const b = new Int32Array(Math.max(16, a.length * 2));
        b.set(a);
        return b;
      };
      this.outPosition = grow(this.outPosition);
      this.outNormal = grow(this.outNormal);
    }
    this.outPosition[this.count] = p;
    this.outNormal[this.count] = n;
    return this.count++;
  }

  finish(positions: Float64Array, normalsIn: Float64Array, indices: Uint32Array): RawMesh {
    const count = this.count;
    const outPositions = new Float64Array(count * 3);
    const outNormals = new Float64Array(count * 3);
    for (let i = 0; i < count; i++) {
      const p = this.outPosition[i] * 3;
      outPositions[3 * i] = positions[p];
      outPositions[3 * i + 1] = positions[p + 1];
      outPositions[3 * i + 2] = positions[p + 2];
      const n = this.outNormal[i];
      if (n >= 0) {
        outNormals[3 * i] = normalsIn[3 * n];
        outNormals[3 * i + 1] = normalsIn[3 * n + 1];
        outNormals[3 * i + 2] = normalsIn[3 * n + 2];
      }
    }
    return { positions: outPositions, indices, normals: outNormals };
  }
}
