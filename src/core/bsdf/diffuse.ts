/**
 * Lambertian reflection, f = albedo / π (pbr-book 4e §9.2), sampled by the
 * cosine-weighted hemisphere so the weight f·cosθ/pdf is just the albedo.
 * Local frame: +z is the normal on the side of wo.
 */
import { squareToCosineHemisphere, squareToCosineHemispherePdf } from '../sampling/warps.ts';
import { M_COLOR } from './materials.ts';
import type { BsdfSample, BsdfValue } from './records.ts';

const INV_PI = 1 / Math.PI;

export function diffuseEval(
  materials: Float64Array,
  o: number,
  woz: number,
  wiz: number,
  out: BsdfValue,
): void {
  if (woz <= 0 || wiz <= 0) {
    out.r = 0;
    out.g = 0;
    out.b = 0;
    return;
  }
  out.r = materials[o + M_COLOR] * INV_PI;
  out.g = materials[o + M_COLOR + 1] * INV_PI;
  out.b = materials[o + M_COLOR + 2] * INV_PI;
}

export function diffusePdf(woz: number, wiz: number): number {
  return woz > 0 ? squareToCosineHemispherePdf(wiz) : 0;
}

export function diffuseSample(
  materials: Float64Array,
  o: number,
  woz: number,
  u0: number,
  u1: number,
  out: BsdfSample,
): boolean {
  if (woz <= 0) return false;
  const w = DIRECTION;
  squareToCosineHemisphere(u0, u1, w);
  if (w.z <= 0) return false;
  out.wx = w.x;
  out.wy = w.y;
  out.wz = w.z;
  out.pdf = squareToCosineHemispherePdf(w.z);
  out.weightR = materials[o + M_COLOR];
  out.weightG = materials[o + M_COLOR + 1];
  out.weightB = materials[o + M_COLOR + 2];
  out.isDelta = false;
  out.etaScale = 1;
  return true;
}
const DIRECTION = { x: 0, y: 0, z: 1 };
