/**
 * Low-discrepancy samples for the leading dimensions (placeholder: see
 * issue "Speed against error"). Not yet implemented: a tracer built with
 * sampler 'sobol' is refused in the PathTracer constructor until it is.
 */
export const SOBOL_DIMENSIONS = 0;
export const SOBOL_IMPLEMENTED = false;

export function sobolSample(
  _seed: number,
  _pixel: number,
  _sample: number,
  _dimension: number,
): number {
  throw new Error('the sobol sampler is not implemented yet');
}
