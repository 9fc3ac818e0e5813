/**
 * The scene's meshes as the tracer reads them: every triangle of every mesh numbered in
 * one sequence, over one position array (x, y, z per vertex, world space), one index
 * array (three per triangle) and, when any mesh has them, one array of shading normals.
 * A scene with a single mesh uses that mesh's arrays as they are (no copy), which keeps
 * a million-triangle mesh at 24 bytes per vertex and 12 per triangle.
 *
 * No per-triangle record of the mesh it belongs to is kept: `meshOf` finds it by binary
 * search over the meshes' first triangles, once per hit, which costs nothing next to
 * the 4 bytes per triangle a table would take.
 */
import type { MeshDesc } from './types.ts';

export class CompiledMeshes {
  /** Number of meshes (with at least one triangle). */
  readonly count: number;
  readonly triangleCount: number;
  readonly positions: Float64Array;
  readonly indices: Uint32Array;
  /** Unit shading normals per vertex, (0, 0, 0) where none; null when no mesh has any. */
  readonly normals: Float32Array | null;
  /** First triangle of each mesh, and the total at the end (count + 1 entries). */
  readonly firstTriangle: Int32Array;
  readonly material: Int32Array;
  /** Whether each mesh has shading normals. */
  readonly hasNormals: Uint8Array;
  /** Largest coordinate magnitude of each mesh, for ray offsets (geometry/shapes.ts OFFSET_SCALE). */
  readonly scale: Float64Array;

  constructor(meshes: MeshDesc[], materialIndex: (name: string) => number) {
    const used = meshes.filter((m) => m.data!.indices.length > 0);
    this.count = used.length;
    this.firstTriangle = new Int32Array(used.length + 1);
    this.material = Int32Array.from(used, (m) => materialIndex(m.material));
    this.hasNormals = Uint8Array.from(used, (m) => (m.data!.normals === null ? 0 : 1));
    this.scale = new Float64Array(used.length);
    let vertices = 0;
    let triangles = 0;
    used.forEach((m, k) => {
      this.firstTriangle[k] = triangles;
      vertices += m.data!.positions.length / 3;
      triangles += m.data!.indices.length / 3;
    });
    this.firstTriangle[used.length] = triangles;
    this.triangleCount = triangles;
    const anyNormals = this.hasNormals.some((h) => h === 1);
    if (used.length === 1) {
      const d = used[0].data!;
      this.positions = d.positions;
      this.indices = d.indices;
      this.normals = d.normals;
    } else {
      this.positions = new Float64Array(vertices * 3);
      this.indices = new Uint32Array(triangles * 3);
      this.normals = anyNormals ? new Float32Array(vertices * 3) : null;
      let v = 0;
      used.forEach((m, k) => {
        const d = m.data!;
        this.positions.set(d.positions, v * 3);
        if (d.normals !== null) this.normals!.set(d.normals, v * 3);
        const base = this.firstTriangle[k] * 3;
        for (let i = 0; i < d.indices.length; i++) this.indices[base + i] = d.indices[i] + v;
        v += d.positions.length / 3;
      });
    }
    used.forEach((m, k) => {
      const p = m.data!.positions;
      let s = 0;
      for (let i = 0; i < p.length; i++) s = Math.max(s, Math.abs(p[i]));
      this.scale[k] = s;
    });
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
