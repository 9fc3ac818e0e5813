/**
 * From a mesh as read (inline arrays, an OBJ or a PLY file) to its triangles in world
 * space (docs/scene-format.md, Meshes): the transform is applied to the positions and,
 * by its inverse transpose, to the shading normals, which are then normalised; triangles
 * of zero area, judged in double precision after the transform, are dropped and counted.
 */
import { normalMatrix, transformPoints } from '../math/affine.ts';
import { TriangleEdges, triangleEdges } from './triangle-edges.ts';
import type { MeshData } from '../scene/format/types.ts';

/** A mesh as read, indices already checked to be in range. Owned by buildMeshData. */
export interface RawMesh {
  positions: Float64Array;
  indices: Uint32Array;
  /** Per vertex, non-zero except (0, 0, 0) for "none" (an OBJ face without `vn`). */
  normals: Float32Array | Float64Array | null;
}

/** A problem with the mesh's content; the caller prefixes the shape's path. */
export class MeshError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'MeshError';
  }
}

export function buildMeshData(raw: RawMesh, transform: ArrayLike<number> | null): MeshData {
  const positions = raw.positions;
  if (transform !== null) {
    transformPoints(transform, positions);
    for (let i = 0; i < positions.length; i++) {
      if (!Number.isFinite(positions[i])) {
        throw new MeshError(
          `the transform takes vertex ${Math.floor(i / 3)} out of the range of finite numbers`,
        );
      }
    }
  }
  const normals = raw.normals === null ? null : transformNormals(raw.normals, transform);
  const { indices, skipped } = dropZeroArea(positions, raw.indices);
  // Skipping some zero-area triangles is the format's rule; losing all of them
  // leaves a shape that renders as nothing, which no one means (issue 27).
  if (indices.length === 0 && skipped > 0) {
    throw new MeshError(
      skipped === 1
        ? 'its only triangle has zero area, so nothing of the mesh would render'
        : `all ${skipped} of its triangles have zero area, so nothing of the mesh would render`,
    );
  }
  return { positions, indices, normals, skipped };
}

function transformNormals(
  normals: Float32Array | Float64Array,
  transform: ArrayLike<number> | null,
): Float32Array {
  const out = new Float32Array(normals.length);
  const n = transform === null ? null : normalMatrix(transform);
  for (let i = 0; i < normals.length; i += 3) {
    let x = normals[i],
      y = normals[i + 1],
      z = normals[i + 2];
    if (x === 0 && y === 0 && z === 0) continue; // "no normal" stays (0, 0, 0)
    if (n !== null) {
      const tx = n[0] * x + n[1] * y + n[2] * z;
      const ty = n[3] * x + n[4] * y + n[5] * z;
      const tz = n[6] * x + n[7] * y + n[8] * z;
      x = tx;
      y = ty;
      z = tz;
    }
    const len = Math.hypot(x, y, z);
    if (!(len > 0 && len < Infinity)) {
      throw new MeshError(`the normal of vertex ${i / 3} has no direction after the transform`);
    }
    out[i] = x / len;
    out[i + 1] = y / len;
    out[i + 2] = z / len;
  }
  return out;
}

/**
 * Keeps the triangles whose edges span a non-zero area in double precision. The edges
 * are scaled by a power of two (exact) to a largest component near 1 before the cross
 * product, so neither huge nor tiny triangles overflow or underflow into a false zero.
 */
function dropZeroArea(
  p: Float64Array,
  indices: Uint32Array,
): { indices: Uint32Array; skipped: number } {
  const count = indices.length / 3;
  let kept = 0;
  const keep = new Uint8Array(count);
  const E = new TriangleEdges();
  for (let t = 0; t < count; t++) {
    triangleEdges(p, indices[3 * t] * 3, indices[3 * t + 1] * 3, indices[3 * t + 2] * 3, E);
    let e1x = E.e1x,
      e1y = E.e1y,
      e1z = E.e1z;
    let e2x = E.e2x,
      e2y = E.e2y,
      e2z = E.e2z;
    const m = E.m;
    if (m === 0) continue;
    if (m === Infinity) {
      throw new MeshError(`triangle ${t} is too large: its edges overflow double precision`);
    }
    let shift = -Math.floor(Math.log2(m));
    if (shift > 1000) {
      // Subnormal edges: 2^shift itself would overflow, so scale in two steps.
      const big = 2 ** 1000;
      e1x *= big;
      e1y *= big;
      e1z *= big;
      e2x *= big;
      e2y *= big;
      e2z *= big;
      shift -= 1000;
    }
    const s = 2 ** shift;
    e1x *= s;
    e1y *= s;
    e1z *= s;
    e2x *= s;
    e2y *= s;
    e2z *= s;
    const cx = e1y * e2z - e1z * e2y;
    const cy = e1z * e2x - e1x * e2z;
    const cz = e1x * e2y - e1y * e2x;
    if (cx === 0 && cy === 0 && cz === 0) continue;
    keep[t] = 1;
    kept++;
  }
  if (kept === count) return { indices, skipped: 0 };
  const out = new Uint32Array(kept * 3);
  let k = 0;
  for (let t = 0; t < count; t++) {
    if (keep[t] === 0) continue;
    out[k++] = indices[3 * t];
    out[k++] = indices[3 * t + 1];
    out[k++] = indices[3 * t + 2];
  }
  return { indices: out, skipped: count - kept };
}
