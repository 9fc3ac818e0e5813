/**
 * Byte helpers for the generators: a growable writer with both byte orders, CRC-32
 * written from its definition (ISO 3309), not taken from the
 * project's readers, so that a generator cannot share a reader's mistake.
 */
export type Files = Record<string, Uint8Array>;

export const ascii = (s: string): Uint8Array => new TextEncoder().encode(s);

export function concat(parts: readonly Uint8Array[]): Uint8Array {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
}

export class ByteWriter {
  private buf = new Uint8Array(256);
  private view = new DataView(this.buf.buffer);
  length = 0;
  private grow(n: number): void {
    if (this.length + n <= this.buf.length) return;
    let size = this.buf.length * 2;
    while (size < this.length + n) size *= 2;
    const next = new Uint8Array(size);
    next.set(this.buf.subarray(0, this.length));
    this.buf = next;
    this.view = new DataView(next.buffer);
  }
  u8(v: number): this {
    this.grow(1);
    this.buf[this.length++] = v & 0xff;
    return this;
  }
  bytes(b: ArrayLike<number>): this {
    this.grow(b.length);
    this.buf.set(b, this.length);
    this.length += b.length;
    return this;
  }
  text(s: string): this {
    return this.bytes(ascii(s));
  }
  u16(v: number, le: boolean): this {
    this.grow(2);
    this.view.setUint16(this.length, v, le);
    this.length += 2;
    return this;
  }
  u32(v: number, le: boolean): this {
    this.grow(4);
    this.view.setUint32(this.length, v >>> 0, le);
    this.length += 4;
    return this;
  }
  i8(v: number): this {
    this.grow(1);
    this.view.setInt8(this.length, v);
    this.length += 1;
    return this;
  }
  i16(v: number, le: boolean): this {
    this.grow(2);
    this.view.setInt16(this.length, v, le);
    this.length += 2;
    return this;
  }
  i32(v: number, le: boolean): this {
    this.grow(4);
    this.view.setInt32(this.length, v, le);
    this.length += 4;
    return this;
  }
  f32(v: number, le: boolean): this {
    this.grow(4);
    this.view.setFloat32(this.length, v, le);
    this.length += 4;
    return this;
  }
  f64(v: number, le: boolean): this {
    this.grow(8);
    this.view.setFloat64(this.length, v, le);
    this.length += 8;
    return this;
  }
  done(): Uint8Array {
    return this.buf.slice(0, this.length);
  }
}

let crcTable: Uint32Array | undefined;
/** CRC-32 of ISO 3309 / ITU-T V.42 (reflected, polynomial 0xEDB88320), as PNG 1.2 §3.4. */
export function crc32(bytes: Uint8Array, start = 0, end = bytes.length): number {
  if (!crcTable) {
    crcTable = new Uint32Array(256);
    for (let n = 0; n < 256; n++) {
      let c = n;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[n] = c >>> 0;
    }
  }
  let c = 0xffffffff;
  for (let i = start; i < end; i++) c = crcTable[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

export function base64(bytes: Uint8Array): string {
  return Buffer.from(bytes).toString('base64');
}
