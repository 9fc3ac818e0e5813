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
 * KHR_materials_iridescence replaces the Fresnel of the specular layer, the
 * metal and (from outside) the glass by the thin-film one, mixed by its weight
 * (gltf-iridescence.ts); KHR_materials_anisotropy makes the GGX lobe
 * anisotropic (gltf-anisotropy.ts). Both are skipped at weight 0, which
 * leaves the arithmetic of this file exactly as without them.
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
import { ANISO, anisoSampleNormal, anisoTerms } from './gltf-anisotropy.ts';
import { iridescentDielectric, iridescentGlass, iridescentMetal } from './gltf-iridescence.ts';
import { BsdfQuery, type BsdfSample, type BsdfValue } from './records.ts';
import type { ShadingParams } from './shading.ts';

const INV_PI = 1 / Math.PI;
const M = { x: 0, y: 0, z: 1 };
const VQ = new BsdfQuery();
const VALPHA = new Float64Array(1);
const W = { x: 0, y: 0, z: 1 };
/** Mixed (iridescent) Fresnel values: dielectric at v·h, at n·wo, at n·wi, and the metal's. */
const FD = { r: 0, g: 0, b: 0 };
const FO = { r: 0, g: 0, b: 0 };
const FI = { r: 0, g: 0, b: 0 };
const FM = { r: 0, g: 0, b: 0 };
/** The glass lobe's iridescent reflectance per channel (its mean is the reflection probability). */
const FG = { r: 0, g: 0, b: 0 };

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
  let fr = f0.r + (f90 - f0.r) * w;
  let fg = f0.g + (f90 - f0.g) * w;
  let fb = f0.b + (f90 - f0.b) * w;
  if (sp.iridescence > 0 && cOpaque > 0) {
    FO.r = fr;
    FO.g = fg;
    FO.b = fb;
    iridescentDielectric(sp, cosO, FO);
    fr = FO.r;
    fg = FO.g;
    fb = FO.b;
  }
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
  let fr = f0.r + (f90 - f0.r) * w;
  let fg = f0.g + (f90 - f0.g) * w;
  let fb = f0.b + (f90 - f0.b) * w;
  // Lambert base under the layer, weighted by what the layer transmits on
  // the way in and on the way out (see the header).
  const wo5 = schlickWeight(oz);
  const wi5 = schlickWeight(iz);
  const kd = cOpaque * (1 - sp.diffuseTransmission) * INV_PI;
  let tor = 1 - f0.r - (f90 - f0.r) * wo5,
    tog = 1 - f0.g - (f90 - f0.g) * wo5,
    tob = 1 - f0.b - (f90 - f0.b) * wo5;
  let tir = 1 - f0.r - (f90 - f0.r) * wi5,
    tig = 1 - f0.g - (f90 - f0.g) * wi5,
    tib = 1 - f0.b - (f90 - f0.b) * wi5;
  let mr = baseR + (1 - baseR) * w,
    mg = baseG + (1 - baseG) * w,
    mb = baseB + (1 - baseB) * w;
  if (sp.iridescence > 0) {
    // KHR_materials_iridescence: the thin-film Fresnel, mixed in (gltf-iridescence.ts).
    if (cOpaque > 0) {
      FD.r = fr;
      FD.g = fg;
      FD.b = fb;
      iridescentDielectric(sp, c, FD);
      fr = FD.r;
      fg = FD.g;
      fb = FD.b;
      FO.r = 1 - tor;
      FO.g = 1 - tog;
      FO.b = 1 - tob;
      iridescentDielectric(sp, oz, FO);
      tor = 1 - FO.r;
      tog = 1 - FO.g;
      tob = 1 - FO.b;
      FI.r = 1 - tir;
      FI.g = 1 - tig;
      FI.b = 1 - tib;
      iridescentDielectric(sp, iz, FI);
      tir = 1 - FI.r;
      tig = 1 - FI.g;
      tib = 1 - FI.b;
    }
    if (metallic > 0) {
      FM.r = mr;
      FM.g = mg;
      FM.b = mb;
      iridescentMetal(sp, c, FM);
      mr = FM.r;
      mg = FM.g;
      mb = FM.b;
    }
  }
  let r = kd * tor * tir * baseR;
  let g = kd * tog * tig * baseG;
  let b = kd * tob * tib * baseB;
  let pdf = lobe.diffuse * iz * INV_PI;
  const alpha = sp.alpha;
  if (alpha > 0) {
    let d: number, g1o: number, g1i: number;
    if (sp.anisotropy > 0) {
      // KHR_materials_anisotropy (gltf-anisotropy.ts).
      anisoTerms(sp, wox, woy, oz, hx, hy, hz);
      d = ANISO.d;
      g1o = ANISO.g1o;
      g1i = ANISO.g1i;
    } else {
      d = ggxD(hz, alpha);
      g1o = ggxG1(oz, alpha);
      g1i = ggxG1(iz, alpha);
    }
    const s = (d * g1o * g1i) / (4 * oz * iz);
    // A thin wall has air on both sides: the same η from either side.
    let fd =
      cGlass > 0 ? fresnelDielectric(c, inside && sp.thickness > 0 ? 1 / sp.ior : sp.ior) : 0;
    let layer = cGlass * fd,
      layerG = layer,
      layerB = layer;
    // A thin wall has air on both sides: the film faces outwards either way.
    if (cGlass > 0 && sp.iridescence > 0 && (!inside || !(sp.thickness > 0))) {
      FG.r = fd;
      FG.g = fd;
      FG.b = fd;
      fd = iridescentGlass(sp, c, FG);
      layer = cGlass * FG.r;
      layerG = cGlass * FG.g;
      layerB = cGlass * FG.b;
    }
    r += s * (metallic * mr + cOpaque * fr + layer);
    g += s * (metallic * mg + cOpaque * fg + layerG);
    b += s * (metallic * mb + cOpaque * fb + layerB);
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
    let fd = lobe.glass > 0 ? fresnelDielectric(oz, eta) : 0;
    const filmGlass = lobe.glass > 0 && sp.iridescence > 0 && (!inside || !(sp.thickness > 0));
    FG.r = fd;
    FG.g = fd;
    FG.b = fd;
    if (filmGlass) fd = iridescentGlass(sp, oz, FG);
    const pMirror = lobe.reflect + lobe.glass * fd;
    if (u < lobe.diffuse + pMirror || u < glassFrom) {
      const metallic = sp.metallic;
      const cOpaque = (1 - metallic) * (1 - sp.transmission);
      const cGlass = (1 - metallic) * sp.transmission;
      const layer = cGlass * FG.r;
      const w = schlickWeight(oz);
      const f90 = f0.f90;
      const inv = 1 / pMirror;
      FM.r = sp.baseR + (1 - sp.baseR) * w;
      FM.g = sp.baseG + (1 - sp.baseG) * w;
      FM.b = sp.baseB + (1 - sp.baseB) * w;
      FD.r = f0.r + (f90 - f0.r) * w;
      FD.g = f0.g + (f90 - f0.g) * w;
      FD.b = f0.b + (f90 - f0.b) * w;
      if (sp.iridescence > 0) {
        if (metallic > 0) iridescentMetal(sp, oz, FM);
        if (cOpaque > 0) iridescentDielectric(sp, oz, FD);
      }
      const metalR = metallic * FM.r;
      const metalG = metallic * FM.g;
      const metalB = metallic * FM.b;
      out.weightR = (metalR + cOpaque * FD.r + layer) * inv;
      out.weightG = (metalG + cOpaque * FD.g + cGlass * FG.g) * inv;
      out.weightB = (metalB + cOpaque * FD.b + cGlass * FG.b) * inv;
      out.wx = -wox;
      out.wy = -woy;
      out.wz = woz;
      out.pdf = pMirror;
      out.isDelta = true;
      return true;
    }
    if (!refract(sp, q, oz, eta, lobe.glass * (1 - fd), out)) return false;
    if (filmGlass) filmRefraction(fd, out);
    return true;
  } else {
    // The sampler reads a query record and α from an array (no boxed doubles);
    // the reflection frame may be mirrored, so it gets its own query.
    VQ.wox = wox;
    VQ.woy = woy;
    VQ.woz = oz;
    VQ.u0 = q.u0;
    VQ.u1 = q.u1;
    VALPHA[0] = alpha;
    if (sp.anisotropy > 0) anisoSampleNormal(sp, wox, woy, oz, q.u0, q.u1, M);
    else ggxSampleVisibleNormal(VQ, VALPHA, 0, M);
    const c = wox * M.x + woy * M.y + oz * M.z;
    if (c <= 0) return false;
    if (u >= glassFrom) {
      // Glass: reflect about m with probability Fd(wo·m), else refract.
      let fd = fresnelDielectric(c, eta);
      const filmGlass = sp.iridescence > 0 && (!inside || !(sp.thickness > 0));
      if (filmGlass) {
        FG.r = fd;
        FG.g = fd;
        FG.b = fd;
        fd = iridescentGlass(sp, c, FG);
      }
      const ug = (u - lobe.diffuse - lobe.reflect) / lobe.glass;
      if (ug >= fd) {
        if (!refract(sp, q, oz, eta, lobe.glass * (1 - fd), out)) return false;
        if (filmGlass) filmRefraction(fd, out);
        return true;
      }
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
 * KHR_materials_iridescence on glass: the refraction was chosen with
 * probability ∝ 1 − mean(F) and carries 1 − F per channel (FG, mean `fd`).
 */
function filmRefraction(fd: number, out: BsdfSample): void {
  const k = 1 / (1 - fd);
  out.weightR *= (1 - FG.r) * k;
  out.weightG *= (1 - FG.g) * k;
  out.weightB *= (1 - FG.b) * k;
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
