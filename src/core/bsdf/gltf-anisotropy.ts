/**
 * KHR_materials_anisotropy in the glTF BSDF (gltf-pbr.ts): the GGX lobe of the
 * metal, the dielectric specular layer and the glass's rough reflection
 * becomes anisotropic (README "Anisotropy"):
 *
 *   α_x = mix(α, 1, strength²)   along the anisotropy direction,
 *   α_y = α                       across it,
 *
 * with α = roughness². The direction is (cos φ, sin φ) in the local shading
 * frame (ShadingParams.anisotropyCos/Sin, set by the integrator from the
 * tangent frame); these functions rotate wo, wi and h by −φ into the frame of
 * ggx-aniso.ts. Only called when anisotropy > 0 (and α > 0: shading-fill
 * gives a smooth anisotropic surface the smallest α), so other materials run
 * the isotropic code unchanged. Allocation-free.
 */
import type { Vec3Out } from '../sampling/warps.ts';
import { AnisoQuery, ggxDAniso, ggxG1Aniso, ggxSampleVisibleNormalAniso } from './ggx-aniso.ts';
import type { ShadingParams } from './shading.ts';

/** D(h), G1(wo) and G1(wi) of the anisotropic lobe, written by `anisoTerms`. */
export const ANISO = { d: 0, g1o: 0, g1i: 0 };

/** α along the anisotropy direction. */
export function anisoAlphaX(sp: ShadingParams): number {
  const s = sp.anisotropy;
  return sp.alpha + (1 - sp.alpha) * s * s;
}

/**
 * The lobe's terms for wo = (wox, woy, oz) and the unit half vector h (local
 * frame, both with z > 0): wi is the reflection of wo about h.
 */
export function anisoTerms(
  sp: ShadingParams,
  wox: number,
  woy: number,
  oz: number,
  hx: number,
  hy: number,
  hz: number,
): void {
  const c = sp.anisotropyCos,
    s = sp.anisotropySin;
  const ax = anisoAlphaX(sp),
    ay = sp.alpha;
  const k = 2 * (wox * hx + woy * hy + oz * hz);
  const wix = k * hx - wox,
    wiy = k * hy - woy,
    iz = k * hz - oz;
  ANISO.d = ggxDAniso(c * hx + s * hy, c * hy - s * hx, hz, ax, ay);
  ANISO.g1o = ggxG1Aniso(c * wox + s * woy, c * woy - s * wox, oz, ax, ay);
  ANISO.g1i = ggxG1Aniso(c * wix + s * wiy, c * wiy - s * wix, iz, ax, ay);
}

const AQ = new AnisoQuery();

/** Draws a visible normal for wo = (wox, woy, oz) (local frame, oz > 0) into m, in the local frame. */
export function anisoSampleNormal(
  sp: ShadingParams,
  wox: number,
  woy: number,
  oz: number,
  u0: number,
  u1: number,
  m: Vec3Out,
): void {
  const c = sp.anisotropyCos,
    s = sp.anisotropySin;
  AQ.wx = c * wox + s * woy;
  AQ.wy = c * woy - s * wox;
  AQ.wz = oz;
  AQ.ax = anisoAlphaX(sp);
  AQ.ay = sp.alpha;
  AQ.u0 = u0;
  AQ.u1 = u1;
  ggxSampleVisibleNormalAniso(AQ, m);
  const x = m.x,
    y = m.y;
  m.x = c * x - s * y;
  m.y = s * x + c * y;
}
