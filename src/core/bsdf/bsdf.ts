/**
 * The BSDF interface of pbrt — `eval`, `sample`, `pdf` — dispatched over the
 * fixed set of material kinds by one switch on the numeric tag. Directions
 * are in the local shading frame (see each material for which side +z is).
 */
import { conductorEval, conductorPdf, conductorSample } from './conductor.ts';
import { dielectricSample } from './dielectric.ts';
import { diffuseEval, diffusePdf, diffuseSample } from './diffuse.ts';
import {
  MATERIAL_CONDUCTOR,
  MATERIAL_DIELECTRIC,
  MATERIAL_DIFFUSE,
  MATERIAL_STRIDE,
  M_TYPE,
} from './materials.ts';
import type { BsdfSample, BsdfValue } from './records.ts';

/** f(wo, wi) of material `m` into `out` (zero for delta lobes). */
export function bsdfEval(
  materials: Float64Array,
  m: number,
  wox: number,
  woy: number,
  woz: number,
  wix: number,
  wiy: number,
  wiz: number,
  out: BsdfValue,
): void {
  const o = m * MATERIAL_STRIDE;
  switch (materials[o + M_TYPE]) {
    case MATERIAL_DIFFUSE:
      diffuseEval(materials, o, woz, wiz, out);
      return;
    case MATERIAL_CONDUCTOR:
      conductorEval(materials, o, wox, woy, woz, wix, wiy, wiz, out);
      return;
    default:
      out.r = 0;
      out.g = 0;
      out.b = 0;
  }
}

/** Solid-angle density with which `bsdfSample` returns wi (zero for delta lobes). */
export function bsdfPdf(
  materials: Float64Array,
  m: number,
  wox: number,
  woy: number,
  woz: number,
  wix: number,
  wiy: number,
  wiz: number,
): number {
  const o = m * MATERIAL_STRIDE;
  switch (materials[o + M_TYPE]) {
    case MATERIAL_DIFFUSE:
      return diffusePdf(woz, wiz);
    case MATERIAL_CONDUCTOR:
      return conductorPdf(materials, o, wox, woy, woz, wix, wiy, wiz);
    default:
      return 0;
  }
}

/**
 * Samples wi for wo from three uniform numbers (u2 picks between delta
 * lobes). Returns false when the sample carries no energy.
 */
export function bsdfSample(
  materials: Float64Array,
  m: number,
  wox: number,
  woy: number,
  woz: number,
  u0: number,
  u1: number,
  u2: number,
  out: BsdfSample,
): boolean {
  const o = m * MATERIAL_STRIDE;
  switch (materials[o + M_TYPE]) {
    case MATERIAL_DIFFUSE:
      return diffuseSample(materials, o, woz, u0, u1, out);
    case MATERIAL_CONDUCTOR:
      return conductorSample(materials, o, wox, woy, woz, u0, u1, out);
    case MATERIAL_DIELECTRIC:
      return dielectricSample(materials, o, wox, woy, woz, u2, out);
    default:
      return false;
  }
}

/** Whether material m's BSDF uses the geometric (outward) normal rather than the side of wo. */
export function usesGeometricSide(materials: Float64Array, m: number): boolean {
  return materials[m * MATERIAL_STRIDE + M_TYPE] === MATERIAL_DIELECTRIC;
}
