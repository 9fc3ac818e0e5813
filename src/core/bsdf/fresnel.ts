/**
 * Fresnel reflectance. `fresnelDielectric` is the exact unpolarised form for
 * a smooth boundary (pbr-book 4e §9.3.5, eq. 9.5–9.6); `schlick` is Schlick's
 * approximation with reflectance F0 at normal incidence, which the scene
 * format prescribes for conductors.
 */

/**
 * Reflectance of a dielectric boundary for light arriving at cosine cosI
 * (≥ 0) from the side of index n1, with eta = n2 / n1. Total internal
 * reflection returns 1.
 */
export function fresnelDielectric(cosI: number, eta: number): number {
  if (eta === 1) return 0; // index-matched: 1 − cos² would round to a spurious TIR at grazing
  const sin2T = (1 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1) return 1;
  const cosT = Math.sqrt(1 - sin2T);
  const rParallel = (eta * cosI - cosT) / (eta * cosI + cosT);
  const rPerpendicular = (cosI - eta * cosT) / (cosI + eta * cosT);
  return 0.5 * (rParallel * rParallel + rPerpendicular * rPerpendicular);
}

/** Schlick's weight (1 − cosθ)^5, shared by the three channels of a colour. */
export function schlickWeight(cosTheta: number): number {
  const m = Math.min(1, Math.max(0, 1 - cosTheta));
  const m2 = m * m;
  return m2 * m2 * m;
}
