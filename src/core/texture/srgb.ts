/**
 * sRGB → linear conversion (IEC 61966-2-1), done once when a texture is
 * decoded, never per lookup. Texels are stored as 16-bit linear values:
 * the darkest non-zero 8-bit sRGB step (1/255/12.92 ≈ 3.0e-4) is twenty times
 * the 16-bit quantum (1.5e-5), so nothing an 8-bit image holds is lost.
 */

/** Linear value of an sRGB-encoded value in [0, 1]. */
export function srgbToLinear(v: number): number {
  return v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4);
}

/** Largest stored texel value: 1.0. */
export const TEXEL_MAX = 65535;

let lut8: Uint16Array | null = null;

/** 8-bit sRGB code → 16-bit linear code (a table of 256). */
export function srgb8ToLinear16Table(): Uint16Array {
  if (lut8 === null) {
    lut8 = new Uint16Array(256);
    for (let i = 0; i < 256; i++) lut8[i] = Math.round(srgbToLinear(i / 255) * TEXEL_MAX);
  }
  return lut8;
}

/** 16-bit sRGB code → 16-bit linear code. */
export function srgb16ToLinear16(code: number): number {
  return Math.round(srgbToLinear(code / 65535) * TEXEL_MAX);
}
