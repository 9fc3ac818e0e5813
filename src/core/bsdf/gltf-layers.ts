/**
 * The layered glTF material: KHR_materials_clearcoat over KHR_materials_sheen over the
 * metallic–roughness base of gltf-pbr.ts, in the order the extensions' layering
 * sections give (the sheen README: "If clearcoat is active at the same time, clearcoat
 * is layered on top of sheen"), and KHR_materials_unlit:
 *
 *   f(wo, wi) = f_coat(wo, wi) + T(wo) T(wi) · [ f_sheen(wo, wi) + s(wo, wi) · f_base(wo, wi) ]
 *   T(w)      = 1 − c · F_coat(|Nc·w|)                                    (clearcoat.ts)
 *   s         = min(1 − max3(sheenColor) Ê(μo), 1 − max3(sheenColor) Ê(μi))   (sheen README)
 *   f_sheen   = sheenColor · D·V / max(1, E(μo), E(μi)),   Ê = min(E, 1)        (sheen.ts)
 *
 * Deviations from the specifications, each for reciprocity or energy conservation:
 * - the coat's `fresnel_coat` mixes the layers below by 1 − c·F(V·Nc), a function of
 *   the view alone, which is not reciprocal; we weight them by T(wo)·T(wi), identical
 *   at wi = wo and symmetric — the same device gltf-pbr.ts uses for its diffuse base
 *   (Burley 2012). The coat lobe is the Appendix B microfacet form, reciprocal as is;
 * - the Charlie lobe with Conty and Kulla's fitted Λ reflects more than it receives at
 *   grazing angles when it is sharp (E(μ, r) reaches 6 at μ → 0, r = 0.03: sheen-lut.ts).
 *   Dividing it by max(1, E(μo), E(μi)) — symmetric, and 1 wherever E ≤ 1, which is
 *   every roughness above about 0.3 at every angle — bounds its albedo by min(E(μo), 1),
 *   and the albedo scaling uses that same Ê, so sheen + scaled base never exceed 1;
 * - the sheen's albedo scaling is the spec's symmetric min; the one-sided shortcut
 *   1 − max3·E(V·N) that renderers often use is not reciprocal.
 * The layers are seen from outside only: on a transmissive material a path inside the
 * solid (wo.z < 0) meets the plain base (its coat and sheen face the outside world).
 *
 * Sampling: one of coat, sheen and base is picked with probabilities of wo alone —
 * c·F(Nc·wo), T(wo)·max3·Ê(μo) and T(wo)·(1 − max3·Ê(μo)), which sum to 1 — and `pdf`
 * is the exact mixture of the non-delta lobes (pbr-book 4e §9.7). The sheen lobe is
 * sampled uniformly over the hemisphere (sheen.ts). Delta lobes (a smooth coat about
 * Nc, and the base's own mirror and refraction) are separate Dirac branches.
 *
 * Unlit (KHR_materials_unlit): the BSDF is 0 and sampling ends the path; the base
 * colour is the surface's emission, seen by paths that reach it but never sampled as a
 * light (layers-fill.ts, compile-gltf.ts, docs/gltf.md).
 *
 * Without a coat (c = 0) and with a black sheen the calls fall straight through to the
 * base, so such materials render bit-identically to gltf-pbr.ts alone.
 */
import {
  coatDirection,
  coatEval,
  coatFresnel,
  coatSample,
  coatTransmit,
  coatValue,
  setCoatFrame,
} from './clearcoat.ts';
import { gltfEval, gltfPdf, gltfSample } from './gltf-pbr.ts';
import { BsdfQuery, BsdfSample, BsdfValue } from './records.ts';
import type { ShadingParams } from './shading.ts';
import { charlieDV, sheenAlbedo, sheenAlpha } from './sheen.ts';

const INV_2PI = 1 / (2 * Math.PI);
const LQ = new BsdfQuery();
const BASE = new BsdfValue();
const BS = new BsdfSample();

/** Whether sp has no layer at all (the plain base of gltf-pbr.ts). */
function plain(sp: ShadingParams): boolean {
  return sp.clearcoat === 0 && sp.sheenR === 0 && sp.sheenG === 0 && sp.sheenB === 0 && !sp.unlit;
}

/** Lobe probabilities of the current call (functions of wo), and the wo-side terms. */
const lobe = { coat: 0, sheen: 0, base: 0, tO: 1, eO: 0, eHatO: 0, sheenMax: 0 };

function selectLayers(sp: ShadingParams, wox: number, woy: number, woz: number): void {
  const nc = Math.abs(sp.ccnx * wox + sp.ccny * woy + sp.ccnz * woz);
  const pCoat = sp.clearcoat * coatFresnel(nc);
  const tO = 1 - pCoat;
  const sheenMax = Math.max(sp.sheenR, sp.sheenG, sp.sheenB);
  const eO = sheenMax > 0 ? sheenAlbedo(woz, sp.sheenRoughness) : 0;
  const eHatO = Math.min(eO, 1);
  lobe.coat = pCoat;
  lobe.sheen = tO * sheenMax * eHatO;
  lobe.base = tO * (1 - sheenMax * eHatO);
  lobe.tO = tO;
  lobe.eO = eO;
  lobe.eHatO = eHatO;
  lobe.sheenMax = sheenMax;
}

/**
 * The layered f and pdf for wo, wi both above the surface (LQ holds them, wo.z, wi.z >
 * 0). Needs selectLayers for this wo first.
 */
function evalLayers(sp: ShadingParams, out: BsdfValue): void {
  const wox = LQ.wox,
    woy = LQ.woy,
    woz = LQ.woz,
    wix = LQ.wix,
    wiy = LQ.wiy,
    wiz = LQ.wiz;
  const tI = coatTransmit(sp, wix, wiy, wiz);
  const tt = lobe.tO * tI;
  let r = 0,
    g = 0,
    b = 0,
    pdf = 0;
  // Sheen over base.
  let s = 1;
  if (lobe.sheenMax > 0) {
    const eI = sheenAlbedo(wiz, sp.sheenRoughness);
    s = Math.min(1 - lobe.sheenMax * lobe.eHatO, 1 - lobe.sheenMax * Math.min(eI, 1));
    const hx = wox + wix;
    const hy = woy + wiy;
    const hz = woz + wiz;
    const cosH = hz / Math.sqrt(hx * hx + hy * hy + hz * hz);
    const dv = charlieDV(woz, wiz, cosH, sheenAlpha(sp.sheenRoughness)) / Math.max(1, lobe.eO, eI);
    r = sp.sheenR * dv;
    g = sp.sheenG * dv;
    b = sp.sheenB * dv;
    pdf = lobe.sheen * INV_2PI;
  }
  if (lobe.base > 0 || s > 0) {
    gltfEval(sp, LQ, BASE);
    r += s * BASE.r;
    g += s * BASE.g;
    b += s * BASE.b;
    pdf += lobe.base * BASE.pdf;
  }
  r *= tt;
  g *= tt;
  b *= tt;
  // The coat on top.
  if (sp.clearcoat > 0) {
    coatEval(sp, wox, woy, woz, wix, wiy, wiz);
    r += coatValue.f;
    g += coatValue.f;
    b += coatValue.f;
    pdf += lobe.coat * coatValue.pdf;
  }
  out.r = r;
  out.g = g;
  out.b = b;
  out.pdf = pdf;
}

/** f(q.wo, q.wi) without delta lobes, and the density `layeredSample` has for q.wi. */
export function layeredEval(sp: ShadingParams, q: BsdfQuery, out: BsdfValue): void {
  if (plain(sp)) {
    gltfEval(sp, q, out);
    return;
  }
  if (sp.unlit || !(q.woz > 0) || !(q.wiz > 0)) {
    if (sp.unlit) {
      out.r = 0;
      out.g = 0;
      out.b = 0;
      out.pdf = 0;
    } else gltfEval(sp, q, out);
    return;
  }
  selectLayers(sp, q.wox, q.woy, q.woz);
  LQ.wox = q.wox;
  LQ.woy = q.woy;
  LQ.woz = q.woz;
  LQ.wix = q.wix;
  LQ.wiy = q.wiy;
  LQ.wiz = q.wiz;
  evalLayers(sp, out);
}

const PDF_VALUE = new BsdfValue();

/** Solid-angle density with which `layeredSample` returns q.wi (non-delta lobes only). */
export function layeredPdf(sp: ShadingParams, q: BsdfQuery): number {
  if (plain(sp)) return gltfPdf(sp, q);
  layeredEval(sp, q, PDF_VALUE);
  return PDF_VALUE.pdf;
}

/**
 * Samples wi: q.u2 picks coat, sheen or base (rescaled, it is the base's own lobe
 * choice), q.u0, q.u1 the direction. Returns false when the sample carries no energy.
 */
export function layeredSample(sp: ShadingParams, q: BsdfQuery, out: BsdfSample): boolean {
  if (plain(sp)) return gltfSample(sp, q, out);
  if (sp.unlit) return false;
  if (!(q.woz > 0)) return gltfSample(sp, q, out);
  const wox = q.wox,
    woy = q.woy,
    woz = q.woz;
  selectLayers(sp, wox, woy, woz);
  setCoatFrame(sp);
  LQ.wox = wox;
  LQ.woy = woy;
  LQ.woz = woz;
  const u = q.u2;
  out.etaScale = 1;
  if (u < lobe.coat) {
    if (!coatSample(sp, wox, woy, woz, q.u0, q.u1)) return false;
    const d = coatDirection;
    if (!(d.z > 0)) return false;
    if (sp.clearcoatAlpha === 0) {
      // Mirror about Nc: f·cos/pdf = c·F(Nc·wo) / lobe.coat = 1.
      out.wx = d.x;
      out.wy = d.y;
      out.wz = d.z;
      out.weightR = 1;
      out.weightG = 1;
      out.weightB = 1;
      out.pdf = lobe.coat;
      out.isDelta = true;
      return true;
    }
    LQ.wix = d.x;
    LQ.wiy = d.y;
    LQ.wiz = d.z;
  } else if (u < lobe.coat + lobe.sheen) {
    // Uniform over the hemisphere (pbr-book 4e §A.5.2): z = 1 − u0 ∈ (0, 1].
    const z = 1 - q.u0;
    const rr = Math.sqrt(Math.max(0, 1 - z * z));
    const phi = 2 * Math.PI * q.u1;
    LQ.wix = rr * Math.cos(phi);
    LQ.wiy = rr * Math.sin(phi);
    LQ.wiz = z;
  } else {
    if (!(lobe.base > 0)) return false;
    LQ.u0 = q.u0;
    LQ.u1 = q.u1;
    LQ.u2 = Math.min((u - lobe.coat - lobe.sheen) / lobe.base, 1 - Number.EPSILON / 2);
    if (!gltfSample(sp, LQ, BS)) return false;
    if (BS.isDelta) {
      // The base's mirror or refraction, seen through the layers above.
      const wx = BS.wx,
        wy = BS.wy,
        wz = BS.wz;
      const az = Math.abs(wz);
      let s = 1;
      if (lobe.sheenMax > 0) {
        const eI = Math.min(sheenAlbedo(az, sp.sheenRoughness), 1);
        s = Math.min(1 - lobe.sheenMax * lobe.eHatO, 1 - lobe.sheenMax * eI);
      }
      const k = (lobe.tO * coatTransmit(sp, wx, wy, wz) * s) / lobe.base;
      out.wx = wx;
      out.wy = wy;
      out.wz = wz;
      out.weightR = BS.weightR * k;
      out.weightG = BS.weightG * k;
      out.weightB = BS.weightB * k;
      out.pdf = BS.pdf * lobe.base;
      out.isDelta = true;
      out.etaScale = BS.etaScale;
      return true;
    }
    LQ.wix = BS.wx;
    LQ.wiy = BS.wy;
    LQ.wiz = BS.wz;
  }
  if (!(LQ.wiz > 0)) return false;
  const v = PDF_VALUE;
  evalLayers(sp, v);
  if (!(v.pdf > 0)) return false;
  const k = LQ.wiz / v.pdf;
  out.wx = LQ.wix;
  out.wy = LQ.wiy;
  out.wz = LQ.wiz;
  out.weightR = v.r * k;
  out.weightG = v.g * k;
  out.weightB = v.b * k;
  out.pdf = v.pdf;
  out.isDelta = false;
  return true;
}
