/**
 * The counts a Draco stream declares, read from its header without decoding it, so
 * that a stream claiming more faces or points than the glTF accessors hold is refused
 * before the decoder allocates for them (decoders.md §2: the sequential method reads
 * its counts as plain varints and trusts them).
 *
 * Layout (Draco bitstream spec, "Header" and "Connectivity"; draco/compression/
 * point_cloud/point_cloud_decoder.cc, mesh/mesh_sequential_decoder.cc,
 * mesh/mesh_edgebreaker_decoder_impl.cc, metadata/metadata_decoder.cc):
 * `"DRACO"`, version major and minor (u8 each), encoder type (u8; 1 = triangular
 * mesh), method (u8; 0 sequential, 1 edgebreaker), flags (u16; 0x8000 = metadata
 * follows). Then the metadata, if flagged, and the connectivity:
 * - sequential: num_faces, num_points (varints from 2.2, u32 before);
 * - edgebreaker: the traversal type (u8), then from 2.2 num_encoded_vertices and
 *   num_faces (varints).
 * Older bitstreams (glTF's Draco is 2.2) are left to the decoder: counts null.
 */

export interface DracoCounts {
  version: string;
  /** 0 sequential, 1 edgebreaker. */
  method: number;
  /** Triangles the stream declares, or null where not read. */
  faces: number | null;
  /** Points (sequential) the stream declares, or null where not read. */
  points: number | null;
}

const MAGIC = [0x44, 0x52, 0x41, 0x43, 0x4f]; // "DRACO"
const METADATA_FLAG = 0x8000;
/** Nested metadata levels followed before giving up on the counts (the decoder decides). */
const MAX_METADATA_STEPS = 10_000;

class Reader {
  pos = 0;
  constructor(readonly bytes: Uint8Array) {}
  u8(): number {
    if (this.pos >= this.bytes.length) throw new RangeError('truncated');
    return this.bytes[this.pos++];
  }
  /** LEB128, at most 5 bytes (a u32; Draco's DecodeVarint<uint32_t>). */
  varint(): number {
    let v = 0;
    for (let i = 0; i < 5; i++) {
      const b = this.u8();
      v += (b & 0x7f) * 2 ** (7 * i);
      if ((b & 0x80) === 0) return v;
    }
    throw new RangeError('varint too long');
  }
  skip(n: number): void {
    if (this.pos + n > this.bytes.length) throw new RangeError('truncated');
    this.pos += n;
  }
}

/** Skips one metadata block and its sub-metadata (iteratively, with a step bound). */
function skipMetadata(r: Reader): void {
  let pending = 1;
  let steps = 0;
  while (pending > 0) {
    if (++steps > MAX_METADATA_STEPS) throw new RangeError('metadata too deep');
    pending--;
    const entries = r.varint();
    for (let i = 0; i < entries; i++) {
      r.skip(r.u8()); // name
      r.skip(r.varint()); // value
    }
    const subs = r.varint();
    if (subs > r.bytes.length) throw new RangeError('metadata count past the stream');
    for (let i = 0; i < subs; i++) r.skip(r.u8()); // each sub-metadata's name; body follows
    pending += subs;
  }
}

/**
 * The header of the Draco stream `bytes`: its method and declared counts; a string
 * saying what is wrong when it is not a Draco triangle mesh.
 */
export function peekDracoCounts(bytes: Uint8Array): DracoCounts | string {
  const r = new Reader(bytes);
  try {
    for (const m of MAGIC) if (r.u8() !== m) return 'is not a Draco stream (no "DRACO" header)';
    const major = r.u8();
    const minor = r.u8();
    const version = `${major}.${minor}`;
    const type = r.u8();
    const method = r.u8();
    const flags = r.u8() | (r.u8() << 8);
    if (type !== 1) return `is a Draco stream of encoder type ${type}, not a triangle mesh (1)`;
    if (method !== 0 && method !== 1) return `has Draco encoder method ${method}, not 0 or 1`;
    const v22 = major > 2 || (major === 2 && minor >= 2);
    if (!v22) return { version, method, faces: null, points: null };
    if (flags & METADATA_FLAG) {
      const attributes = r.varint();
      if (attributes > bytes.length) return 'has a Draco metadata count past the stream';
      for (let i = 0; i < attributes; i++) {
        r.varint(); // attribute unique id
        skipMetadata(r);
      }
      skipMetadata(r);
    }
    if (method === 0) {
      const faces = r.varint();
      const points = r.varint();
      return { version, method, faces, points };
    }
    r.u8(); // traversal decoder type
    r.varint(); // encoded vertices (seams may add points: not compared)
    return { version, method, faces: r.varint(), points: null };
  } catch (e) {
    return `has a Draco header that ends early or is malformed (${(e as Error).message})`;
  }
}
