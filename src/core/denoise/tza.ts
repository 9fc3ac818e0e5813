/**
 * Open Image Denoise's weight container, TZA ("tensor archive", version 2.0), as its
 * training script writes it (RenderKit/oidn training/tza.py) and its core reads it
 * (core/tza.cpp). Little-endian throughout:
 *
 *   header   u16 magic 0x41D7, u8 major 2, u8 minor 0, u64 offset of the table
 *   data     the tensors, each at a 64-byte aligned offset
 *   table    u32 count, then per tensor: u16 name length, the name (ASCII), u8 ndims,
 *            ndims × u32 shape, ndims layout letters (e.g. "oihw", "x"), one dtype letter
 *            ('f' float32 or 'h' float16), u64 offset of its data
 *
 * Every read is checked against the file's length before it happens and every size is
 * bounded, so a hostile file costs at most its own length in work and memory and fails
 * with one FormatError that names the tensor and field. Half floats are widened to
 * float32 exactly (every binary16 value is a float32 value), as OIDN's CPU device does.
 */
import { FormatError } from '../util/format-error.ts';
import { halfToFloat } from '../math/half.ts';

export { halfToFloat };

export interface TzaTensor {
  readonly name: string;
  readonly shape: readonly number[];
  /** One letter per dimension, e.g. "oihw" for a convolution's weights, "x" for a bias. */
  readonly layout: string;
  /** The values, widened to float32, in the file's (row-major) order. */
  readonly data: Float32Array;
}

const MAGIC = 0x41d7;
const MAX_TENSORS = 4096;
const MAX_DIMS = 8;
const MAX_NAME = 256;

function fail(detail: string): never {
  throw new FormatError('TZA', detail);
}

/** Parses a TZA file into its tensors by name; throws FormatError on any malformed byte. */
export function parseTza(bytes: Uint8Array): Map<string, TzaTensor> {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const size = bytes.byteLength;
  let p = 0;
  const need = (n: number, what: string): void => {
    if (p + n > size) fail(`file ends inside ${what} (at byte ${p}, file has ${size})`);
  };
  need(12, 'the header');
  const magic = view.getUint16(0, true);
  if (magic !== MAGIC) fail(`bad magic 0x${magic.toString(16)} (expected 0x41d7)`);
  const major = view.getUint8(2);
  const minor = view.getUint8(3);
  if (major !== 2) fail(`unsupported version ${major}.${minor} (expected 2.x)`);
  const tableOffset = Number(view.getBigUint64(4, true));
  if (tableOffset < 12 || tableOffset > size)
    fail(`table offset ${tableOffset} is outside the file (${size} bytes)`);
  p = tableOffset;
  need(4, 'the tensor count');
  const count = view.getUint32(p, true);
  p += 4;
  if (count > MAX_TENSORS) fail(`${count} tensors (at most ${MAX_TENSORS})`);
  const tensors = new Map<string, TzaTensor>();
  for (let t = 0; t < count; t++) {
    const where = `tensor ${t}`;
    need(2, `${where}'s name length`);
    const nameLength = view.getUint16(p, true);
    p += 2;
    if (nameLength === 0 || nameLength > MAX_NAME) fail(`${where}'s name has length ${nameLength}`);
    need(nameLength, `${where}'s name`);
    let name = '';
    for (let i = 0; i < nameLength; i++) {
      const c = bytes[p + i]!;
      if (c < 0x20 || c > 0x7e) fail(`${where}'s name has the non-printable byte ${c}`);
      name += String.fromCharCode(c);
    }
    p += nameLength;
    const at = `tensor "${name}"`;
    if (tensors.has(name)) fail(`${at} appears twice`);
    need(1, `${at}'s dimension count`);
    const ndims = view.getUint8(p);
    p += 1;
    if (ndims === 0 || ndims > MAX_DIMS) fail(`${at} has ${ndims} dimensions`);
    need(4 * ndims, `${at}'s shape`);
    const shape: number[] = [];
    let elements = 1;
    for (let d = 0; d < ndims; d++) {
      const n = view.getUint32(p, true);
      p += 4;
      if (n === 0) fail(`${at} has an empty dimension ${d}`);
      shape.push(n);
      elements *= n;
      if (elements > size) fail(`${at} has more elements than the file has bytes`);
    }
    need(ndims + 1, `${at}'s layout and type`);
    let layout = '';
    for (let d = 0; d < ndims; d++) layout += String.fromCharCode(bytes[p + d]!);
    if (!/^[a-z]+$/.test(layout)) fail(`${at} has the layout "${layout}"`);
    p += ndims;
    const dtype = String.fromCharCode(bytes[p]!);
    p += 1;
    if (dtype !== 'f' && dtype !== 'h')
      fail(`${at} has the data type '${dtype}' (expected 'f' or 'h')`);
    need(8, `${at}'s data offset`);
    const offset = Number(view.getBigUint64(p, true));
    p += 8;
    const width = dtype === 'f' ? 4 : 2;
    if (offset < 12 || offset + elements * width > size)
      fail(
        `${at}'s data (${elements} × ${width} bytes at ${offset}) is outside the file (${size} bytes)`,
      );
    const data = new Float32Array(elements);
    if (dtype === 'f')
      for (let i = 0; i < elements; i++) data[i] = view.getFloat32(offset + 4 * i, true);
    else
      for (let i = 0; i < elements; i++)
        data[i] = halfToFloat(view.getUint16(offset + 2 * i, true));
    for (let i = 0; i < elements; i++)
      if (!Number.isFinite(data[i]!)) fail(`${at} holds a non-finite value at ${i}`);
    tensors.set(name, { name, shape, layout, data });
  }
  return tensors;
}
