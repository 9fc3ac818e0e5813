/**
 * Conductor per `pathwise-scene/1`: GGX microfacet reflection with
 * α = roughness², separable Smith G = G1(wo)·G1(wi) and Schlick Fresnel with
 * F0 = color (Walter et al. 2007; pbr-book 4e §9.6). Sampling draws visible
 * normals (Heitz 2018), so pdf = G1(wo)·D(m) / (4·cosθo) and the sample
 * weight reduces to F·G1(wi). Roughness 0 is an exact mirror whose
 * reflectance is Schlick's F(cosθo).
 * Local frame: +z is the normal on the side of wo.
 */
import { ggxD, ggxG1, ggxSampleVisibleNormal } from './ggx.ts';
import { schlickWeight } from './fresnel.ts';
import { M_ALPHA, M_COLOR } from './materials.ts';
import type { BsdfQuery, BsdfSample, BsdfValue } from './records.ts';

const M = { x: 0, y: 0, z: 1 };

export function conductorEval(
  materials: Float64Array,
  o: number,
  q: BsdfQuery,
  out: BsdfValue,
): void {
  const alpha = materials[o + M_ALPHA];
  const wox = q.wox,
    woy = q.woy,
    woz = q.woz;
  const wix = q.wix,
    wiy = q.wiy,
    wiz = q.wiz;
  out.r = 0;
  out.g = 0;
  out.b = 0;
  out.pdf = 0;
  if (alpha === 0 || woz <= 0 || wiz <= 0) return;
  let hx = wox + wix;
  let hy = woy + wiy;
  let hz = woz + wiz;
  const hl = Math.sqrt(hx * hx + hy * hy + hz * hz);
  if (hl === 0) return;
  hx /= hl;
  hy /= hl;
  hz /= hl;
  const cosOH = wox * hx + woy * hy + woz * hz;
  const d = ggxD(hz, alpha);
  const g1o = ggxG1(woz, alpha);
  const common = (d * g1o * ggxG1(wiz, alpha)) / (4 * woz * wiz);
  // The visible-normal density of sampling wi: G1(wo)·D(h) / (4·cosθo).
  out.pdf = (g1o * d) / (4 * woz);
  const w = schlickWeight(cosOH);
  const r0 = materials[o + M_COLOR];
  const g0 = materials[o + M_COLOR + 1];
  const b0 = materials[o + M_COLOR + 2];
  out.r = common * (r0 + (1 - r0) * w);
  out.g = common * (g0 + (1 - g0) * w);
  out.b = common * (b0 + (1 - b0) * w);
}

export function conductorPdf(materials: Float64Array, o: number, q: BsdfQuery): number {
  const alpha = materials[o + M_ALPHA];
  const wox = q.wox,
    woy = q.woy,
    woz = q.woz;
  const wix = q.wix,
    wiy = q.wiy,
    wiz = q.wiz;
  if (alpha === 0 || woz <= 0 || wiz <= 0) return 0;
  let hx = wox + wix;
  let hy = woy + wiy;
  let hz = woz + wiz;
  const hl = Math.sqrt(hx * hx + hy * hy + hz * hz);
  if (hl === 0) return 0;
  hz /= hl;
  return (ggxG1(woz, alpha) * ggxD(hz, alpha)) / (4 * woz);
}

export function conductorSample(
  materials: Float64Array,
  o: number,
  q: BsdfQuery,
  out: BsdfSample,
): boolean {
  const wox = q.wox,
    woy = q.woy,
    woz = q.woz;
  if (woz <= 0) return false;
  const alpha = materials[o + M_ALPHA];
  const r0 = materials[o + M_COLOR];
  const g0 = materials[o + M_COLOR + 1];
  const b0 = materials[o + M_COLOR + 2];
  out.etaScale = 1;
  if (alpha === 0) {
    const w = schlickWeight(woz);
    out.wx = -wox;
    out.wy = -woy;
    out.wz = woz;
    out.pdf = 1;
    out.isDelta = true;
    out.weightR = r0 + (1 - r0) * w;
    out.weightG = g0 + (1 - g0) * w;
    out.weightB = b0 + (1 - b0) * w;
    return true;
  }
  ggxSampleVisibleNormal(q, materials, o + M_ALPHA, M);
  const cosOM = wox * M.x + woy * M.y + woz * M.z;
  if (cosOM <= 0) return false;
  const wix = 2 * cosOM * M.x - wox;
  const wiy = 2 * cosOM * M.y - woy;
  const wiz = 2 * cosOM * M.z - woz;
  if (wiz <= 0) return false;
  out.wx = wix;
  out.wy = wiy;
  out.wz = wiz;
  out.pdf = (ggxG1(woz, alpha) * ggxD(M.z, alpha)) / (4 * woz);
  out.isDelta = false;
  const g1 = ggxG1(wiz, alpha);
  const w = schlickWeight(cosOM);
  out.weightR = (r0 + (1 - r0) * w) * g1;
  out.weightG = (g0 + (1 - g0) * w) * g1;
  out.weightB = (b0 + (1 - b0) * w) * g1;
  return true;
}
