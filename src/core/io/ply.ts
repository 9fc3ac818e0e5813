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
 * index (and, in an ASCII body, the line). The header is ply-header.ts; the bodies,
 * ply-ascii.ts (one line per instance, checked) and ply-binary.ts.
 */
import { checkCancel } from '../util/cancel.ts';
import type { RawMesh } from '../geometry/mesh-data.ts';
import type { MeshLimits } from './obj.ts';
import { FormatError } from './format-error.ts';
import { AsciiBody } from './ply-ascii.ts';
import { BinaryBody } from './ply-binary.ts';
import {
  checkLayout,
  checkSizes,
  parseHeader,
  type Element,
  type Header,
  type Layout,
  type Reader,
} from './ply-header.ts';

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

/** Reads past one instance of an element; returns the length of list `list` (or −1). */
function skipInstance(reader: Reader, element: Element, index: number, list: number): number {
  let length = -1;
  const props = element.properties;
  reader.begin(element, index);
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
  reader.end(element, index);
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
  reader.finish();
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
        reader.begin(e, i);
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
        reader.end(e, i);
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
        reader.begin(e, i);
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
        reader.end(e, i);
      }
    } else {
      for (let i = 0; i < e.count; i++) skipInstance(reader, e, i, -1);
    }
  });
  return { positions, indices, normals };
}
