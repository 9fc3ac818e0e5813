/**
 * The direction of KHR_materials_anisotropy at a hit, from tangent space to the
 * BSDF's local frame. The README defines it in the TBN frame of the mesh
 * ("in tangent, bitangent space", T from TANGENT or generated per glTF 2.0
 * §3.7.2.1, B = (N × T)·w); the glTF BSDF gets it as (cos φ, sin φ) in the
 * integrator's shading frame, whose tangents are an arbitrary (but fixed)
 * function of the shading normal. Two steps, because that frame (and which
 * side of the surface it faces) is only known once wo is:
 * - `anisotropyToWorld` (at the hit, gltf-surface.ts): the world direction
 *   d = cos·T + sin·B, with T made orthogonal to the final shading normal;
 * - `anisotropyToLocal` (trace-path.ts, after the frame is built): d's
 *   coordinates on the frame's two tangents.
 * Allocation-free.
 */
import type { ShadingParams } from '../bsdf/shading.ts';
import type { Vec3Out } from '../sampling/warps.ts';

/**
 * World direction of the anisotropy for the interpolated tangent `tg` (x, y,
 * z, w) and the unit shading normal n, into `out`. Returns false (out
 * untouched) when the tangent is missing or parallel to n.
 */
export function anisotropyToWorld(
  tg: Float64Array,
  nx: number,
  ny: number,
  nz: number,
  sp: ShadingParams,
  out: Vec3Out,
): boolean {
  const tw = tg[3];
  const d = tg[0] * nx + tg[1] * ny + tg[2] * nz;
  let ux = tg[0] - d * nx;
  let uy = tg[1] - d * ny;
  let uz = tg[2] - d * nz;
  const ul = Math.sqrt(ux * ux + uy * uy + uz * uz);
  if (!(ul > 1e-12) || tw === 0) return false;
  ux /= ul;
  uy /= ul;
  uz /= ul;
  const s = tw < 0 ? -1 : 1;
  const bx = s * (ny * uz - nz * uy);
  const by = s * (nz * ux - nx * uz);
  const bz = s * (nx * uy - ny * ux);
  const c = sp.anisotropyCos,
    si = sp.anisotropySin;
  out.x = c * ux + si * bx;
  out.y = c * uy + si * by;
  out.z = c * uz + si * bz;
  return true;
}

/** The world direction d as (cos φ, sin φ) on the frame tangents f (x axis) and t (y axis). */
export function anisotropyToLocal(
  d: { x: number; y: number; z: number },
  fx: number,
  fy: number,
  fz: number,
  tx: number,
  ty: number,
  tz: number,
  sp: ShadingParams,
): void {
  const c = d.x * fx + d.y * fy + d.z * fz;
  const s = d.x * tx + d.y * ty + d.z * tz;
  const l = Math.sqrt(c * c + s * s);
  if (!(l > 0)) {
    sp.anisotropy = 0;
    return;
  }
  sp.anisotropyCos = c / l;
  sp.anisotropySin = s / l;
}
