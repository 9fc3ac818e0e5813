/**
 * Anisotropic GGX (Trowbridge–Reitz) for KHR_materials_anisotropy, in the
 * anisotropy frame: +z the macro-surface normal, +x the direction of
 * increased roughness (α_x), +y the perpendicular (α_y).
 *
 * - D: Walter et al. 2007 / Heitz, "Understanding the Masking-Shadowing
 *   Function in Microfacet-Based BRDFs", JCGT 3(2) 2014, eq. 85;
 * - G1: Smith with the anisotropic Λ of Heitz 2014 §5.3 (eq. 86), written
 *   2z / (z + sqrt(z² + α_x²x² + α_y²y²)) like ggx.ts's isotropic form, to
 *   which it reduces exactly in exact arithmetic when α_x = α_y;
 * - visible-normal sampling: Heitz, "Sampling the GGX Distribution of Visible
 *   Normals", JCGT 7(4) 2018, listing 1, which stretches by (α_x, α_y).
 *
 * The glTF BSDF keeps the separable G1(wo)·G1(wi) of its isotropic lobe
 * (gltf-pbr.ts), not the README's height-correlated V_GGX_anisotropic, so
 * that strength 0 is the isotropic lobe. Allocation-free: records in,
 * records out.
 */
import type { Vec3Out } from '../sampling/warps.ts';

/** D(m) for the unit microfacet normal (x, y, z) and roughnesses (ax, ay). */
export function ggxDAniso(x: number, y: number, z: number, ax: number, ay: number): number {
  if (z <= 0) return 0;
  const sx = x / ax;
  const sy = y / ay;
  const d = sx * sx + sy * sy + z * z;
  return 1 / (Math.PI * ax * ay * d * d);
}

/** Smith G1 of the unit direction (x, y, z) (0 below the surface). */
export function ggxG1Aniso(x: number, y: number, z: number, ax: number, ay: number): number {
  if (z <= 0) return 0;
  const t = ax * ax * x * x + ay * ay * y * y;
  return (2 * z) / (z + Math.sqrt(z * z + t));
}

/**
 * The query of `ggxSampleVisibleNormalAniso`: the view direction (z > 0) in
 * the anisotropy frame, the roughnesses and the unit-square point.
 */
export class AnisoQuery {
  wx = 0;
  wy = 0;
  wz = 1;
  ax = 1;
  ay = 1;
  u0 = 0;
  u1 = 0;
}

/**
 * Draws a microfacet normal m with density D_wo(m) = G1(wo)·max(0, wo·m)·D(m)
 * / wo.z (Heitz 2018) into `m`.
 */
export function ggxSampleVisibleNormalAniso(q: AnisoQuery, m: Vec3Out): void {
  const ax = q.ax,
    ay = q.ay;
  // Stretch the view direction into the hemisphere configuration.
  let vx = ax * q.wx;
  let vy = ay * q.wy;
  let vz = q.wz;
  const vl = 1 / Math.sqrt(vx * vx + vy * vy + vz * vz);
  vx *= vl;
  vy *= vl;
  vz *= vl;
  // Orthonormal basis around it (T1 horizontal).
  const lensq = vx * vx + vy * vy;
  let t1x = 1;
  let t1y = 0;
  if (lensq > 0) {
    const inv = 1 / Math.sqrt(lensq);
    t1x = -vy * inv;
    t1y = vx * inv;
  }
  const t2x = -vz * t1y;
  const t2y = vz * t1x;
  const t2z = vx * t1y - vy * t1x;
  // Uniform point on the projected disk, warped toward the visible half.
  const r = Math.sqrt(q.u0);
  const phi = 2 * Math.PI * q.u1;
  const p1 = r * Math.cos(phi);
  let p2 = r * Math.sin(phi);
  const s = 0.5 * (1 + vz);
  p2 = (1 - s) * Math.sqrt(Math.max(0, 1 - p1 * p1)) + s * p2;
  const p3 = Math.sqrt(Math.max(0, 1 - p1 * p1 - p2 * p2));
  const nx = p1 * t1x + p2 * t2x + p3 * vx;
  const ny = p1 * t1y + p2 * t2y + p3 * vy;
  const nz = p2 * t2z + p3 * vz;
  // Unstretch back to the ellipsoid configuration.
  let mx = ax * nx;
  let my = ay * ny;
  let mz = Math.max(0, nz);
  const ml = 1 / Math.sqrt(mx * mx + my * my + mz * mz);
  mx *= ml;
  my *= ml;
  mz *= ml;
  m.x = mx;
  m.y = my;
  m.z = mz;
}

/** Density of `ggxSampleVisibleNormalAniso` at m for view w (both in the anisotropy frame). */
export function ggxVisibleNormalPdfAniso(
  wx: number,
  wy: number,
  wz: number,
  mx: number,
  my: number,
  mz: number,
  ax: number,
  ay: number,
): number {
  const c = wx * mx + wy * my + wz * mz;
  if (!(c > 0) || !(wz > 0)) return 0;
  return (ggxG1Aniso(wx, wy, wz, ax, ay) * c * ggxDAniso(mx, my, mz, ax, ay)) / wz;
}
