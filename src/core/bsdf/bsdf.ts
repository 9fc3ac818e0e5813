/**
 * The BSDF interface of pbrt — `eval`, `sample`, `pdf` — dispatched over the
 * fixed set of material kinds by one switch on the numeric tag. Directions
 * are in the local shading frame (see each material for which side +z is).
 */
import { conductorEval, conductorPdf, conductorSample } from './conductor.ts';
import { dielectricSample } from './dielectric.ts';
import { diffuseEval, diffusePdf, diffuseSample } from './diffuse.ts';
import { layeredEval, layeredPdf, layeredSample } from './gltf-layers.ts';
import {
  MATERIAL_CONDUCTOR,
  MATERIAL_DIELECTRIC,
  MATERIAL_DIFFUSE,
  MATERIAL_GLTF,
  MATERIAL_STRIDE,
  M_GEOMETRIC_SIDE,
  M_TYPE,
} from './materials.ts';
import type { BsdfQuery, BsdfSample, BsdfValue } from './records.ts';

/**
 * f(q.wo, q.wi) of material `m` into `out`, with the density `bsdfSample`
 * has for q.wi in `out.pdf` (both zero for delta lobes).
 */
export function bsdfEval(materials: Float64Array, m: number, q: BsdfQuery, out: BsdfValue): void {
  const o = m * MATERIAL_STRIDE;
  switch (materials[o + M_TYPE]) {
    case MATERIAL_DIFFUSE:
      diffuseEval(materials, o, q, out);
      return;
    case MATERIAL_CONDUCTOR:
      conductorEval(materials, o, q, out);
      return;
    case MATERIAL_GLTF:
      layeredEval(q.shading, q, out);
      return;
    default:
      out.r = 0;
      out.g = 0;
      out.b = 0;
      out.pdf = 0;
  }
}

/** Solid-angle density with which `bsdfSample` returns q.wi (zero for delta lobes). */
export function bsdfPdf(materials: Float64Array, m: number, q: BsdfQuery): number {
  const o = m * MATERIAL_STRIDE;
  switch (materials[o + M_TYPE]) {
    case MATERIAL_DIFFUSE:
      return diffusePdf(q);
    case MATERIAL_CONDUCTOR:
      return conductorPdf(materials, o, q);
    case MATERIAL_GLTF:
      return layeredPdf(q.shading, q);
    default:
      return 0;
  }
}

/**
 * Samples wi for q.wo from q.u0, q.u1 (the direction) and q.u2 (the choice
 * between lobes). Returns false when the sample carries no energy.
 */
export function bsdfSample(
  materials: Float64Array,
  m: number,
  q: BsdfQuery,
  out: BsdfSample,
): boolean {
  const o = m * MATERIAL_STRIDE;
  switch (materials[o + M_TYPE]) {
    case MATERIAL_DIFFUSE:
      return diffuseSample(materials, o, q, out);
    case MATERIAL_CONDUCTOR:
      return conductorSample(materials, o, q, out);
    case MATERIAL_DIELECTRIC:
      return dielectricSample(materials, o, q, out);
    case MATERIAL_GLTF:
      return layeredSample(q.shading, q, out);
    default:
      return false;
  }
}

/** Whether material m's BSDF uses the geometric (outward) normal rather than the side of wo. */
export function usesGeometricSide(materials: Float64Array, m: number): boolean {
  return materials[m * MATERIAL_STRIDE + M_GEOMETRIC_SIDE] !== 0;
}
