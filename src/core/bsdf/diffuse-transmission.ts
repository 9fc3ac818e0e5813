/**
 * KHR_materials_diffuse_transmission's lobe: a Lambertian BTDF on the
 * hemisphere opposite wo. The extension defines the dielectric base as
 *
 *   mix(diffuse_brdf(baseColor), diffuse_btdf(diffuseTransmissionColor), diffuseTransmission)
 *
 * under the specular layer, so the BTDF is weighted like the Lambert base
 * of gltf-pbr.ts: by what the layer transmits on the way in and on the way
 * out, (1 − F(|cosθo|))(1 − F(|cosθi|)) — the reciprocal, energy-conserving
 * coupling that file's header explains — and by (1 − metallic)(1 − transmission).
 * The wall is thin (the extension's default): the light leaves on the other
 * side at the same point, and f(wo, wi) = f(wi, wo) because the weight is
 * symmetric in the two cosines.
 *
 * Frame: z is the normal on wo's side (gltf-pbr.ts mirrors it for a path
 * arriving from behind); cosO = wo.z > 0, cosI = −wi.z > 0.
 */
import type { ShadingParams } from './shading.ts';
import { schlickWeight } from './fresnel.ts';

const INV_PI = 1 / Math.PI;

/** F0 per channel and f90 of the dielectric layer (gltf-pbr.ts's record). */
export interface LayerF0 {
  r: number;
  g: number;
  b: number;
  f90: number;
}

/**
 * The lobe's weight in the lobe choice at cosO: its share of the energy,
 * (1 − metallic)(1 − transmission) · dt · mean over channels of (1 − F(cosO)) · colour.
 */
export function diffuseTransmissionAlbedo(sp: ShadingParams, f0: LayerF0, cosO: number): number {
  const w = schlickWeight(cosO);
  const f90 = f0.f90;
  const c = (1 - sp.metallic) * (1 - sp.transmission) * sp.diffuseTransmission;
  return (
    (c *
      ((1 - f0.r - (f90 - f0.r) * w) * sp.dtR +
        (1 - f0.g - (f90 - f0.g) * w) * sp.dtG +
        (1 - f0.b - (f90 - f0.b) * w) * sp.dtB)) /
    3
  );
}

/**
 * f of the lobe for cosines cosO, cosI > 0 on opposite sides, and its pdf:
 * `probability` (the lobe's selection probability) times the cosine density.
 */
export function evalDiffuseTransmission(
  sp: ShadingParams,
  f0: LayerF0,
  probability: number,
  cosO: number,
  cosI: number,
  out: { r: number; g: number; b: number; pdf: number },
): void {
  const wo5 = schlickWeight(cosO);
  const wi5 = schlickWeight(cosI);
  const f90 = f0.f90;
  const k = (1 - sp.metallic) * (1 - sp.transmission) * sp.diffuseTransmission * INV_PI;
  out.r = k * (1 - f0.r - (f90 - f0.r) * wo5) * (1 - f0.r - (f90 - f0.r) * wi5) * sp.dtR;
  out.g = k * (1 - f0.g - (f90 - f0.g) * wo5) * (1 - f0.g - (f90 - f0.g) * wi5) * sp.dtG;
  out.b = k * (1 - f0.b - (f90 - f0.b) * wo5) * (1 - f0.b - (f90 - f0.b) * wi5) * sp.dtB;
  out.pdf = probability * cosI * INV_PI;
}
