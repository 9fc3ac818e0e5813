/**
 * Getting a glTF file's resources: external buffers and images through the
 * injected reader (the same `read(path, maxBytes)` as every other scene
 * file, so the core needs neither fs nor fetch), `data:` URIs decoded here,
 * and a glTF-Transform I/O that reads only what was handed to it.
 */
import { PlatformIO } from '@gltf-transform/core';
import { quote } from '../util/message.ts';
import { GltfError } from './errors.ts';

import type { GltfFileReader } from '../scene/format/gltf-model.ts';

export type { GltfFileReader };

/**
 * glTF-Transform I/O over resources that are already in memory: every
 * buffer and image was read (and bounds-checked) before `readJSON`.
 */
export class PreloadedIO extends PlatformIO {
  protected async readURI(uri: string, _type: 'view' | 'text'): Promise<never> {
    throw new GltfError(`resource ${quote(uri)} was not preloaded`);
  }
  protected resolve(base: string, path: string): string {
    return joinPath(base, path);
  }
  protected dirname(uri: string): string {
    return dirname(uri);
  }
}

export function dirname(path: string): string {
  const i = path.lastIndexOf('/');
  return i < 0 ? '' : path.slice(0, i + 1);
}

/** `a/b/` + `../c.bin` → `a/c.bin`; leading `..` that climb above the base are kept. */
export function joinPath(base: string, rel: string): string {
  const parts = (base + rel).split('/');
  const out: string[] = [];
  for (const p of parts) {
    if (p === '.' || p === '') continue;
    if (p === '..' && out.length > 0 && out[out.length - 1] !== '..') out.pop();
    else out.push(p);
  }
  return out.join('/');
}

/**
 * The path of a relative URI of the file at `filePath`. URIs with a scheme
 * (http:, file:) and absolute paths are refused: a model's resources live
 * beside it.
 */
export function resolveUri(filePath: string, uri: string, where: string): string {
  if (/^[a-zA-Z][a-zA-Z0-9+.-]*:/.test(uri) || uri.startsWith('/')) {
    throw new GltfError(
      `${where}: ${quote(uri)} is not a relative path; only files beside the model can be read`,
    );
  }
  let decoded: string;
  try {
    decoded = decodeURIComponent(uri);
  } catch {
    throw new GltfError(`${where}: ${quote(uri)} is not a valid URI`);
  }
  return joinPath(dirname(filePath), decoded);
}

const BASE64 = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/';
let lookup: Int16Array | null = null;

/** The bytes of a `data:` URI (base64 or percent-encoded). */
export function decodeDataUri(uri: string, where: string): Uint8Array {
  const comma = uri.indexOf(',');
  if (comma < 0) throw new GltfError(`${where}: data URI without a comma`);
  const header = uri.slice(5, comma);
  const body = uri.slice(comma + 1);
  if (!header.endsWith(';base64')) {
    let text: string;
    try {
      text = decodeURIComponent(body);
    } catch {
      throw new GltfError(`${where}: data URI is not valid percent-encoding`);
    }
    const out = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) out[i] = text.charCodeAt(i) & 0xff;
    return out;
  }
  if (lookup === null) {
    lookup = new Int16Array(128).fill(-1);
    for (let i = 0; i < 64; i++) lookup[BASE64.charCodeAt(i)] = i;
  }
  let end = body.length;
  while (end > 0 && body[end - 1] === '=') end--;
  const out = new Uint8Array(Math.floor((end * 3) / 4));
  let acc = 0;
  let bits = 0;
  let o = 0;
  for (let i = 0; i < end; i++) {
    const c = body.charCodeAt(i);
    const v = c < 128 ? lookup[c] : -1;
    if (v < 0) throw new GltfError(`${where}: data URI has a character that is not base64 at ${i}`);
    acc = (acc << 6) | v;
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out[o++] = (acc >> bits) & 0xff;
    }
  }
  return out.subarray(0, o);
}
