/**
 * KHR_materials_dispersion in an RGB path tracer. The extension's
 * non-normative section gives the RGB approximation: the three channels see
 * the indices (ior − h, ior, ior + h) with h = (ior − 1) · 0.025 · dispersion,
 * where dispersion = 20 / V_d (V_d the Abbe number).
 *
 * A path that meets a dispersive volume picks one channel c with
 * probability ⅓ and from then on carries only that channel, with throughput
 * × 3·e_c: the expectation over c is the sum of the three single-channel
 * estimates, so the estimator is unbiased for that approximation with no
 * spectral data (issue 25 plan §2.11). Every later dielectric event of a
 * dispersive material on that path uses ior_c; a non-dispersive one has
 * h = 0 and is unchanged. The cost is colour noise where dispersion is.
 */

/** The index channel `c` (0 red, 1 green, 2 blue) sees through a material of index `ior`. */
export function dispersedIor(ior: number, dispersion: number, c: number): number {
  const h = (ior - 1) * 0.025 * dispersion;
  // Red travels faster (a lower index) than blue in normal dispersion.
  return c === 0 ? ior - h : c === 2 ? ior + h : ior;
}

/** The channel a path takes at its first dispersive event, from one uniform number u ∈ [0, 1). */
export function dispersionChannel(u: number): number {
  const v = u * 3;
  return v < 1 ? 0 : v < 2 ? 1 : 2;
}
