/**
 * The albedo of a hit's material for the denoising features (aux.ts): the record one
 * sample's albedo and normal are written into, and the glTF material's layer sum.
 * Definitions per material: docs/film-format.md, "What albedo and normal mean".
 */
import type { ShadingParams } from '../bsdf/shading.ts';

/** The coat's reflectance at normal incidence (ior 1.5): KHR_materials_clearcoat's F0. */
const COAT_F0 = 0.04;

/** One sample's auxiliary values, written by traceAux. */
export class AuxSample {
  ar = 0;
  ag = 0;
  ab = 0;
  nx = 0;
  ny = 0;
  nz = 0;
}

/** v clamped to [0, 1]; NaN gives 0. */
export const clamp01 = (v: number): number => (v > 0 ? (v < 1 ? v : 1) : 0);

/**
 * The albedo of a glTF hit (OIDN: "the weighted sum of the albedos of the individual
 * layers"): the base colour — which is the diffuse colour, a metal's F0 and the
 * transmission tint alike — blended toward the diffuse-transmission colour by its
 * weight, under the sheen (weight: its largest channel, the albedo-scaling of
 * KHR_materials_sheen with E taken as 1) and the clear coat (F0 0.04 times its
 * weight). Unlit: the base colour. Emission is added by the caller.
 */
export function gltfAlbedo(sp: ShadingParams, out: AuxSample): void {
  let r = sp.baseR,
    g = sp.baseG,
    b = sp.baseB;
  if (!sp.unlit) {
    const dt = sp.diffuseTransmission * (1 - sp.metallic) * (1 - sp.transmission);
    if (dt > 0) {
      r += (sp.dtR - r) * dt;
      g += (sp.dtG - g) * dt;
      b += (sp.dtB - b) * dt;
    }
    const sheen = Math.max(sp.sheenR, sp.sheenG, sp.sheenB);
    if (sheen > 0) {
      r = sp.sheenR + (1 - sheen) * r;
      g = sp.sheenG + (1 - sheen) * g;
      b = sp.sheenB + (1 - sheen) * b;
    }
    if (sp.clearcoat > 0) {
      const c = sp.clearcoat * COAT_F0;
      r = c + (1 - c) * r;
      g = c + (1 - c) * g;
      b = c + (1 - c) * b;
    }
  }
  out.ar = r;
  out.ag = g;
  out.ab = b;
}

/** Writes the sample's values; a throughput above 1 (glass's tint is ≤ 1, but a chain's weight may round) is clamped. */
export function finish(
  out: AuxSample,
  r: number,
  g: number,
  b: number,
  nx: number,
  ny: number,
  nz: number,
): void {
  out.ar = clamp01(r);
  out.ag = clamp01(g);
  out.ab = clamp01(b);
  out.nx = nx;
  out.ny = ny;
  out.nz = nz;
}
