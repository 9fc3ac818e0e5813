/**
 * The display transform, identical to shaders/display.frag.glsl so the
 * Canvas 2D fallback and PNG export show the same picture as WebGL2:
 * exposure (a linear gain), ACES filmic (Narkowicz's fit, "ACES Filmic Tone
 * Mapping Curve", 2015) and the sRGB transfer function (IEC 61966-2-1).
 */

/** Narkowicz's rational fit of the ACES RRT+ODT, input pre-scaled by 0.6 as in his post. */
export function acesFilmic(x: number): number {
  const v = x * 0.6;
  const y = (v * (2.51 * v + 0.03)) / (v * (2.43 * v + 0.59) + 0.14);
  return y < 0 ? 0 : y > 1 ? 1 : y;
}

/** Linear [0, 1] to the sRGB-encoded [0, 1]. */
export function srgbEncode(c: number): number {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
}

/** One channel: linear radiance to an 8-bit display value. */
export function toDisplayByte(linear: number, exposure: number): number {
  const v = srgbEncode(acesFilmic(linear * exposure));
  return Math.round(v * 255);
}

/**
 * Tone maps accumulated sums (RGBA, A = sample count) to RGBA8 pixels.
 * Pixels with no sample yet are black. `out` must hold width·height·4 bytes.
 */
export function tonemapSums(
  sums: Float32Array,
  exposure: number,
  out: Uint8ClampedArray | Uint8Array,
): void {
  for (let i = 0, n = sums.length; i < n; i += 4) {
    const count = sums[i + 3];
    const inv = count > 0 ? 1 / count : 0;
    out[i] = toDisplayByte(sums[i] * inv, exposure);
    out[i + 1] = toDisplayByte(sums[i + 1] * inv, exposure);
    out[i + 2] = toDisplayByte(sums[i + 2] * inv, exposure);
    out[i + 3] = 255;
  }
}
