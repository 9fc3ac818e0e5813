/**
 * A loaded glTF model split into one triangle group per material, each with
 * its own compact vertex arrays — the shape the tracer's meshes take (one
 * material per mesh, an emissive mesh one light sampled by area). Vertices
 * shared by two materials are duplicated at their boundary only; nothing
 * else is copied twice.
 */
import type { GltfTriangles } from '../format/gltf-model.ts';

export interface GltfGroup {
  /** Row of the model's material table. */
  material: number;
  positions: Float64Array;
  indices: Uint32Array;
  normals: Float32Array | null;
  uv0: Float32Array | null;
  uv1: Float32Array | null;
  colors: Float32Array | null;
  tangents: Float32Array | null;
}

function pick(src: Float32Array | null, size: number, order: Uint32Array): Float32Array | null {
  if (src === null) return null;
  const out = new Float32Array(order.length * size);
  for (let i = 0; i < order.length; i++) {
    const s = order[i] * size;
    for (let k = 0; k < size; k++) out[i * size + k] = src[s + k];
  }
  return out;
}

export function groupByMaterial(g: GltfTriangles): GltfGroup[] {
  const triCount = g.triangleMaterial.length;
  const vertexCount = g.positions.length / 3;
  if (triCount === 0) return [];
  // One material (the common case for big scanned models): the arrays as they are, no copy.
  const first = g.triangleMaterial[0];
  let single = true;
  for (let t = 1; t < triCount && single; t++) single = g.triangleMaterial[t] === first;
  if (single) {
    return [
      {
        material: first,
        positions: g.positions,
        indices: g.indices,
        normals: g.normals,
        uv0: g.uv0,
        uv1: g.uv1,
        colors: g.colors,
        tangents: g.tangents,
      },
    ];
  }
  // Triangles per material, by counting sort (stable: file order within a group).
  let materials = 0;
  for (let t = 0; t < triCount; t++) materials = Math.max(materials, g.triangleMaterial[t] + 1);
  const start = new Uint32Array(materials + 1);
  for (let t = 0; t < triCount; t++) start[g.triangleMaterial[t] + 1]++;
  for (let m = 0; m < materials; m++) start[m + 1] += start[m];
  const order = new Uint32Array(triCount);
  const fill = start.slice(0, materials);
  for (let t = 0; t < triCount; t++) order[fill[g.triangleMaterial[t]]++] = t;
  const remap = new Int32Array(vertexCount).fill(-1);
  const groups: GltfGroup[] = [];
  for (let m = 0; m < materials; m++) {
    const first = start[m];
    const count = start[m + 1] - first;
    if (count === 0) continue;
    const indices = new Uint32Array(count * 3);
    const used: number[] = [];
    for (let k = 0; k < count; k++) {
      const t = order[first + k];
      for (let c = 0; c < 3; c++) {
        const v = g.indices[3 * t + c];
        if (remap[v] < 0) {
          remap[v] = used.length;
          used.push(v);
        }
        indices[3 * k + c] = remap[v];
      }
    }
    const vertices = Uint32Array.from(used);
    for (const v of used) remap[v] = -1;
    const positions = new Float64Array(vertices.length * 3);
    for (let i = 0; i < vertices.length; i++) {
      positions[3 * i] = g.positions[3 * vertices[i]];
      positions[3 * i + 1] = g.positions[3 * vertices[i] + 1];
      positions[3 * i + 2] = g.positions[3 * vertices[i] + 2];
    }
    groups.push({
      material: m,
      positions,
      indices,
      normals: pick(g.normals, 3, vertices),
      uv0: pick(g.uv0, 2, vertices),
      uv1: pick(g.uv1, 2, vertices),
      colors: pick(g.colors, 4, vertices),
      tangents: pick(g.tangents, 4, vertices),
    });
  }
  return groups;
}
