/**
 * The coat lobe of KHR_materials_clearcoat (README "Clearcoat BRDF"): a dielectric
 * GGX reflection of ior 1.5 around the coat normal Nc, with α = clearcoatRoughness²,
 * weighted by the coat factor c:
 *
 *   f_coat = c · F(wo·h) · D(h) · G1(wo) · G1(wi) / (4 |Nc·wo| |Nc·wi|)   (all about Nc)
 *   F(x)   = 0.04 + 0.96 (1 − x)⁵
 *   T(w)   = 1 − c · F(|Nc·w|)   what the coat lets through towards the layers below
 *
 * The spec's `fresnel_coat` mixes the base by 1 − c·F(V·Nc), a function of the view
 * alone; gltf-layers.ts weights the layers below by T(wo)·T(wi) instead (reciprocal,
 * the same coupling gltf-pbr.ts uses for its diffuse base).
 *
 * The same GGX D and separable Smith G as gltf-pbr.ts (ggx.ts), sampled by visible
 * normals (Heitz 2018) in an orthonormal frame around Nc (Duff et al. 2017, as in
 * math/frame.ts); Nc = +z uses the identity, so a coat without a normal texture is
 * exactly the isotropic lobe about the shading normal. α = 0 is a mirror about Nc,
 * a Dirac lobe the layered sampler returns on its own.
 *
 * Nc (ShadingParams.ccnx, ccny, ccnz) is in the BSDF's local frame here (trace-path
 * puts it there). A tilted Nc is normal mapping: like any normal map it does not
 * conserve energy exactly, because the integrator's cosine is the shading normal's.
 */
import { schlickWeight } from './fresnel.ts';
import { ggxD, ggxG1, ggxSampleVisibleNormal } from './ggx.ts';
import { BsdfQuery } from './records.ts';
import type { ShadingParams } from './shading.ts';

/** Coat Fresnel at normal incidence: ior 1.5 against air, ((1.5 − 1)/(1.5 + 1))². */
const COAT_F0 = 0.04;

/** Schlick's Fresnel of the coat at cosine x. */
export function coatFresnel(x: number): number {
  return COAT_F0 + (1 - COAT_F0) * schlickWeight(x);
}

/**
 * The frame around Nc: s, t and Nc, in the shading frame. `identity` when Nc = +z, so
 * that the common case involves no rotation (and no rounding).
 */
export const coatFrame = { sx: 1, sy: 0, sz: 0, tx: 0, ty: 1, tz: 0, identity: true };

/** Sets coatFrame for sp's Nc (Duff et al. 2017). */
export function setCoatFrame(sp: ShadingParams): void {
  const x = sp.ccnx,
    y = sp.ccny,
    z = sp.ccnz;
  const f = coatFrame;
  if (x === 0 && y === 0) {
    f.identity = true;
    return;
  }
  f.identity = false;
  const sign = z >= 0 ? 1 : -1;
  const a = -1 / (sign + z);
  const b = x * y * a;
  f.sx = 1 + sign * x * x * a;
  f.sy = sign * b;
  f.sz = -sign * x;
  f.tx = b;
  f.ty = sign + y * y * a;
  f.tz = -y;
}

/** What the coat transmits for a direction of cosine |Nc·w|: 1 − c·F. */
export function coatTransmit(sp: ShadingParams, wx: number, wy: number, wz: number): number {
  const cos = Math.abs(sp.ccnx * wx + sp.ccny * wy + sp.ccnz * wz);
  return 1 - sp.clearcoat * coatFresnel(cos);
}

/** The coat's value (grey) and its sampler's density, for eval below. */
export const coatValue = { f: 0, pdf: 0 };

/**
 * f_coat(wo, wi) and the density with which `coatSample` returns wi (non-delta only:
 * both 0 for a smooth coat), all in the shading frame (no rotation needed).
 */
export function coatEval(
  sp: ShadingParams,
  wox: number,
  woy: number,
  woz: number,
  wix: number,
  wiy: number,
  wiz: number,
): void {
  const alpha = sp.clearcoatAlpha;
  const nx = sp.ccnx,
    ny = sp.ccny,
    nz = sp.ccnz;
  const oz = nx * wox + ny * woy + nz * woz;
  const iz = nx * wix + ny * wiy + nz * wiz;
  coatValue.f = 0;
  coatValue.pdf = 0;
  if (!(alpha > 0) || !(oz > 0) || !(iz > 0)) return;
  let hx = wox + wix;
  let hy = woy + wiy;
  let hz = woz + wiz;
  const inv = 1 / Math.sqrt(hx * hx + hy * hy + hz * hz);
  hx *= inv;
  hy *= inv;
  hz *= inv;
  const c = Math.max(0, wox * hx + woy * hy + woz * hz);
  const d = ggxD(nx * hx + ny * hy + nz * hz, alpha);
  const g1o = ggxG1(oz, alpha);
  coatValue.f = (sp.clearcoat * coatFresnel(c) * d * g1o * ggxG1(iz, alpha)) / (4 * oz * iz);
  coatValue.pdf = (g1o * d) / (4 * oz);
}

const CQ = new BsdfQuery();
const CALPHA = new Float64Array(1);
const CM = { x: 0, y: 0, z: 1 };
/** The direction `coatSample` drew, in the shading frame. */
export const coatDirection = { x: 0, y: 0, z: 1 };

/**
 * Draws wi from the coat lobe for wo (shading frame) with u0, u1: a visible normal
 * of GGX(α) about Nc and the reflection about it, or the mirror about Nc for α = 0.
 * Writes coatDirection; false when wo is below the coat. Needs setCoatFrame(sp).
 */
export function coatSample(
  sp: ShadingParams,
  wox: number,
  woy: number,
  woz: number,
  u0: number,
  u1: number,
): boolean {
  const f = coatFrame;
  const nx = sp.ccnx,
    ny = sp.ccny,
    nz = sp.ccnz;
  let lx = wox,
    ly = woy,
    lz = woz;
  if (!f.identity) {
    lx = f.sx * wox + f.sy * woy + f.sz * woz;
    ly = f.tx * wox + f.ty * woy + f.tz * woz;
    lz = nx * wox + ny * woy + nz * woz;
  }
  if (!(lz > 0)) return false;
  let mx = 0,
    my = 0,
    mz = 1;
  if (sp.clearcoatAlpha > 0) {
    CQ.wox = lx;
    CQ.woy = ly;
    CQ.woz = lz;
    CQ.u0 = u0;
    CQ.u1 = u1;
    CALPHA[0] = sp.clearcoatAlpha;
    ggxSampleVisibleNormal(CQ, CALPHA, 0, CM);
    mx = CM.x;
    my = CM.y;
    mz = CM.z;
  }
  const c = lx * mx + ly * my + lz * mz;
  if (!(c > 0)) return false;
  const ix = 2 * c * mx - lx;
  const iy = 2 * c * my - ly;
  const iz = 2 * c * mz - lz;
  // Below the coat: f_coat is 0 there (coatEval), so the sample is refused, as gltf-pbr.ts does.
  if (!(iz > 0)) return false;
  const d = coatDirection;
  if (f.identity) {
    d.x = ix;
    d.y = iy;
    d.z = iz;
  } else {
    d.x = f.sx * ix + f.tx * iy + nx * iz;
    d.y = f.sy * ix + f.ty * iy + ny * iz;
    d.z = f.sz * ix + f.tz * iy + nz * iz;
  }
  return true;
}
