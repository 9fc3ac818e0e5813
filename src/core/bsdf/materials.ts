/**
 * Materials compiled into one Float64Array, MATERIAL_STRIDE numbers each, so
 * the tracer reads them without touching objects. The type tag selects the
 * BSDF in one switch (see bsdf.ts).
 */
import type { MaterialDesc } from '../scene/format/types.ts';

export const MATERIAL_DIFFUSE = 0;
export const MATERIAL_CONDUCTOR = 1;
export const MATERIAL_DIELECTRIC = 2;
/**
 * glTF 2.0 metallic–roughness (gltf-pbr.ts). Its parameters can vary per
 * hit, so the BSDF reads them from the query's ShadingParams, which the
 * integrator fills from the glTF material table (src/core/gltf/).
 */
export const MATERIAL_GLTF = 3;

export const MATERIAL_STRIDE = 16;
/** Offsets inside one material record. */
export const M_TYPE = 0;
/** albedo (diffuse) or color (conductor F0, dielectric transmission tint) */
export const M_COLOR = 1;
/** GGX alpha = roughness² (conductor) */
export const M_ALPHA = 4;
/** relative index of refraction (dielectric) */
export const M_IOR = 5;
export const M_EMISSION = 6;
/** 1 when the emission is non-zero */
export const M_EMISSIVE = 9;
/** 1 when the BSDF is a Dirac delta (mirror, smooth glass): no light sampling there */
export const M_DELTA = 10;
/** glTF materials: the index of the material in the glTF material table */
export const M_GLTF_INDEX = 11;
/**
 * 1 when the BSDF needs the geometric (outward) normal to tell inside from
 * outside rather than a frame facing wo: dielectrics and transmissive glTF
 * materials
 */
export const M_GEOMETRIC_SIDE = 12;

/**
 * Smallest GGX alpha used: below it (roughness < 1e-3) the lobe is narrower
 * than double precision can resolve usefully, and roughness 0 is handled as
 * an exact mirror instead.
 */
export const MIN_ALPHA = 1e-6;

export function compileMaterials(descs: MaterialDesc[]): Float64Array {
  const out = new Float64Array(descs.length * MATERIAL_STRIDE);
  descs.forEach((m, i) => {
    const o = i * MATERIAL_STRIDE;
    const color = m.type === 'diffuse' ? m.albedo : m.color;
    out[o + M_COLOR] = color[0];
    out[o + M_COLOR + 1] = color[1];
    out[o + M_COLOR + 2] = color[2];
    out[o + M_EMISSION] = m.emission[0];
    out[o + M_EMISSION + 1] = m.emission[1];
    out[o + M_EMISSION + 2] = m.emission[2];
    out[o + M_EMISSIVE] = m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0 ? 1 : 0;
    switch (m.type) {
      case 'diffuse':
        out[o + M_TYPE] = MATERIAL_DIFFUSE;
        break;
      case 'conductor':
        out[o + M_TYPE] = MATERIAL_CONDUCTOR;
        out[o + M_ALPHA] = m.roughness === 0 ? 0 : Math.max(MIN_ALPHA, m.roughness * m.roughness);
        out[o + M_DELTA] = m.roughness === 0 ? 1 : 0;
        break;
      case 'dielectric':
        if (m.roughness > 0) {
          throw new Error('rough dielectrics (roughness > 0) are not supported by pathwise');
        }
        out[o + M_TYPE] = MATERIAL_DIELECTRIC;
        out[o + M_IOR] = m.ior;
        out[o + M_DELTA] = 1;
        out[o + M_GEOMETRIC_SIDE] = 1;
        break;
    }
  });
  return out;
}
