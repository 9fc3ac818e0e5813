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

/**
 * `a/b/` + `../c.bin` → `a/c.bin`. Leading `..` that climb above a relative base are
 * kept (`../c.bin` names a file beside the scene's folder); an absolute base keeps its
 * leading `/`, and `..` at the root stays at the root.
 */
export function joinPath(base: string, rel: string): string {
  const absolute = base.startsWith('/') || (base === '' && rel.startsWith('/'));
  const parts = (base + rel).split('/');
  const out: string[] = [];
  for (const p of parts) {
    if (p === '.' || p === '') continue;
    if (p === '..' && out.length > 0 && out[out.length - 1] !== '..') out.pop();
    else if (p === '..' && absolute) continue;
    else out.push(p);
  }
  return (absolute ? '/' : '') + out.join('/');
}

/**
 * Whether the normalized path `file` lies inside the normalized folder `folder`
 * (`''`: the scene's folder, which every relative path without a leading `..` is in).
 */
export function isInsideFolder(file: string, folder: string): boolean {
  if (folder === '') return !file.startsWith('/') && file !== '..' && !file.startsWith('../');
  return file.startsWith(folder.endsWith('/') ? folder : folder + '/');
}

/**
 * The path, relative to the scene's folder, of the file a model at `filePath` names by
 * `uri`. A model's resources stay beside it (docs/gltf.md, "Files a model may read"):
 * the path must lie inside the model's folder, or inside the scene's folder (for a bare
 * model the two are one), or inside one of `allowedFolders` (normalized like joinPath's
 * results; the command line's `--allow-read`). URIs with a scheme (http:, file:),
 * absolute paths, backslashes (not a separator in a URI, RFC 3986 §3.3, but one on
 * Windows and in a browser's URL parser) and `..` that climbs out are refused. Links on
 * disk are the reader's to check (src/cli/scene-files.ts), since only it sees them.
 */
export function resolveUri(
  filePath: string,
  uri: string,
  where: string,
  allowedFolders: readonly string[] = [],
): string {
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
  // Checked again once decoded: `%2F` is a slash, `%5C` a backslash, `%3A` a colon.
  if (decoded.startsWith('/') || /[\\\u0000]/.test(decoded)) {
    throw new GltfError(
      `${where}: ${quote(uri)} is not a relative path of forward slashes; only files beside the model can be read`,
    );
  }
  const folder = dirname(filePath);
  const file = joinPath(folder, decoded);
  // A segment with a colon would read as a URL scheme once joined (`a/../http:x`).
  if (/^[a-zA-Z][a-zA-Z0-9+.-]*:/.test(file)) {
    throw new GltfError(`${where}: ${quote(uri)} resolves to ${quote(file)}, which reads as a URL`);
  }
  const modelFolder = joinPath(folder, '');
  const inside =
    isInsideFolder(file, '') ||
    (modelFolder !== '' && isInsideFolder(file, modelFolder)) ||
    allowedFolders.some((f) => isInsideFolder(file, f));
  if (!inside) {
    throw new GltfError(
      `${where}: ${quote(uri)} resolves to ${quote(file)}, outside the model's folder` +
        (modelFolder === '' ? '' : ` (${quote(modelFolder)})`) +
        " and the scene's; a model may read only files beside it (docs/gltf.md)",
    );
  }
  return file;
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
