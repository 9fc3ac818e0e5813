/**
 * Small glTF files for the hostile-input table (formats.ts), made
 * synchronously from JSON and binary data: a GLB quad (indexed, with normals
 * and texture coordinates), the same with a 1×1 PNG base colour texture in
 * its buffer, and a .gltf whose buffer is a data: URI. A few hundred bytes
 * each, so that every prefix can be tried.
 */
import { encode as encodePng } from 'fast-png';

type Json = Record<string, unknown>;

const POSITIONS = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0];
const NORMALS = [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1];
const UVS = [0, 1, 1, 1, 1, 0, 0, 0];
const INDICES = [0, 1, 2, 0, 2, 3];

/** Offset of vertex 2's y in the binary data (for NaN injection). */
export const POSITION_Y2_OFFSET = 2 * 12 + 4;

function quadBinary(image: Uint8Array | null): { bin: Uint8Array; json: Json } {
  const parts: Uint8Array[] = [
    new Uint8Array(Float32Array.from(POSITIONS).buffer),
    new Uint8Array(Float32Array.from(NORMALS).buffer),
    new Uint8Array(Float32Array.from(UVS).buffer),
    new Uint8Array(Uint16Array.from(INDICES).buffer),
  ];
  if (image !== null) parts.push(image);
  const views: Json[] = [];
  let offset = 0;
  for (const p of parts) {
    views.push({ buffer: 0, byteOffset: offset, byteLength: p.length });
    offset += Math.ceil(p.length / 4) * 4;
  }
  const bin = new Uint8Array(offset);
  parts.forEach((p, i) => bin.set(p, views[i].byteOffset as number));
  const json: Json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, translation: [0, 0, -1] }],
    meshes: [
      {
        primitives: [
          {
            attributes: { POSITION: 0, NORMAL: 1, TEXCOORD_0: 2 },
            indices: 3,
            ...(image !== null ? { material: 0 } : {}),
          },
        ],
      },
    ],
    accessors: [
      {
        bufferView: 0,
        componentType: 5126,
        count: 4,
        type: 'VEC3',
        min: [0, 0, 0],
        max: [1, 1, 0],
      },
      { bufferView: 1, componentType: 5126, count: 4, type: 'VEC3' },
      { bufferView: 2, componentType: 5126, count: 4, type: 'VEC2' },
      { bufferView: 3, componentType: 5123, count: 6, type: 'SCALAR' },
    ],
    bufferViews: views.slice(0, 4),
    buffers: [{ byteLength: bin.length }],
  };
  if (image !== null) {
    (json.bufferViews as Json[]).push(views[4]);
    json.images = [{ bufferView: 4, mimeType: 'image/png' }];
    json.textures = [{ source: 0 }];
    json.materials = [
      { pbrMetallicRoughness: { baseColorTexture: { index: 0 }, metallicFactor: 0 } },
    ];
  }
  return { bin, json };
}

/** A GLB from JSON and a BIN chunk. */
export function makeGlb(json: Json, bin: Uint8Array | null): Uint8Array {
  const text = new TextEncoder().encode(JSON.stringify(json));
  const jl = Math.ceil(text.length / 4) * 4;
  const bl = bin === null ? 0 : Math.ceil(bin.length / 4) * 4;
  const out = new Uint8Array(20 + jl + (bin === null ? 0 : 8 + bl));
  const v = new DataView(out.buffer);
  v.setUint32(0, 0x46546c67, true);
  v.setUint32(4, 2, true);
  v.setUint32(8, out.length, true);
  v.setUint32(12, jl, true);
  v.setUint32(16, 0x4e4f534a, true);
  out.set(text, 20);
  out.fill(0x20, 20 + text.length, 20 + jl);
  if (bin !== null) {
    v.setUint32(20 + jl, bl, true);
    v.setUint32(24 + jl, 0x004e4942, true);
    out.set(bin, 28 + jl);
  }
  return out;
}

/** The quad as a GLB; `edit` may change its JSON or binary first. */
export function quadGlb(
  options: { texture?: boolean; edit?: (json: Json, bin: Uint8Array) => void } = {},
): Uint8Array {
  const image = options.texture
    ? encodePng({
        width: 1,
        height: 1,
        data: Uint8Array.of(200, 100, 50, 255),
        channels: 4,
        depth: 8,
      })
    : null;
  const { json, bin } = quadBinary(image);
  options.edit?.(json, bin);
  return makeGlb(json, bin);
}

/** The quad as a .gltf whose buffer is a base64 data: URI; `edit` may change its JSON first. */
export function quadGltfDataUri(options: { edit?: (json: Json) => void } = {}): Uint8Array {
  const { json, bin } = quadBinary(null);
  options.edit?.(json);
  (json.buffers as Json[])[0].uri =
    'data:application/octet-stream;base64,' + Buffer.from(bin).toString('base64');
  return new TextEncoder().encode(JSON.stringify(json));
}
