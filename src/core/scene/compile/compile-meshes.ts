/**
 * The scene's meshes as the tracer reads them: every triangle of every mesh numbered in
 * one sequence, over one position array (x, y, z per vertex, world space), one index
 * array (three per triangle) and, when any mesh has them, one array of shading normals.
 * A scene with a single mesh uses that mesh's arrays as they are (no copy), which keeps
 * a million-triangle mesh at 24 bytes per vertex and 12 per triangle.
 *
 * The arrays are part of the compiled scene's SceneData (compile.ts), so they travel to
 * the workers in the packed scene (pack.ts) like every other kind's.
 *
 * No per-triangle record of the mesh it belongs to is kept: `meshOf` finds it by binary
 * search over the meshes' first triangles, once per hit, which costs nothing next to
 * the 4 bytes per triangle a table would take.
 */
import type { MeshData } from '../format/types.ts';

/** The mesh arrays of SceneData. */
export interface MeshArrays {
  triPositions: Float64Array;
  /** Three vertex indices per triangle (below 2^31; a view of the mesh's Uint32Array). */
  triIndices: Int32Array;
  /** Unit shading normals per vertex, (0, 0, 0) where none; empty when no mesh has any. */
  triNormals: Float32Array;
  /**
   * glTF vertex attributes per vertex of all meshes (zeros for vertices of meshes that
   * lack them): TEXCOORD_0 and _1 (2 each), COLOR_0 (RGBA) and tangents (x, y, z, w).
   * Each is empty unless some mesh needs it, so scenes without glTF pay nothing.
   */
  triUV0: Float32Array;
  triUV1: Float32Array;
  triColors: Float32Array;
  triTangents: Float32Array;
  /** First triangle of each mesh, and the total at the end (meshes + 1 entries). */
  meshFirstTriangle: Int32Array;
  meshMaterial: Int32Array;
  /** 1 where the mesh has shading normals. */
  meshHasNormals: Int32Array;
  /** Largest coordinate magnitude of each mesh (for OFFSET_SCALE, geometry/shapes.ts). */
  meshScale: Float64Array;
}

/** Per-vertex glTF attributes of one mesh (null where it has none). */
export interface MeshAttributes {
  uv0: Float32Array | null;
  uv1: Float32Array | null;
  colors: Float32Array | null;
  tangents: Float32Array | null;
}

/** One mesh to compile: its triangles, its row of the material table, and glTF attributes. */
export interface MeshInput {
  data: MeshData;
  material: number;
  attributes?: MeshAttributes | null;
}

const ATTRIBUTES = [
  ['uv0', 'triUV0', 2],
  ['uv1', 'triUV1', 2],
  ['colors', 'triColors', 4],
  ['tangents', 'triTangents', 4],
] as const;

export function compileMeshArrays(meshes: MeshInput[]): MeshArrays {
  const used = meshes.filter((m) => m.data.indices.length > 0);
  const meshFirstTriangle = new Int32Array(used.length + 1);
  let vertices = 0;
  let triangles = 0;
  used.forEach((m, k) => {
    meshFirstTriangle[k] = triangles;
    vertices += m.data.positions.length / 3;
    triangles += m.data.indices.length / 3;
  });
  meshFirstTriangle[used.length] = triangles;
  const meshHasNormals = Int32Array.from(used, (m) => (m.data.normals === null ? 0 : 1));
  const anyNormals = meshHasNormals.some((h) => h === 1);
  let triPositions: Float64Array;
  let triIndices: Int32Array;
  let triNormals: Float32Array;
  const attributes: Record<(typeof ATTRIBUTES)[number][1], Float32Array> = {
    triUV0: new Float32Array(0),
    triUV1: new Float32Array(0),
    triColors: new Float32Array(0),
    triTangents: new Float32Array(0),
  };
  if (used.length === 1) {
    const d = used[0].data;
    triPositions = d.positions;
    triIndices = new Int32Array(d.indices.buffer, d.indices.byteOffset, d.indices.length);
    triNormals = d.normals ?? new Float32Array(0);
    const a = used[0].attributes;
    for (const [key, name] of ATTRIBUTES) attributes[name] = a?.[key] ?? new Float32Array(0);
  } else {
    triPositions = new Float64Array(vertices * 3);
    triIndices = new Int32Array(triangles * 3);
    triNormals = new Float32Array(anyNormals ? vertices * 3 : 0);
    for (const [key, name, size] of ATTRIBUTES) {
      if (used.some((m) => (m.attributes?.[key] ?? null) !== null)) {
        attributes[name] = new Float32Array(vertices * size);
      }
    }
    let v = 0;
    used.forEach((m, k) => {
      const d = m.data;
      triPositions.set(d.positions, v * 3);
      if (d.normals !== null) triNormals.set(d.normals, v * 3);
      for (const [key, name, size] of ATTRIBUTES) {
        const src = m.attributes?.[key] ?? null;
        if (src !== null) attributes[name].set(src, v * size);
        else if (key === 'colors' && attributes[name].length > 0) {
          // A mesh without COLOR_0 is white (glTF's default), not black.
          attributes[name].fill(1, v * size, (v + d.positions.length / 3) * size);
        }
      }
      const base = meshFirstTriangle[k] * 3;
      for (let i = 0; i < d.indices.length; i++) triIndices[base + i] = d.indices[i] + v;
      v += d.positions.length / 3;
    });
  }
  const meshScale = Float64Array.from(used, (m) => {
    const p = m.data.positions;
    let s = 0;
    for (let i = 0; i < p.length; i++) s = Math.max(s, Math.abs(p[i]));
    return s;
  });
  return {
    triPositions,
    triIndices,
    triNormals,
    ...attributes,
    meshFirstTriangle,
    meshMaterial: Int32Array.from(used, (m) => m.material),
    meshHasNormals,
    meshScale,
  };
}

export class CompiledMeshes {
  /** Number of meshes (with at least one triangle). */
  readonly count: number;
  readonly triangleCount: number;
  readonly positions: Float64Array;
  readonly indices: Int32Array;
  /** Shading normals, or null when no mesh has any. */
  readonly normals: Float32Array | null;
  readonly firstTriangle: Int32Array;
  readonly material: Int32Array;
  readonly hasNormals: Int32Array;
  readonly scale: Float64Array;

  constructor(a: MeshArrays) {
    this.count = a.meshMaterial.length;
    this.triangleCount = a.triIndices.length / 3;
    this.positions = a.triPositions;
    this.indices = a.triIndices;
    this.normals = a.triNormals.length > 0 ? a.triNormals : null;
    this.firstTriangle = a.meshFirstTriangle;
    this.material = a.meshMaterial;
    this.hasNormals = a.meshHasNormals;
    this.scale = a.meshScale;
  }

  /** The mesh that triangle t belongs to. */
  meshOf(t: number): number {
    const first = this.firstTriangle;
    let lo = 0;
    let hi = this.count - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (first[mid] <= t) lo = mid;
      else hi = mid - 1;
    }
    return lo;
  }

  /** Largest coordinate magnitude of triangle t's vertices (for OFFSET_SCALE). */
  triangleScale(t: number): number {
    const p = this.positions;
    const ix = this.indices;
    let s = 0;
    for (let k = 0; k < 3; k++) {
      const o = ix[3 * t + k] * 3;
      s = Math.max(s, Math.abs(p[o]), Math.abs(p[o + 1]), Math.abs(p[o + 2]));
    }
    return s;
  }

  /** Resident bytes of the triangle data (positions, indices, normals). */
  get byteLength(): number {
    return this.positions.byteLength + this.indices.byteLength + (this.normals?.byteLength ?? 0);
  }
}
