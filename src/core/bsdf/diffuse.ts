/**
 * Lambertian reflection, f = albedo / π (pbr-book 4e §9.2), sampled by the
 * cosine-weighted hemisphere so the weight f·cosθ/pdf is just the albedo.
 * Local frame: +z is the normal on the side of wo.
 */
import { squareToCosineHemisphere, squareToCosineHemispherePdf } from '../sampling/warps.ts';
import { M_COLOR } from './materials.ts';
import type { BsdfQuery, BsdfSample, BsdfValue } from './records.ts';

const INV_PI = 1 / Math.PI;
const DIRECTION = { x: 0, y: 0, z: 1 };

export function diffuseEval(
  materials: Float64Array,
  o: number,
  q: BsdfQuery,
  out: BsdfValue,
): void {
  if (q.woz <= 0 || q.wiz <= 0) {
    out.r = 0;
    out.g = 0;
    out.b = 0;
    out.pdf = 0;
    return;
  }
  out.r = materials[o + M_COLOR] * INV_PI;
  out.g = materials[o + M_COLOR + 1] * INV_PI;
  out.b = materials[o + M_COLOR + 2] * INV_PI;
  out.pdf = squareToCosineHemispherePdf(q.wiz);
}

export function diffusePdf(q: BsdfQuery): number {
  return q.woz > 0 ? squareToCosineHemispherePdf(q.wiz) : 0;
}

export function diffuseSample(
  materials: Float64Array,
  o: number,
  q: BsdfQuery,
  out: BsdfSample,
): boolean {
  if (q.woz <= 0) return false;
  const w = DIRECTION;
  squareToCosineHemisphere(q.u0, q.u1, w);
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
