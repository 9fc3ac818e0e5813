/**
 * KHR_materials_iridescence in the glTF BSDF (gltf-pbr.ts): the Fresnel of the
 * dielectric specular layer and of the metal become
 *
 *   F = mix(F_schlick, F_film, iridescence)
 *
 * (the extension's README, "Iridescence Fresnel": fresnel_mix and
 * conductor_fresnel take the thin-film Fresnel, weighted by
 * iridescenceFactor × texture.r), with F_film the Belcour–Barla reflectance
 * of thin-film.ts over a base of the same F0: the dielectric's
 * min(((ior−1)/(ior+1))² · specularColor, 1) scaled by `specular` (as f90 is,
 * KHR_materials_specular), the metal's baseColor. The outside medium is air
 * (index 1), as in the README.
 *
 * The diffuse base under the layer is weighted by (1 − F(n·wo))(1 − F(n·wi))
 * with the same mixed F, which keeps the BSDF reciprocal (the Sample Viewer
 * weights it by max3 of the film's F at the view only). Only called when
 * iridescence > 0, so other materials run the plain code. Allocation-free.
 */
import type { ShadingParams } from './shading.ts';
import { ThinFilm, thinFilmFresnel } from './thin-film.ts';

const TF = new ThinFilm();

/** A mixed Fresnel per channel, written by the functions below. */
export interface Rgb {
  r: number;
  g: number;
  b: number;
}

/**
 * Mixed Fresnel of the dielectric layer at incidence cosine c, where the
 * caller's plain Schlick values are (fr, fg, fb) (in `out` on entry).
 */
export function iridescentDielectric(sp: ShadingParams, c: number, out: Rgb): void {
  const k = (sp.ior - 1) / (sp.ior + 1);
  const k2 = k * k;
  TF.eta = sp.iridescenceIor;
  TF.thickness = sp.iridescenceThickness;
  TF.f0r = Math.min(k2 * sp.specR, 1);
  TF.f0g = Math.min(k2 * sp.specG, 1);
  TF.f0b = Math.min(k2 * sp.specB, 1);
  TF.cos = c;
  thinFilmFresnel(TF);
  const i = sp.iridescence;
  const s = sp.specular;
  out.r += i * (s * TF.r - out.r);
  out.g += i * (s * TF.g - out.g);
  out.b += i * (s * TF.b - out.b);
}

/** Mixed Fresnel of the metal (F0 = base colour) at c; `out` holds the plain Schlick values on entry. */
export function iridescentMetal(sp: ShadingParams, c: number, out: Rgb): void {
  TF.eta = sp.iridescenceIor;
  TF.thickness = sp.iridescenceThickness;
  TF.f0r = sp.baseR;
  TF.f0g = sp.baseG;
  TF.f0b = sp.baseB;
  TF.cos = c;
  thinFilmFresnel(TF);
  const i = sp.iridescence;
  out.r += i * (TF.r - out.r);
  out.g += i * (TF.g - out.g);
  out.b += i * (TF.b - out.b);
}

/**
 * Mixed reflectance of the glass lobe at c, for a path arriving from outside
 * (the film is on the outer surface, seen from air): `out` holds the exact
 * Fresnel on entry; the film's base is the glass of index ior (exact Fresnel, so
 * that a vanishing film leaves exactly the glass's own reflectance).
 * Returns the mean over the channels, the probability of reflecting: the
 * refraction then carries (1 − F) per channel over (1 − mean).
 */
export function iridescentGlass(sp: ShadingParams, c: number, out: Rgb): number {
  TF.eta = sp.iridescenceIor;
  TF.thickness = sp.iridescenceThickness;
  TF.baseIor = sp.ior;
  TF.cos = c;
  thinFilmFresnel(TF);
  TF.baseIor = 0;
  const i = sp.iridescence;
  out.r += i * (TF.r - out.r);
  out.g += i * (TF.g - out.g);
  out.b += i * (TF.b - out.b);
  return (out.r + out.g + out.b) / 3;
}
