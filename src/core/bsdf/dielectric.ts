/**
 * Smooth dielectric boundary (pbr-book 4e §9.3 and §9.5.1): reflection with
 * the exact unpolarised Fresnel reflectance F, refraction by Snell's law with
 * probability 1 − F, total internal reflection when no refracted direction
 * exists. Both lobes are Dirac deltas, so `eval` and `pdf` are zero and only
 * `sample` contributes.
 *
 * Local frame: +z is the *geometric* normal, which points to the outside (air,
 * index 1); wo.z < 0 means the path arrives from inside (index `ior`).
 * In radiance mode a path going from index n1 into n2 carries (n1/n2)²
 * (pbr-book 4e §9.5.2 "Non-Symmetric Scattering and Refraction"); `color`
 * tints transmitted light only.
 */
import { fresnelDielectric } from './fresnel.ts';
import { M_COLOR, M_IOR } from './materials.ts';
import type { BsdfQuery, BsdfSample } from './records.ts';

export function dielectricSample(
  materials: Float64Array,
  o: number,
  q: BsdfQuery,
  out: BsdfSample,
): boolean {
  const wox = q.wox,
    woy = q.woy,
    woz = q.woz;
  const ior = materials[o + M_IOR];
  const entering = woz > 0;
  // eta = n2 / n1, with n1 the side of wo.
  const eta = entering ? ior : 1 / ior;
  const cosI = entering ? woz : -woz;
  const f = fresnelDielectric(cosI, eta);
  out.isDelta = true;
  if (q.u2 < f) {
    out.wx = -wox;
    out.wy = -woy;
    out.wz = woz;
    out.pdf = f;
    out.weightR = 1;
    out.weightG = 1;
    out.weightB = 1;
    out.etaScale = 1;
    return true;
  }
  // Refraction (f < 1 here, so sin²θt < 1).
  const invEta = 1 / eta;
  const sin2T = (1 - cosI * cosI) * invEta * invEta;
  const cosT = Math.sqrt(Math.max(0, 1 - sin2T));
  const side = entering ? 1 : -1;
  const k = cosI * invEta - cosT;
  out.wx = -wox * invEta;
  out.wy = -woy * invEta;
  out.wz = -woz * invEta + k * side;
  out.pdf = 1 - f;
  const scale = invEta * invEta;
  out.weightR = materials[o + M_COLOR] * scale;
  out.weightG = materials[o + M_COLOR + 1] * scale;
  out.weightB = materials[o + M_COLOR + 2] * scale;
  out.etaScale = eta * eta;
  return true;
}
