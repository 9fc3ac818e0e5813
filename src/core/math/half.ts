/**
 * IEEE 754-2008 binary16 (§3.6), the half floats of OIDN's weight files and of three.js's
 * HalfFloatType textures (HDRLoader's default).
 */

/** binary16 → number: subnormals, infinities and NaN included. */
export function halfToFloat(h: number): number {
  const sign = h & 0x8000 ? -1 : 1;
  const exp = (h >> 10) & 0x1f;
  const frac = h & 0x3ff;
  if (exp === 0) return sign * frac * 2 ** -24;
  if (exp === 31) return frac === 0 ? sign * Infinity : NaN;
  return sign * (1 + frac / 1024) * 2 ** (exp - 15);
}
