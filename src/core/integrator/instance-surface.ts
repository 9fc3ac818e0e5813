/**
 * The surface at a hit on an instance's triangle (accel/instances.ts): the triangle is
 * in object space, so what completeTriangleHit computes there is carried to world
 * space by the instance's transform M (object to world), the inverse of the stored
 * world-to-object W:
 * - the point: M·p of the barycentric point p (on the transformed triangle up to
 *   rounding, as a copy's point is on its triangle);
 * - normals by (M⁻¹)ᵀ = Wᵀ, renormalised (pbr-book 4e §3.10.1); the cross product of
 *   the object-space edges carried so points to the side a copy's would (a copy under a
 *   mirroring M swaps two corners, flatten.ts, which the transpose-inverse does here);
 * - tangents (normal maps) by M, with the handedness flipped where M mirrors;
 * - the offset scale: a bound on the world coordinates' magnitude, Σ|M_ij·p_j| + |t_i|
 *   over the three vertices, which also bounds the rounding of the transform.
 * Nothing is allocated: the matrix goes into the caller's TriangleSurface.
 */
import { invertAffine } from '../accel/instances.ts';
import type { Hit } from '../geometry/ray.ts';
import { triangleNormal } from '../lights/mesh-light.ts';
import type { CompiledScene } from '../scene/compile/compile.ts';
import type { TriangleSurface } from './triangle-surface.ts';

export function completeInstanceHit(scene: CompiledScene, hit: Hit, out: TriangleSurface): void {
  const meshes = scene.meshes!;
  const p = scene.triPositions;
  const ix = scene.triIndices;
  const t = hit.index;
  const w = scene.instXform;
  const k = hit.instance * 12;
  const m = out.objectToWorld;
  invertAffine(w, k, m, 0);
  out.mirrors =
    m[0] * (m[4] * m[8] - m[7] * m[5]) -
      m[3] * (m[1] * m[8] - m[7] * m[2]) +
      m[6] * (m[1] * m[5] - m[4] * m[2]) <
    0;
  const i0 = ix[3 * t] * 3,
    i1 = ix[3 * t + 1] * 3,
    i2 = ix[3 * t + 2] * 3;
  const b0 = hit.b0,
    b1 = hit.b1,
    b2 = hit.b2;
  const px = b0 * p[i0] + b1 * p[i1] + b2 * p[i2];
  const py = b0 * p[i0 + 1] + b1 * p[i1 + 1] + b2 * p[i2 + 1];
  const pz = b0 * p[i0 + 2] + b1 * p[i1 + 2] + b2 * p[i2 + 2];
  out.x = m[0] * px + m[3] * py + m[6] * pz + m[9];
  out.y = m[1] * px + m[4] * py + m[7] * pz + m[10];
  out.z = m[2] * px + m[5] * py + m[8] * pz + m[11];
  out.scale = Math.max(worldBound(m, p, i0), worldBound(m, p, i1), worldBound(m, p, i2));
  triangleNormal(p, i0, i1, i2, out);
  toWorldNormal(w, k, out.nx, out.ny, out.nz, out, false);
  const mesh = meshes.meshOf(t);
  out.material = meshes.material[mesh];
  out.light = scene.meshLight[mesh];
  out.snx = out.nx;
  out.sny = out.ny;
  out.snz = out.nz;
  const n = meshes.normals;
  if (n !== null && meshes.hasNormals[mesh] === 1) {
    const sx = b0 * n[i0] + b1 * n[i1] + b2 * n[i2];
    const sy = b0 * n[i0 + 1] + b1 * n[i1 + 1] + b2 * n[i2 + 1];
    const sz = b0 * n[i0 + 2] + b1 * n[i1 + 2] + b2 * n[i2 + 2];
    if (sx !== 0 || sy !== 0 || sz !== 0) toWorldNormal(w, k, sx, sy, sz, out, true);
  }
}

/** Wᵀ·n, normalised, into out's geometric (or shading) normal; left alone if it vanishes. */
function toWorldNormal(
  w: Float64Array,
  k: number,
  x: number,
  y: number,
  z: number,
  out: TriangleSurface,
  shading: boolean,
): void {
  let nx = w[k] * x + w[k + 1] * y + w[k + 2] * z;
  let ny = w[k + 3] * x + w[k + 4] * y + w[k + 5] * z;
  let nz = w[k + 6] * x + w[k + 7] * y + w[k + 8] * z;
  // Scaled first, so that a huge or tiny matrix neither over- nor underflows the squares.
  const s = Math.max(Math.abs(nx), Math.abs(ny), Math.abs(nz));
  if (!(s > 0 && s < Infinity)) return;
  nx /= s;
  ny /= s;
  nz /= s;
  const len = Math.sqrt(nx * nx + ny * ny + nz * nz);
  if (shading) {
    out.snx = nx / len;
    out.sny = ny / len;
    out.snz = nz / len;
  } else {
    out.nx = nx / len;
    out.ny = ny / len;
    out.nz = nz / len;
  }
}

/**
 * An object-space tangent (x, y, z, handedness w in tg) of the hit completed into `ts`
 * carried to world space by M and normalised, in place; the handedness flips where M
 * mirrors (as flatten.ts does for a copy).
 */
export function instanceTangent(ts: TriangleSurface, tg: Float64Array): void {
  const m = ts.objectToWorld;
  const x = tg[0],
    y = tg[1],
    z = tg[2];
  const wx = m[0] * x + m[3] * y + m[6] * z;
  const wy = m[1] * x + m[4] * y + m[7] * z;
  const wz = m[2] * x + m[5] * y + m[8] * z;
  const l = Math.sqrt(wx * wx + wy * wy + wz * wz);
  if (l > 0 && l < Infinity) {
    tg[0] = wx / l;
    tg[1] = wy / l;
    tg[2] = wz / l;
  }
  if (ts.mirrors) tg[3] = -tg[3];
}

/** max over axes of Σ_j |M_aj·p_j| + |t_a| for vertex v: bounds |M·p + t| and its rounding. */
function worldBound(m: Float64Array, p: Float64Array, v: number): number {
  const x = p[v],
    y = p[v + 1],
    z = p[v + 2];
  let s = 0;
  for (let a = 0; a < 3; a++) {
    const e =
      Math.abs(m[a] * x) + Math.abs(m[3 + a] * y) + Math.abs(m[6 + a] * z) + Math.abs(m[9 + a]);
    if (e > s) s = e;
  }
  return s;
}
