/**
 * Which uses of a glTF mesh become instances (docs/gltf.md, Instancing): a mesh the
 * scene draws more than once (several nodes, or EXT_mesh_gpu_instancing rows) is kept
 * once in object space and each use becomes an instance of it — a transform and the
 * mesh's number, under a top-level BVH (accel/instances.ts) — rather than a copy.
 * Emissive meshes are copied all the same: a mesh light is sampled by its world-space
 * area (lights/mesh-light.ts), which a scaled instance changes, and emissive forests are
 * rare. A mesh drawn once stays in the world-space arrays, as before instancing.
 */
import type { GltfInstances, GltfTriangles } from '../scene/format/gltf-model.ts';
import { GltfError } from './errors.ts';
import { det3, type Mat4 } from './transforms.ts';

export interface MeshUse {
  mesh: number;
  matrix: Mat4;
  node: number;
}

export interface InstanceSplit {
  /** Uses drawn as world-space copies. */
  world: MeshUse[];
  /** The glTF meshes kept in object space, and the first node using each (for messages). */
  blasMeshes: number[];
  blasNode: number[];
  /** Instances: object-space mesh (index into blasMeshes), transform, node. */
  instances: { blas: number; matrix: Mat4; node: number }[];
}

export function splitInstances(
  uses: MeshUse[],
  meshCount: number,
  emissive: (mesh: number) => boolean,
): InstanceSplit {
  const count = new Uint32Array(meshCount);
  for (const u of uses) count[u.mesh]++;
  const blasOf = new Int32Array(meshCount).fill(-1);
  const out: InstanceSplit = { world: [], blasMeshes: [], blasNode: [], instances: [] };
  for (const u of uses) {
    if (count[u.mesh] < 2) {
      out.world.push(u);
      continue;
    }
    let b = blasOf[u.mesh];
    if (b === -1) {
      if (emissive(u.mesh)) blasOf[u.mesh] = -2;
      else {
        b = blasOf[u.mesh] = out.blasMeshes.length;
        out.blasMeshes.push(u.mesh);
        out.blasNode.push(u.node);
      }
    }
    if (b < 0) out.world.push(u);
    // A singular transform (scale 0 hides objects in some files) draws nothing.
    else if (det3(u.matrix) !== 0) out.instances.push({ blas: b, matrix: u.matrix, node: u.node });
  }
  return out;
}

/**
 * The instances as GltfInstances (those of meshes left without a triangle dropped),
 * and their world boxes added to `bounds`. Throws GltfError when an instance's box
 * leaves the double range.
 */
/** Instanced vertices up to which the bounds are exact. */
const EXACT_BOUNDS_VERTICES = 1 << 22;

export function gatherInstances(
  split: InstanceSplit,
  blas: GltfTriangles[],
  bounds: Float64Array,
): GltfInstances | null {
  const kept = split.instances.filter((i) => blas[i.blas].triangleMaterial.length > 0);
  if (kept.length === 0) return null;
  // The camera of a bare model frames these bounds: exact (every vertex transformed, as
  // a copy's would be) while that is cheap, the transformed object boxes beyond.
  let work = 0;
  for (const i of kept) work += blas[i.blas].positions.length / 3;
  const exact = work <= EXACT_BOUNDS_VERTICES;
  const mesh = new Uint32Array(kept.length);
  const matrices = new Float64Array(kept.length * 12);
  kept.forEach((inst, k) => {
    mesh[k] = inst.blas;
    const m = inst.matrix;
    const o = 12 * k;
    for (let c = 0; c < 4; c++) {
      for (let r = 0; r < 3; r++) matrices[o + 3 * c + r] = m[4 * c + r];
    }
    const b = blas[inst.blas].bounds;
    const p = blas[inst.blas].positions;
    const n = exact ? p.length / 3 : 8;
    for (let v = 0; v < n; v++) {
      const x = exact ? p[3 * v] : b[v & 1 ? 3 : 0],
        y = exact ? p[3 * v + 1] : b[v & 2 ? 4 : 1],
        z = exact ? p[3 * v + 2] : b[v & 4 ? 5 : 2];
      for (let a = 0; a < 3; a++) {
        const w = m[a] * x + m[4 + a] * y + m[8 + a] * z + m[12 + a];
        if (!Number.isFinite(w)) {
          throw new GltfError(
            `nodes[${inst.node}]: an instance of meshes[${split.blasMeshes[inst.blas]}] reaches ${w} in world space: its transform overflows the double range`,
          );
        }
        if (w < bounds[a]) bounds[a] = w;
        if (w > bounds[3 + a]) bounds[3 + a] = w;
      }
    }
  });
  return { meshes: blas, mesh, matrices };
}
