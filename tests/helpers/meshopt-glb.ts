/**
 * A meshopt-compressed quad made in memory with meshoptimizer's own encoder: positions
 * (ATTRIBUTES, no filter), indices (TRIANGLES) and, optionally, vertex colours through
 * the KHR_meshopt_compression COLOR filter. The views keep their uncompressed layout in a
 * fallback buffer without a URI (as gltfpack writes them); `edit` may change the JSON
 * (or the BIN chunk of compressed streams) before the GLB is made, for hostile cases.
 */
import { MeshoptEncoder } from 'meshoptimizer/encoder';
import { makeGlb } from '../fuzz/gltf-samples.ts';

type Json = Record<string, any>;

export type MeshoptName = 'EXT_meshopt_compression' | 'KHR_meshopt_compression';

export const QUAD_POSITIONS = Float32Array.of(0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0);
export const QUAD_INDICES = Uint16Array.of(0, 1, 2, 0, 2, 3);
/** Linear RGBA per vertex. */
export const QUAD_COLORS = Float32Array.of(1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0.5, 0.25, 0.75, 1);

export interface MeshoptQuadOptions {
  name?: MeshoptName;
  /** Attribute bitstream version: 0 (EXT) or 1 (KHR_meshopt_compression only). */
  version?: 0 | 1;
  /** COLOR_0 through the COLOR filter (KHR). */
  color?: boolean;
  /** NORMAL (+z) through the OCTAHEDRAL filter, as snorm8 (KHR_mesh_quantization). */
  normals?: boolean;
  edit?: (json: Json, bin: Uint8Array) => unknown;
}

const bytesOf = (a: ArrayBufferView) => new Uint8Array(a.buffer, a.byteOffset, a.byteLength);

export async function meshoptQuadGlb(options: MeshoptQuadOptions = {}): Promise<Uint8Array> {
  await MeshoptEncoder.ready;
  const name = options.name ?? 'EXT_meshopt_compression';
  const version = options.version ?? 0;
  const streams: {
    data: Uint8Array;
    count: number;
    stride: number;
    mode: string;
    filter?: string;
    target: number;
  }[] = [
    { data: bytesOf(QUAD_POSITIONS), count: 4, stride: 12, mode: 'ATTRIBUTES', target: 34962 },
    { data: bytesOf(QUAD_INDICES), count: 6, stride: 2, mode: 'TRIANGLES', target: 34963 },
  ];
  if (options.color) {
    const filtered = MeshoptEncoder.encodeFilterColor(QUAD_COLORS, 4, 4, 8);
    streams.push({
      data: filtered,
      count: 4,
      stride: 4,
      mode: 'ATTRIBUTES',
      filter: 'COLOR',
      target: 34962,
    });
  }
  if (options.normals) {
    const n = Float32Array.of(0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0);
    const filtered = MeshoptEncoder.encodeFilterOct(n, 4, 4, 8);
    streams.push({
      data: filtered,
      count: 4,
      stride: 4,
      mode: 'ATTRIBUTES',
      filter: 'OCTAHEDRAL',
      target: 34962,
    });
  }
  const parts: Uint8Array[] = [];
  const views: Json[] = [];
  let bin = 0;
  let fallback = 0;
  for (const s of streams) {
    const encoded = MeshoptEncoder.encodeGltfBuffer(
      s.data,
      s.count,
      s.stride,
      s.mode,
      s.mode === 'ATTRIBUTES' ? version : undefined,
    );
    const ext: Json = {
      buffer: 0,
      byteOffset: bin,
      byteLength: encoded.length,
      byteStride: s.stride,
      count: s.count,
      mode: s.mode,
    };
    if (s.filter !== undefined) ext.filter = s.filter;
    const view: Json = {
      buffer: 1,
      byteOffset: fallback,
      byteLength: s.count * s.stride,
      target: s.target,
      extensions: { [name]: ext },
    };
    if (s.mode === 'ATTRIBUTES') view.byteStride = s.stride;
    views.push(view);
    parts.push(encoded);
    bin += encoded.length;
    const pad = (4 - (bin % 4)) % 4;
    parts.push(new Uint8Array(pad));
    bin += pad;
    fallback += Math.ceil((s.count * s.stride) / 4) * 4;
  }
  let chunk: Uint8Array = new Uint8Array(bin);
  let o = 0;
  for (const p of parts) {
    chunk.set(p, o);
    o += p.length;
  }
  const attributes: Json = { POSITION: 0 };
  const accessors: Json[] = [
    { bufferView: 0, componentType: 5126, count: 4, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] },
    { bufferView: 1, componentType: 5123, count: 6, type: 'SCALAR' },
  ];
  if (options.color) {
    attributes.COLOR_0 = 2;
    accessors.push({
      bufferView: 2,
      componentType: 5121,
      normalized: true,
      count: 4,
      type: 'VEC4',
    });
  }
  if (options.normals) {
    attributes.NORMAL = accessors.length;
    accessors.push({
      bufferView: accessors.length,
      componentType: 5120,
      normalized: true,
      count: 4,
      type: 'VEC3',
    });
  }
  const json: Json = {
    asset: { version: '2.0' },
    extensionsUsed: options.normals ? [name, 'KHR_mesh_quantization'] : [name],
    extensionsRequired: [name],
    buffers: [
      { byteLength: bin },
      { byteLength: fallback, extensions: { [name]: { fallback: true } } },
    ],
    bufferViews: views,
    accessors,
    meshes: [{ primitives: [{ attributes, indices: 1 }] }],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
    scene: 0,
  };
  const edited = options.edit?.(json, chunk);
  if (edited instanceof Uint8Array) chunk = edited;
  return makeGlb(json, chunk);
}
