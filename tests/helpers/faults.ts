/**
 * Helpers of the worker-fault tests (tests/unit/pool-faults, shared-claims,
 * tests/cli/worker-faults): how far a disturbed film is from the undisturbed
 * one, and the seeded PRNG that places the faults (the CLI's own test hook
 * uses the same one).
 */
import type { Film } from '../../src/core/index.ts';

export { mulberry32 } from '../../src/cli/test-faults.ts';

/** Number of 32-bit words of two films' buffers that differ. */
export function differingWords(a: Film, b: Film): number {
  const x = new Uint32Array(a.buffer as ArrayBuffer);
  const y = new Uint32Array(b.buffer as ArrayBuffer);
  // Films of different layouts (one with aux planes) differ everywhere.
  if (x.length !== y.length) return Math.max(x.length, y.length);
  let n = 0;
  for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) n++;
  return n;
}
