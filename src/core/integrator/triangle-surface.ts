/**
 * The surface at a triangle hit (docs/scene-format.md, Meshes): the point from the hit's
 * barycentrics (on the triangle up to rounding, whatever the ray's length; pbr-book 4e
 * §6.5.3), the geometric normal from the winding, which alone decides the emitting
 * side, and the shading normal interpolated from the vertices' normals and normalised,
 * where the mesh has them (the geometric one otherwise).
 */
import type { Hit } from '../geometry/ray.ts';
import { triangleNormal } from '../lights/mesh-light.ts';
import type { CompiledScene } from '../scene/compile/compile.ts';
import { completeInstanceHit } from './instance-surface.ts';

/** What `completeTriangleHit` writes. */
export class TriangleSurface {
  x = 0;
  y = 0;
  z = 0;
  /** Unit geometric normal. */
  nx = 0;
  ny = 0;
  nz = 1;
  /** Unit shading normal. */
  snx = 0;
  sny = 0;
  snz = 1;
  material = 0;
  /** Light index of the mesh, −1 if it does not emit. */
  light = -1;
  /** Coordinate magnitude of the triangle, for ray offsets. */
  scale = 0;
  /** The hit's instance (hit.instance), −1 for a world-space triangle. */
  instance = -1;
  /** An instance's object-to-world 3×4 and whether it mirrors (instance-surface.ts). */
  readonly objectToWorld = new Float64Array(12);
  mirrors = false;
}

export function completeTriangleHit(scene: CompiledScene, hit: Hit, out: TriangleSurface): void {
  out.instance = hit.instance;
  if (hit.instance >= 0) {
    completeInstanceHit(scene, hit, out);
    return;
  }
  const meshes = scene.meshes!;
  const p = scene.triPositions;
  const ix = scene.triIndices;
  const t = hit.index;
  const i0 = ix[3 * t] * 3,
    i1 = ix[3 * t + 1] * 3,
    i2 = ix[3 * t + 2] * 3;
  const b0 = hit.b0,
    b1 = hit.b1,
    b2 = hit.b2;
  out.x = b0 * p[i0] + b1 * p[i1] + b2 * p[i2];
  out.y = b0 * p[i0 + 1] + b1 * p[i1 + 1] + b2 * p[i2 + 1];
  out.z = b0 * p[i0 + 2] + b1 * p[i1 + 2] + b2 * p[i2 + 2];
  triangleNormal(p, i0, i1, i2, out);
  const mesh = meshes.meshOf(t);
  out.material = meshes.material[mesh];
  out.light = scene.meshLight[mesh];
  out.scale = meshes.triangleScale(t);
  out.snx = out.nx;
  out.sny = out.ny;
  out.snz = out.nz;
  const n = meshes.normals;
  if (n !== null && meshes.hasNormals[mesh] === 1) {
    // A face without normals (an OBJ face lacking vn) has (0, 0, 0) at its vertices.
    const sx = b0 * n[i0] + b1 * n[i1] + b2 * n[i2];
    const sy = b0 * n[i0 + 1] + b1 * n[i1 + 1] + b2 * n[i2 + 1];
    const sz = b0 * n[i0 + 2] + b1 * n[i1 + 2] + b2 * n[i2 + 2];
    const len = Math.sqrt(sx * sx + sy * sy + sz * sz);
    if (len > 0) {
      out.snx = sx / len;
      out.sny = sy / len;
      out.snz = sz / len;
    }
  }
}
