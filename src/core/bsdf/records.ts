/** Caller-owned records the BSDFs write into, so hot loops allocate nothing. */
import { ShadingParams } from './shading.ts';

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

/**
 * The directions (local frame) and random numbers a BSDF call reads. Passing
 * them in a record rather than as arguments keeps the doubles unboxed when
 * the call is not inlined, so the tracer allocates nothing per bounce.
 */
export class BsdfQuery {
  wox = 0;
  woy = 0;
  woz = 1;
  wix = 0;
  wiy = 0;
  wiz = 1;
  /** Random numbers for `sample`: u0, u1 pick the direction, u2 the lobe. */
  u0 = 0;
  u1 = 0;
  u2 = 0;
  /**
   * Per-hit parameters of a glTF material (textures already looked up);
   * the integrator fills it at each hit on one, the other kinds ignore it.
   */
  readonly shading = new ShadingParams();
}

/**
 * Result of `eval`: the BSDF value f(wo, wi) per channel (without the
 * cosine), and the density with which `sample` would return wi — MIS needs
 * both at the same point, and they share most of their arithmetic.
 */
export class BsdfValue {
  r = 0;
  g = 0;
  b = 0;
  pdf = 0;
}
