/**
 * The GLB container (glTF 2.0 §4.4): a 12-byte header (magic "glTF",
 * version 2, total length), a JSON chunk, then an optional BIN chunk. Checked
 * here, before anything reads it, so that a truncated or lying file gets one
 * clear error instead of a RangeError from deep inside a library.
 */
import { GltfError } from './errors.ts';

const MAGIC = 0x46546c67; // "glTF"
const CHUNK_JSON = 0x4e4f534a; // "JSON"
const CHUNK_BIN = 0x004e4942; // "BIN\0"

export function isGlb(bytes: Uint8Array): boolean {
  return (
    bytes.length >= 4 &&
    bytes[0] === 0x67 &&
    bytes[1] === 0x6c &&
    bytes[2] === 0x54 &&
    bytes[3] === 0x46
  );
}

export interface GlbChunks {
  json: Uint8Array;
  /** The BIN chunk, or null when the file has none. */
  bin: Uint8Array | null;
}

export function parseGlb(bytes: Uint8Array): GlbChunks {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.length < 12) {
    throw new GltfError(`GLB header: file is ${bytes.length} bytes, the header alone needs 12`);
  }
  if (view.getUint32(0, true) !== MAGIC) throw new GltfError('GLB header: magic is not "glTF"');
  const version = view.getUint32(4, true);
  if (version !== 2) {
    throw new GltfError(`GLB header: version ${version}, only glTF 2.0 (version 2) is supported`);
  }
  const length = view.getUint32(8, true);
  if (length > bytes.length) {
    throw new GltfError(
      `GLB header: says ${length} bytes, but the file has ${bytes.length} (truncated?)`,
    );
  }
  if (length < 20)
    throw new GltfError(`GLB header: length ${length} leaves no room for the JSON chunk`);
  const jsonLength = view.getUint32(12, true);
  if (view.getUint32(16, true) !== CHUNK_JSON) {
    throw new GltfError('GLB chunk 0: the first chunk must be JSON');
  }
  if (20 + jsonLength > length) {
    throw new GltfError(
      `GLB chunk 0: JSON chunk of ${jsonLength} bytes runs past the end of the file (${length} bytes)`,
    );
  }
  const json = bytes.subarray(20, 20 + jsonLength);
  let p = 20 + jsonLength;
  // Chunks start on 4-byte boundaries; a writer that did not pad is tolerated.
  if (p % 4 !== 0 && p + 8 > length) p = length;
  let bin: Uint8Array | null = null;
  if (p + 8 <= length) {
    const binLength = view.getUint32(p, true);
    const type = view.getUint32(p + 4, true);
    if (p + 8 + binLength > length) {
      throw new GltfError(
        `GLB chunk 1: chunk of ${binLength} bytes runs past the end of the file (${length} bytes)`,
      );
    }
    if (type === CHUNK_BIN) bin = bytes.subarray(p + 8, p + 8 + binLength);
  }
  return { json, bin };
}
