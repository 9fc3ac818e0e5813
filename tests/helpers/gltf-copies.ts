/**
 * The "flattened copy" of a glTF file with instancing (docs/gltf.md, Instancing): the
 * same scene with every use of a mesh a mesh of its own (a new entry of `meshes` over
 * the same accessors, so the loader keeps it in world space) and every
 * EXT_mesh_gpu_instancing row a child node with that row's TRS — what the instanced
 * file looks like to a loader without instancing.
 */
import { parseGlb } from '../../src/core/gltf/glb.ts';

type Json = Record<string, any>;

/** A GLB of `json` and the binary chunk `bin`. */
export function writeGlb(json: Json, bin: Uint8Array | null): Uint8Array {
  const text = new TextEncoder().encode(JSON.stringify(json));
  const jsonLen = (text.length + 3) & ~3;
  const binLen = bin === null ? 0 : (bin.length + 3) & ~3;
  const total = 12 + 8 + jsonLen + (bin === null ? 0 : 8 + binLen);
  const out = new Uint8Array(total);
  const dv = new DataView(out.buffer);
  dv.setUint32(0, 0x46546c67, true);
  dv.setUint32(4, 2, true);
  dv.setUint32(8, total, true);
  dv.setUint32(12, jsonLen, true);
  dv.setUint32(16, 0x4e4f534a, true);
  out.fill(0x20, 20, 20 + jsonLen);
  out.set(text, 20);
  if (bin !== null) {
    const o = 20 + jsonLen;
    dv.setUint32(o, binLen, true);
    dv.setUint32(o + 4, 0x004e4942, true);
    out.set(bin, o + 8);
  }
  return out;
}

/** Float components of accessor i of a GLB (floats, or normalized bytes/shorts). */
function floats(json: Json, bin: Uint8Array, i: number): number[] {
  const a = json.accessors[i];
  const view = json.bufferViews[a.bufferView];
  const size = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 }[a.type as string]!;
  const bytes = { 5126: 4, 5120: 1, 5122: 2 }[a.componentType as number]!;
  const stride = view.byteStride ?? size * bytes;
  const dv = new DataView(
    bin.buffer,
    bin.byteOffset + (view.byteOffset ?? 0) + (a.byteOffset ?? 0),
  );
  const out: number[] = [];
  for (let k = 0; k < a.count; k++) {
    for (let c = 0; c < size; c++) {
      const at = k * stride + c * bytes;
      if (a.componentType === 5126) out.push(dv.getFloat32(at, true));
      else if (a.componentType === 5120) out.push(Math.max(dv.getInt8(at) / 127, -1));
      else out.push(Math.max(dv.getInt16(at, true) / 32767, -1));
    }
  }
  return out;
}

export function flattenedCopy(glb: Uint8Array): Uint8Array {
  const { json: jsonBytes, bin } = parseGlb(glb);
  const json = JSON.parse(new TextDecoder().decode(jsonBytes)) as Json;
  flattenJson(json, bin);
  return writeGlb(json, bin);
}

/** The flattened copy of a glTF's JSON, in place (`bin`: the GLB chunk, for instancing rows). */
export function flattenJson(json: Json, bin: Uint8Array | null): void {
  const meshes: Json[] = json.meshes;
  const uses = new Map<number, number>();
  const ownMesh = (m: number): number => {
    const n = uses.get(m) ?? 0;
    uses.set(m, n + 1);
    if (n === 0) return m;
    meshes.push(structuredClone(meshes[m]));
    return meshes.length - 1;
  };
  const nodes: Json[] = json.nodes;
  const count = nodes.length;
  for (let i = 0; i < count; i++) {
    const n = nodes[i];
    if (typeof n.mesh !== 'number') continue;
    const ext = n.extensions?.EXT_mesh_gpu_instancing;
    if (ext === undefined) {
      n.mesh = ownMesh(n.mesh);
      continue;
    }
    const at = ext.attributes;
    const t = at.TRANSLATION === undefined ? null : floats(json, bin!, at.TRANSLATION);
    const r = at.ROTATION === undefined ? null : floats(json, bin!, at.ROTATION);
    const s = at.SCALE === undefined ? null : floats(json, bin!, at.SCALE);
    const k = (t?.length ?? 0) / 3 || (r?.length ?? 0) / 4 || (s?.length ?? 0) / 3;
    n.children ??= [];
    for (let j = 0; j < k; j++) {
      const child: Json = { mesh: ownMesh(n.mesh) };
      if (t) child.translation = t.slice(3 * j, 3 * j + 3);
      if (r) child.rotation = r.slice(4 * j, 4 * j + 4);
      if (s) child.scale = s.slice(3 * j, 3 * j + 3);
      n.children.push(nodes.length);
      nodes.push(child);
    }
    delete n.mesh;
    delete n.extensions.EXT_mesh_gpu_instancing;
  }
}
