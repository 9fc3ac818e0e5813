/**
 * The glTF 2.0 metallic–roughness BSDF of the glTF specification's Appendix B
 * ("BRDF Implementation"), with KHR_materials_ior, KHR_materials_specular and
 * KHR_materials_transmission:
 *
 *   f = metallic · metal + (1 − metallic) · [(1 − t) · opaque + t · glass]
 *   metal  = S · (base + (1 − base)(1 − |v·h|)⁵)            conductor_fresnel
 *   opaque = (1 − F(cosθo)) (1 − F(cosθi)) · base/π + F(v·h) · S
 *            F(c) = f0 + (f90 − f0)(1 − c)⁵,  f0 = ((ior−1)/(ior+1))² · specColor · specular,
 *            f90 = specular
 *   glass  = Fd(v·h) · S  +  smooth refraction tinted by base
 *   S      = D(h) · G1(wo) · G1(wi) / (4 |cosθo| |cosθi|),   GGX with α = roughness²
 *
 * The diffuse weight is the one deviation from Appendix B's main formula,
 * whose `fresnel_mix` weights the Lambert base by 1 − F(v·h): that
 * reflects more light than it receives (a white smooth base returns 1.025 of
 * the light arriving at 60°; tests/statistical/gltf-bsdf-chi2.test.ts shows
 * it), which Appendix B's own discussion of coupling diffuse and specular
 * reflection points out. We use the energy-conserving coupling that
 * discussion names (Burley 2012), (1 − F(n·wo))(1 − F(n·wi)): reciprocal,
 * identical at normal incidence, and a pure Lambert base when specular = 0.
 *
 * S is the same GGX lobe as the conductor of `pathwise-scene/1` (separable
 * Smith G, Walter et al. 2007), so metallic 1 is exactly that conductor with
 * F0 = base. The transmissive part is the smooth dielectric of the scene
 * format — exact Fresnel Fd, Snell refraction, (n1/n2)² in radiance mode —
 * with its reflection roughened by the same GGX lobe: a visible normal m is
 * drawn, the path reflects about m with probability Fd(wo·m) and otherwise
 * refracts through the smooth macro-surface. That delta lobe therefore
 * carries exactly the energy the rough reflection leaves, 1 − E_m[Fd(wo·m)]
 * (so glass never gains energy), and at roughness 0 it is the smooth
 * dielectric exactly. A transmissive surface bounds a solid of index `ior`
 * only when KHR_materials_volume gives it a thicknessFactor > 0; otherwise it
 * is KHR_materials_transmission's default thin wall: the refracted ray goes
 * straight on (wi = −wo) and η sets only the Fresnel split, the same from
 * both sides. Absorption inside a solid is the integrator's (medium.ts).
 *
 * KHR_materials_diffuse_transmission adds a thin Lambertian BTDF under the
 * specular layer, beside the Lambert base (diffuse-transmission.ts): the one
 * lobe with density on the far side of the surface.
 *
 * Sampling picks one lobe (diffuse, GGX reflection, glass, diffuse transmission) with
 * probabilities from wo alone, so `pdf` is the exact mixture density of the
 * non-delta lobes (pbr-book 4e §9.7 on mixtures); non-delta sample weights
 * are the full f·cosθi / pdf. At roughness 0 every reflection lobe is the
 * mirror direction and they are sampled together as one Dirac lobe.
 *
 * Local frame: for an opaque material +z faces wo; for a transmissive one
 * (the integrator's geometric-side mode, as for dielectrics) +z is the
 * outward normal and wo.z < 0 means the path arrives from inside. Reflection
 * lobes then work in the mirrored frame z → −z.
 */
import { squareToCosineHemisphere } from '../sampling/warps.ts';
import { fresnelDielectric, schlickWeight } from './fresnel.ts';
import { ggxD, ggxG1, ggxSampleVisibleNormal } from './ggx.ts';
import { diffuseTransmissionAlbedo, evalDiffuseTransmission } from './diffuse-transmission.ts';
import { BsdfQuery, type BsdfSample, type BsdfValue } from './records.ts';
import type { ShadingParams } from './shading.ts';

const INV_PI = 1 / Math.PI;
const M = { x: 0, y: 0, z: 1 };
const VQ = new BsdfQuery();
const VALPHA = new Float64Array(1);
const W = { x: 0, y: 0, z: 1 };

/**
 * Lobe-selection probabilities of the current call (functions of wo only):
 * `diffuse`, `reflect` (metal + opaque specular) and `glass`; `total` is the
 * unnormalised sum they were divided by.
 */
const lobe = { diffuse: 0, reflect: 0, glass: 0, dtrans: 0, total: 0 };

/** F0 of the dielectric layer per channel, and f90 (KHR_materials_specular). */
const f0 = { r: 0, g: 0, b: 0, f90: 1 };

function setF0(sp: ShadingParams): void {
  const k = (sp.ior - 1) / (sp.ior + 1);
  const k2 = k * k;
  const s = sp.specular;
  f0.r = Math.min(k2 * sp.specR, 1) * s;
  f0.g = Math.min(k2 * sp.specG, 1) * s;
  f0.b = Math.min(k2 * sp.specB, 1) * s;
  f0.f90 = s;
}

/**
 * Chooses the lobe probabilities for wo at cosine `cosO` (> 0): the weight
 * of each lobe times an estimate of its albedo. Returns false when the
 * material reflects nothing at all.
 */
function selectLobes(sp: ShadingParams, cosO: number): boolean {
  setF0(sp);
  const metallic = sp.metallic;
  const t = sp.transmission;
  const cOpaque = (1 - metallic) * (1 - t);
  const w = schlickWeight(cosO);
  const f90 = f0.f90;
  const fr = f0.r + (f90 - f0.r) * w;
  const fg = f0.g + (f90 - f0.g) * w;
  const fb = f0.b + (f90 - f0.b) * w;
  const pSpec = (cOpaque * (fr + fg + fb)) / 3;
  const dt = sp.diffuseTransmission;
  const pDiffuse =
    (cOpaque * (1 - dt) * ((1 - fr) * sp.baseR + (1 - fg) * sp.baseG + (1 - fb) * sp.baseB)) / 3;
  const pGlass = (1 - metallic) * t;
  // KHR_materials_diffuse_transmission (diffuse-transmission.ts): last, so
  // that without it the sum and the other lobes' intervals in u2 are unchanged.
  const pTrans = dt > 0 ? diffuseTransmissionAlbedo(sp, f0, cosO) : 0;
  const total = pDiffuse + metallic + pSpec + pGlass + pTrans;
  lobe.total = total;
  if (!(total > 0)) {
    lobe.diffuse = 0;
    lobe.reflect = 0;
    lobe.glass = 0;
    lobe.dtrans = 0;
    return false;
  }
  const inv = 1 / total;
  lobe.diffuse = pDiffuse * inv;
  lobe.reflect = (metallic + pSpec) * inv;
  lobe.glass = pGlass * inv;
  lobe.dtrans = pTrans * inv;
  return true;
}

/**
 * f and the mixture pdf of the non-delta lobes for wo, wi on the same side,
 * in the frame where both have z > 0 (`inside` says whether that frame is
 * mirrored, i.e. the path is inside a transmissive solid), with h their
 * half vector. Needs selectLobes(sp, oz) first.
 */
function evalReflection(
  sp: ShadingParams,
  wox: number,
  woy: number,
  oz: number,
  iz: number,
  hx: number,
  hy: number,
  hz: number,
  inside: boolean,
  out: BsdfValue,
): void {
  const c = Math.max(0, wox * hx + woy * hy + oz * hz);
  const metallic = sp.metallic;
  const t = sp.transmission;
  const cOpaque = (1 - metallic) * (1 - t);
  const cGlass = (1 - metallic) * t;
  const baseR = sp.baseR,
    baseG = sp.baseG,
    baseB = sp.baseB;
  const w = schlickWeight(c);
  const f90 = f0.f90;
  const fr = f0.r + (f90 - f0.r) * w;
  const fg = f0.g + (f90 - f0.g) * w;
  const fb = f0.b + (f90 - f0.b) * w;
  // Lambert base under the layer, weighted by what the layer transmits on
  // the way in and on the way out (see the header).
  const wo5 = schlickWeight(oz);
  const wi5 = schlickWeight(iz);
  const kd = cOpaque * (1 - sp.diffuseTransmission) * INV_PI;
  let r = kd * (1 - f0.r - (f90 - f0.r) * wo5) * (1 - f0.r - (f90 - f0.r) * wi5) * baseR;
  let g = kd * (1 - f0.g - (f90 - f0.g) * wo5) * (1 - f0.g - (f90 - f0.g) * wi5) * baseG;
  let b = kd * (1 - f0.b - (f90 - f0.b) * wo5) * (1 - f0.b - (f90 - f0.b) * wi5) * baseB;
  let pdf = lobe.diffuse * iz * INV_PI;
  const alpha = sp.alpha;
  if (alpha > 0) {
    const d = ggxD(hz, alpha);
    const g1o = ggxG1(oz, alpha);
    const s = (d * g1o * ggxG1(iz, alpha)) / (4 * oz * iz);
    // A thin wall has air on both sides: the same η from either side.
    const fd =
      cGlass > 0 ? fresnelDielectric(c, inside && sp.thickness > 0 ? 1 / sp.ior : sp.ior) : 0;
    const layer = cGlass * fd;
    r += s * (metallic * (baseR + (1 - baseR) * w) + cOpaque * fr + layer);
    g += s * (metallic * (baseG + (1 - baseG) * w) + cOpaque * fg + layer);
    b += s * (metallic * (baseB + (1 - baseB) * w) + cOpaque * fb + layer);
    // Every reflection lobe draws the visible normal: G1(wo)·D(h) / (4 cosθo).
    pdf += (lobe.reflect + lobe.glass * fd) * ((g1o * d) / (4 * oz));
  }
  out.r = r;
  out.g = g;
  out.b = b;
  out.pdf = pdf;
}

/** f(q.wo, q.wi) without delta lobes, with the density `gltfSample` has for q.wi. */
export function gltfEval(sp: ShadingParams, q: BsdfQuery, out: BsdfValue): void {
  const inside = q.woz < 0;
  const oz = inside ? -q.woz : q.woz;
  const iz = inside ? -q.wiz : q.wiz;
  if (iz < 0 && sp.diffuseTransmission > 0 && oz > 0 && selectLobes(sp, oz)) {
    // wi behind the surface: only the diffuse transmission reaches it.
    evalDiffuseTransmission(sp, f0, lobe.dtrans, oz, -iz, out);
    return;
  }
  if (!(oz > 0) || !(iz > 0) || !selectLobes(sp, oz)) {
    out.r = 0;
    out.g = 0;
    out.b = 0;
    out.pdf = 0;
    return;
  }
  const wox = q.wox,
    woy = q.woy;
  const hx = wox + q.wix;
  const hy = woy + q.wiy;
  const hz = oz + iz;
  const inv = 1 / Math.sqrt(hx * hx + hy * hy + hz * hz);
  evalReflection(sp, wox, woy, oz, iz, hx * inv, hy * inv, hz * inv, inside, out);
}

const PDF_VALUE = { r: 0, g: 0, b: 0, pdf: 0 };

/** Solid-angle density with which `gltfSample` returns q.wi (non-delta lobes only). */
export function gltfPdf(sp: ShadingParams, q: BsdfQuery): number {
  gltfEval(sp, q, PDF_VALUE);
  return PDF_VALUE.pdf;
}

/**
 * Samples wi: q.u2 picks the lobe (and, rescaled, reflection or refraction
 * inside the glass lobe), q.u0, q.u1 the direction. Returns false when the
 * sample carries no energy.
 */
export function gltfSample(sp: ShadingParams, q: BsdfQuery, out: BsdfSample): boolean {
  const woz = q.woz;
  const inside = woz < 0;
  const oz = inside ? -woz : woz;
  if (!(oz > 0) || !selectLobes(sp, oz)) return false;
  const wox = q.wox,
    woy = q.woy;
  const u = q.u2;
  // Where the glass lobe starts in u2; never reached when there is no glass
  // (so rounding in the sum of the probabilities cannot pick it).
  const glassFrom = lobe.glass > 0 ? lobe.diffuse + lobe.reflect : Infinity;
  const alpha = sp.alpha;
  const eta = inside && sp.thickness > 0 ? 1 / sp.ior : sp.ior;
  out.etaScale = 1;
  let wix: number, wiy: number, iz: number;
  // The half vector: computed for a diffuse sample, the sampled microfacet
  // normal for a reflection (the same in exact arithmetic, and then the pdf
  // is exactly the density the sampler drew m with).
  let hx: number, hy: number, hz: number;
  if (lobe.dtrans > 0 && u >= lobe.diffuse + lobe.reflect + lobe.glass) {
    // Diffuse transmission: cosine-weighted on the far side (diffuse-transmission.ts).
    squareToCosineHemisphere(q.u0, q.u1, W);
    const fv = PDF_VALUE;
    evalDiffuseTransmission(sp, f0, lobe.dtrans, oz, W.z, fv);
    if (!(fv.pdf > 0)) return false;
    const k = W.z / fv.pdf;
    out.weightR = fv.r * k;
    out.weightG = fv.g * k;
    out.weightB = fv.b * k;
    out.wx = W.x;
    out.wy = W.y;
    out.wz = inside ? W.z : -W.z;
    out.pdf = fv.pdf;
    out.isDelta = false;
    return true;
  }
  if (u < lobe.diffuse || (lobe.reflect === 0 && lobe.glass === 0)) {
    squareToCosineHemisphere(q.u0, q.u1, W);
    wix = W.x;
    wiy = W.y;
    iz = W.z;
    hx = wox + wix;
    hy = woy + wiy;
    hz = oz + iz;
    const inv = 1 / Math.sqrt(hx * hx + hy * hy + hz * hz);
    hx *= inv;
    hy *= inv;
    hz *= inv;
  } else if (alpha === 0) {
    // Smooth: metal, specular layer and glass reflection share the mirror direction.
    const fd = lobe.glass > 0 ? fresnelDielectric(oz, eta) : 0;
    const pMirror = lobe.reflect + lobe.glass * fd;
    if (u < lobe.diffuse + pMirror || u < glassFrom) {
      const metallic = sp.metallic;
      const cOpaque = (1 - metallic) * (1 - sp.transmission);
      const layer = (1 - metallic) * sp.transmission * fd;
      const w = schlickWeight(oz);
      const f90 = f0.f90;
      const inv = 1 / pMirror;
      const metalR = metallic * (sp.baseR + (1 - sp.baseR) * w);
      const metalG = metallic * (sp.baseG + (1 - sp.baseG) * w);
      const metalB = metallic * (sp.baseB + (1 - sp.baseB) * w);
      out.weightR = (metalR + cOpaque * (f0.r + (f90 - f0.r) * w) + layer) * inv;
      out.weightG = (metalG + cOpaque * (f0.g + (f90 - f0.g) * w) + layer) * inv;
      out.weightB = (metalB + cOpaque * (f0.b + (f90 - f0.b) * w) + layer) * inv;
      out.wx = -wox;
      out.wy = -woy;
      out.wz = woz;
      out.pdf = pMirror;
      out.isDelta = true;
      return true;
    }
    return refract(sp, q, oz, eta, lobe.glass * (1 - fd), out);
  } else {
    // The sampler reads a query record and α from an array (no boxed doubles);
    // the reflection frame may be mirrored, so it gets its own query.
    VQ.wox = wox;
    VQ.woy = woy;
    VQ.woz = oz;
    VQ.u0 = q.u0;
    VQ.u1 = q.u1;
    VALPHA[0] = alpha;
    ggxSampleVisibleNormal(VQ, VALPHA, 0, M);
    const c = wox * M.x + woy * M.y + oz * M.z;
    if (c <= 0) return false;
    if (u >= glassFrom) {
      // Glass: reflect about m with probability Fd(wo·m), else refract.
      const fd = fresnelDielectric(c, eta);
      const ug = (u - lobe.diffuse - lobe.reflect) / lobe.glass;
      if (ug >= fd) return refract(sp, q, oz, eta, lobe.glass * (1 - fd), out);
    }
    wix = 2 * c * M.x - wox;
    wiy = 2 * c * M.y - woy;
    iz = 2 * c * M.z - oz;
    hx = M.x;
    hy = M.y;
    hz = M.z;
  }
  if (!(iz > 0)) return false;
  const fv = PDF_VALUE;
  evalReflection(sp, wox, woy, oz, iz, hx, hy, hz, inside, fv);
  if (!(fv.pdf > 0)) return false;
  const k = iz / fv.pdf;
  out.weightR = fv.r * k;
  out.weightG = fv.g * k;
  out.weightB = fv.b * k;
  out.wx = wix;
  out.wy = wiy;
  out.wz = inside ? -iz : iz;
  out.pdf = fv.pdf;
  out.isDelta = false;
  return true;
}

/**
 * The smooth refraction of the glass lobe (Snell, pbr-book 4e §9.3): chosen
 * with probability lobe.glass × (what the reflection left), it carries
 * glass × (the same) × base / η², so its weight is total · base / η².
 */
function refract(
  sp: ShadingParams,
  q: BsdfQuery,
  cosI: number,
  eta: number,
  probability: number,
  out: BsdfSample,
): boolean {
  if (!(sp.thickness > 0)) {
    // Thin-walled (KHR_materials_volume absent or thicknessFactor 0): the
    // wall's two faces bend the ray back, so it passes straight through;
    // η only sets the Fresnel split, and no (n1/n2)² applies (air on both sides).
    out.wx = -q.wox;
    out.wy = -q.woy;
    out.wz = -q.woz;
    const total = lobe.total;
    out.weightR = sp.baseR * total;
    out.weightG = sp.baseG * total;
    out.weightB = sp.baseB * total;
    out.pdf = probability;
    out.isDelta = true;
    out.etaScale = 1;
    return true;
  }
  const invEta = 1 / eta;
  const sin2T = (1 - cosI * cosI) * invEta * invEta;
  // Total internal reflection of the macro-surface: no refracted direction.
  if (sin2T >= 1) return false;
  const cosT = Math.sqrt(1 - sin2T);
  const side = q.woz > 0 ? 1 : -1;
  const k = cosI * invEta - cosT;
  out.wx = -q.wox * invEta;
  out.wy = -q.woy * invEta;
  out.wz = -q.woz * invEta + k * side;
  const scale = lobe.total * invEta * invEta;
  out.weightR = sp.baseR * scale;
  out.weightG = sp.baseG * scale;
  out.weightB = sp.baseB * scale;
  out.pdf = probability;
  out.isDelta = true;
  out.etaScale = eta * eta;
  return true;
}
