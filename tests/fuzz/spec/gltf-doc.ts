/**
 * A glTF 2.0 asset written from the Khronos specification (2.0.1): a textured box as one
 * indexed primitive (§3.7.2: POSITION with min/max, NORMAL, TEXCOORD_0), accessors over
 * 4-byte-aligned buffer views (§3.6.2), a node hierarchy with TRS (§3.5), an optional
 * perspective camera (§3.10), a metallic–roughness material with a base-colour texture.
 * Packing into .gltf/.glb/data URIs is gltf-pack.ts.
 */
import { ByteWriter } from './bytes.ts';
import type { Rng } from './rng.ts';

export type Json = Record<string, any>; // eslint-disable-line @typescript-eslint/no-explicit-any

export interface Model {
  json: Json;
  /** The geometry buffer (buffer 0); an embedded image is appended by the packer. */
  bin: Uint8Array;
  image?: { bytes: Uint8Array; mime: string };
}

export const FLOAT = 5126;
export const UNSIGNED_SHORT = 5123;
export const UNSIGNED_INT = 5125;
export const UNSIGNED_BYTE = 5121;

/** 24 vertices (4 a face, so that each face has its own normal and UVs), 12 triangles. */
function box(): { pos: number[][]; nrm: number[][]; uv: number[][]; idx: number[] } {
  const pos: number[][] = [];
  const nrm: number[][] = [];
  const uv: number[][] = [];
  const idx: number[] = [];
  const axes = [
    [0, 1, 2],
    [1, 2, 0],
    [2, 0, 1],
  ];
  for (const [a, b, c] of axes) {
    for (const s of [1, -1]) {
      const base = pos.length;
      for (const [u, v] of [
        [-1, -1],
        [1, -1],
        [1, 1],
        [-1, 1],
      ]) {
        const p = [0, 0, 0];
        p[a] = s * 0.5;
        p[b] = u * 0.5 * s;
        p[c] = v * 0.5;
        pos.push(p);
        const n = [0, 0, 0];
        n[a] = s;
        nrm.push(n);
        uv.push([(u + 1) / 2, (v + 1) / 2]);
      }
      idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
    }
  }
  return { pos, nrm, uv, idx };
}

export function buildModel(rng: Rng, image?: { bytes: Uint8Array; mime: string }): Model {
  const { pos, nrm, uv, idx } = box();
  const w = new ByteWriter();
  const views: Json[] = [];
  const view = (write: () => void, target?: number) => {
    while (w.length % 4) w.u8(0);
    const byteOffset = w.length;
    write();
    views.push({
      buffer: 0,
      byteOffset,
      byteLength: w.length - byteOffset,
      ...(target ? { target } : {}),
    });
    return views.length - 1;
  };
  const vPos = view(() => pos.flat().forEach((v) => w.f32(v, true)), 34962);
  const vNrm = view(() => nrm.flat().forEach((v) => w.f32(v, true)), 34962);
  const vUv = view(() => uv.flat().forEach((v) => w.f32(v, true)), 34962);
  const indexType = rng.pick([UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT]);
  const vIdx = view(() => {
    for (const i of idx) {
      if (indexType === UNSIGNED_BYTE) w.u8(i);
      else if (indexType === UNSIGNED_SHORT) w.u16(i, true);
      else w.u32(i, true);
    }
  }, 34963);
  while (w.length % 4) w.u8(0);
  const bin = w.done();
  const accessors: Json[] = [
    {
      bufferView: vPos,
      componentType: FLOAT,
      count: 24,
      type: 'VEC3',
      min: [-0.5, -0.5, -0.5],
      max: [0.5, 0.5, 0.5],
    },
    { bufferView: vNrm, componentType: FLOAT, count: 24, type: 'VEC3' },
    { bufferView: vUv, componentType: FLOAT, count: 24, type: 'VEC2' },
    { bufferView: vIdx, componentType: indexType, count: 36, type: 'SCALAR' },
  ];
  const material: Json = {
    name: 'painted',
    pbrMetallicRoughness: {
      baseColorFactor: [0.9, 0.8, 0.7, 1],
      metallicFactor: 0,
      roughnessFactor: 0.7,
    },
    doubleSided: rng.chance(0.5),
  };
  const json: Json = {
    asset: { version: '2.0', generator: 'pathwise spec-fuzz' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [
      { name: 'root', children: [1], rotation: [0, Math.sin(0.3), 0, Math.cos(0.3)] },
      {
        name: 'box',
        mesh: 0,
        translation: [rng.float(-0.2, 0.2), 0, 0],
        scale: [1, rng.float(0.5, 1.5), 1],
      },
    ],
    meshes: [
      {
        primitives: [
          {
            attributes: { POSITION: 0, NORMAL: 1, TEXCOORD_0: 2 },
            indices: 3,
            material: 0,
            mode: 4,
          },
        ],
      },
    ],
    materials: [material],
    accessors,
    bufferViews: views,
    buffers: [{ byteLength: bin.length }],
  };
  if (rng.chance(0.3)) {
    // A camera 3 units back along +z looking down −z (§3.10.1: cameras look along −z).
    json.cameras = [
      { type: 'perspective', perspective: { yfov: 0.8, znear: 0.05, zfar: 100, aspectRatio: 1 } },
    ];
    json.nodes.push({ name: 'eye', camera: 0, translation: [0, 0, 3] });
    json.scenes[0].nodes.push(2);
  }
  if (image) {
    material.pbrMetallicRoughness.baseColorTexture = { index: 0 };
    json.textures = [{ source: 0, sampler: 0 }];
    json.samplers = [{ magFilter: 9729, minFilter: 9987, wrapS: 10497, wrapT: 33648 }];
    json.images = [{ mimeType: image.mime }];
  }
  return { json, bin, image };
}
