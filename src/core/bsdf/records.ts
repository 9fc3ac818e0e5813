/** Caller-owned records the BSDFs write into, so hot loops allocate nothing. */

/** Result of `sample`: a direction in the local frame and its weight f·|cosθi|/pdf. */
export class BsdfSample {
  wx = 0;
  wy = 0;
  wz = 1;
  weightR = 0;
  weightG = 0;
  weightB = 0;
  /** Solid-angle density, or the discrete probability of a delta lobe. */
  pdf = 0;
  /** True when the lobe is a Dirac delta (mirror, smooth glass). */
  isDelta = false;
  /** Squared relative IOR n2/n1 when the sample refracted, else 1 (for Russian roulette). */
  etaScale = 1;
}

/** Result of `eval`: the BSDF value f(wo, wi) per channel (without the cosine). */
export class BsdfValue {
  r = 0;
  g = 0;
  b = 0;
}
