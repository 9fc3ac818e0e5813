/**
 * A buffer of bytes the loader decoded itself (meshopt views, Draco primitives), added
 * to the document as one more `buffers` entry with a synthetic URI that names no file.
 * Once the decoding pre-passes have pointed the views at it, glTF-Transform and the
 * byte-range checks (validate-buffers.ts) see a plain glTF file, and check real bytes.
 */
type Json = Record<string, unknown>;

export class DecodedBuffer {
  private readonly parts: Uint8Array[] = [];
  private length = 0;
  /** Index of the buffer in `json.buffers`, reserved when the first part is added. */
  private index = -1;

  constructor(
    private readonly json: Json,
    /** Synthetic resource name, `@meshopt` or `@draco`: starts with `@`, so no file. */
    private readonly uri: string,
  ) {}

  /**
   * Appends `bytes` at an offset that is a multiple of 4 (glTF 2.0 §3.6.2.4: vertex
   * attribute elements and accessor offsets stay aligned), and returns the buffer's
   * index and that offset, to be written into a bufferView.
   */
  add(bytes: Uint8Array): { buffer: number; byteOffset: number } {
    if (this.index < 0) {
      const buffers = (this.json.buffers ??= []) as Json[];
      this.index = buffers.length;
      buffers.push({ uri: this.uri, byteLength: 0 });
    }
    const pad = (4 - (this.length % 4)) % 4;
    if (pad > 0) this.parts.push(new Uint8Array(pad));
    const byteOffset = this.length + pad;
    this.parts.push(bytes);
    this.length = byteOffset + bytes.length;
    return { buffer: this.index, byteOffset };
  }

  /**
   * Joins the parts and registers the bytes: in `resources` under the URI, for
   * glTF-Transform, and as `data[index]`, for the loader's own checks. Nothing added:
   * nothing done.
   */
  finish(resources: Record<string, Uint8Array>, data: Uint8Array[]): void {
    if (this.index < 0) return;
    const bytes = new Uint8Array(this.length);
    let o = 0;
    for (const p of this.parts) {
      bytes.set(p, o);
      o += p.length;
    }
    this.parts.length = 0;
    ((this.json.buffers as Json[])[this.index] as Json).byteLength = bytes.length;
    resources[this.uri] = bytes;
    data[this.index] = bytes;
  }
}

/** Removes `names` from extensionsUsed and extensionsRequired (their data is decoded). */
export function dropExtensionNames(json: Json, names: readonly string[]): void {
  for (const key of ['extensionsUsed', 'extensionsRequired']) {
    const list = json[key];
    if (!Array.isArray(list)) continue;
    const kept = list.filter((n) => !names.includes(n as string));
    if (kept.length > 0) json[key] = kept;
    else delete json[key];
  }
}
