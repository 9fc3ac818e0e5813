/**
 * A `.glb` writer for the generator's glTF family (archetypes-gltf.ts): one mesh of
 * one primitive (POSITION, NORMAL, TEXCOORD_0, TANGENT, u32 indices) under one node,
 * with one material given as glTF JSON, extensions and all. The JSON and the binary
 * chunk are laid out by hand (glTF 2.0 §4.4: 12-byte header, JSON chunk padded with
 * spaces, BIN chunk padded with zeros, every chunk 4-byte aligned), so the file is
 * exactly what the test asks for: the loader under test parses it, not a library
 * shared with it.
 */
import type { LocalMesh } from './meshes.ts';

/** A glTF material object (`materials[0]`), e.g. `{ pbrMetallicRoughness: {…}, extensions: {…} }`. */
export type GltfMaterialJson = Record<string, unknown> & {
  extensions?: Record<string, unknown>;
};

/** A glTF object and its material, for the generator to write as a `.glb`. */
export interface GltfObject {
  mesh: LocalMesh;
  material: GltfMaterialJson;
  /** Row-major 4×4 placing the model (the scene's `transform`). */
  transform: number[];
}

const encoder = new TextEncoder();

/**
 * Texture coordinates and tangents for a mesh that has none: a planar (x, z) map, and the
 * tangent along +x made orthogonal to the normal (Gram–Schmidt), falling back to +z where
 * the normal is along x. Anisotropic lobes only need *a* smooth frame; it need not match
 * MikkTSpace.
 */
function uvAndTangents(m: LocalMesh): { uv: Float32Array; tangents: Float32Array } {
  const n = m.positions.length / 3;
  const uv = new Float32Array(2 * n);
  const tangents = new Float32Array(4 * n);
  for (let i = 0; i < n; i++) {
    uv[2 * i] = m.positions[3 * i] * 0.5 + 0.5;
    uv[2 * i + 1] = m.positions[3 * i + 2] * 0.5 + 0.5;
    const nx = m.normals[3 * i];
    const ny = m.normals[3 * i + 1];
    const nz = m.normals[3 * i + 2];
    let ax = 1;
    let az = 0;
    if (Math.abs(nx) > 0.9) {
      ax = 0;
      az = 1;
    }
    const d = ax * nx + az * nz;
    let tx = ax - d * nx;
    let ty = -d * ny;
    let tz = az - d * nz;
    const l = Math.hypot(tx, ty, tz);
    tx /= l;
    ty /= l;
    tz /= l;
    tangents.set([tx, ty, tz, 1], 4 * i);
  }
  return { uv, tangents };
}

function minMax(a: ArrayLike<number>): { min: number[]; max: number[] } {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < a.length; i++) {
    min[i % 3] = Math.min(min[i % 3], a[i]);
    max[i % 3] = Math.max(max[i % 3], a[i]);
  }
  return { min, max };
}

/** The mesh and material as a glb; `extensionsUsed` lists the material's extensions. */
export function encodeGlb(mesh: LocalMesh, material: GltfMaterialJson): Uint8Array {
  const positions = Float32Array.from(mesh.positions);
  const normals = Float32Array.from(mesh.normals);
  const { uv, tangents } = uvAndTangents(mesh);
  const indices = Uint32Array.from(mesh.indices);
  const parts: ArrayBufferView[] = [positions, normals, uv, tangents, indices];
  const views: { byteOffset: number; byteLength: number; target: number }[] = [];
  let offset = 0;
  for (const p of parts) {
    views.push({
      byteOffset: offset,
      byteLength: p.byteLength,
      target: p === indices ? 34963 : 34962,
    });
    offset += p.byteLength; // every part is a multiple of 4 bytes
  }
  const bin = new Uint8Array(offset);
  parts.forEach((p, i) =>
    bin.set(new Uint8Array(p.buffer, p.byteOffset, p.byteLength), views[i].byteOffset),
  );
  const n = positions.length / 3;
  const used = Object.keys(material.extensions ?? {});
  const json = {
    asset: { version: '2.0', generator: 'pathwise tests/validation/gltf-files.ts' },
    ...(used.length > 0 ? { extensionsUsed: used } : {}),
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [
      {
        primitives: [
          {
            attributes: { POSITION: 0, NORMAL: 1, TEXCOORD_0: 2, TANGENT: 3 },
            indices: 4,
            material: 0,
          },
        ],
      },
    ],
    materials: [material],
    buffers: [{ byteLength: bin.length }],
    bufferViews: views.map((v) => ({ buffer: 0, ...v })),
    accessors: [
      { bufferView: 0, componentType: 5126, count: n, type: 'VEC3', ...minMax(positions) },
      { bufferView: 1, componentType: 5126, count: n, type: 'VEC3' },
      { bufferView: 2, componentType: 5126, count: n, type: 'VEC2' },
      { bufferView: 3, componentType: 5126, count: n, type: 'VEC4' },
      { bufferView: 4, componentType: 5125, count: indices.length, type: 'SCALAR' },
    ],
  };
  let text = encoder.encode(JSON.stringify(json));
  const padded = new Uint8Array((text.length + 3) & ~3).fill(0x20);
  padded.set(text);
  text = padded;
  const total = 12 + 8 + text.length + 8 + bin.length;
  const out = new Uint8Array(total);
  const dv = new DataView(out.buffer);
  dv.setUint32(0, 0x46546c67, true); // 'glTF'
  dv.setUint32(4, 2, true);
  dv.setUint32(8, total, true);
  dv.setUint32(12, text.length, true);
  dv.setUint32(16, 0x4e4f534a, true); // 'JSON'
  out.set(text, 20);
  const b = 20 + text.length;
  dv.setUint32(b, bin.length, true);
  dv.setUint32(b + 4, 0x004e4942, true); // 'BIN\0'
  out.set(bin, b + 8);
  return out;
}
