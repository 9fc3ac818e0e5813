/**
 * The three ways a glTF 2.0 asset is stored (spec §3.6.1.1, §4.4): a `.gltf` with its
 * buffer and image in files beside it, a `.gltf` with everything in `data:` URIs (RFC 2397,
 * base64), and a binary `.glb` (§4.4: a 12-byte header, a JSON chunk padded with spaces, a
 * BIN chunk padded with zeros, each chunk's length a multiple of 4).
 */
import { ByteWriter, ascii, base64, concat, type Files } from './bytes.ts';
import type { Json, Model } from './gltf-doc.ts';

export type Container = 'gltf' | 'glb' | 'data';
/** Models live two folders down, so that `../../x` leaves both the model's and the scene's. */
export const MODEL_DIR = 's/m';

export function modelPath(container: Container): string {
  return `${MODEL_DIR}/model.${container === 'glb' ? 'glb' : 'gltf'}`;
}

const pad4 = (n: number) => (n + 3) & ~3;

export interface GlbLies {
  totalLength?: number;
  jsonLength?: number;
  binLength?: number;
  version?: number;
  magic?: number;
  jsonType?: number;
}

export function glb(json: Json, bin: Uint8Array | null, lies: GlbLies = {}): Uint8Array {
  const j = ascii(JSON.stringify(json));
  const jLen = pad4(j.length);
  const bLen = bin ? pad4(bin.length) : 0;
  const total = 12 + 8 + jLen + (bin ? 8 + bLen : 0);
  const w = new ByteWriter()
    .u32(lies.magic ?? 0x46546c67, true)
    .u32(lies.version ?? 2, true)
    .u32(lies.totalLength ?? total, true)
    .u32(lies.jsonLength ?? jLen, true)
    .u32(lies.jsonType ?? 0x4e4f534a, true)
    .bytes(j);
  for (let i = j.length; i < jLen; i++) w.u8(0x20);
  if (bin) {
    w.u32(lies.binLength ?? bLen, true)
      .u32(0x004e4942, true)
      .bytes(bin);
    for (let i = bin.length; i < bLen; i++) w.u8(0);
  }
  return w.done();
}

/** The files of `m` stored as `container`; the JSON is copied, never changed in place. */
export function pack(m: Model, container: Container): Files {
  const json = structuredClone(m.json);
  let bin = m.bin;
  const dir = MODEL_DIR;
  if (m.image && json.images?.[0]) {
    const img = json.images[0];
    if (container === 'glb') {
      const offset = pad4(bin.length);
      bin = concat([bin, new Uint8Array(offset - bin.length), m.image.bytes]);
      json.bufferViews.push({ buffer: 0, byteOffset: offset, byteLength: m.image.bytes.length });
      img.bufferView = json.bufferViews.length - 1;
      json.buffers[0].byteLength = bin.length;
    } else if (container === 'gltf') {
      img.uri ??= m.image.mime === 'image/jpeg' ? 'tex.jpg' : 'tex.png';
      delete img.mimeType;
    } else {
      img.uri ??= `data:${m.image.mime};base64,${base64(m.image.bytes)}`;
    }
  }
  if (container === 'glb') {
    return { [`${dir}/model.glb`]: glb(json, json.buffers[0].uri === undefined ? bin : null) };
  }
  const files: Files = {};
  if (container === 'gltf') {
    json.buffers[0].uri ??= 'model.bin';
    files[`${dir}/model.bin`] = bin;
    if (m.image)
      files[`${dir}/${m.image.mime === 'image/jpeg' ? 'tex.jpg' : 'tex.png'}`] = m.image.bytes;
  } else {
    json.buffers[0].uri ??= `data:application/octet-stream;base64,${base64(bin)}`;
  }
  files[`${dir}/model.gltf`] = ascii(JSON.stringify(json, null, 1));
  return files;
}
