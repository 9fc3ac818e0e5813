/**
 * Thin-film interference Fresnel of KHR_materials_iridescence: L. Belcour and
 * P. Barla, "A Practical Extension to Microfacet Theory for the Modeling of
 * Varying Iridescence", ACM TOG 36(4), 2017, in the form the extension's
 * README ("Iridescence Fresnel", "Analytic Spectral Integration") and the glTF
 * Sample Viewer give it: an Airy sum over the film's inter-reflections, two
 * orders of the oscillating terms, integrated against the CIE XYZ
 * sensitivities in Fourier space and converted to linear Rec. 709 (our RGB).
 *
 * The film → base interface uses Schlick's Fresnel, as the README does, with
 * the base's index derived from its F0 per channel (Fresnel0ToIor) — except
 * over glass (the transmission lobe, whose plain reflectance is the exact
 * Fresnel), where it is the exact Fresnel of the base's index. The
 * film's index is blended towards the outside medium's (1) as the thickness
 * goes to 0 (the README's smoothstep over 0.03 nm), so a vanishing film
 * leaves the plain Schlick Fresnel of the base.
 *
 * Three deliberate departures from the Sample Viewer, all so that "no film"
 * is exactly the plain Fresnel and energy is conserved:
 * - the air → film interface uses the exact dielectric Fresnel (the one
 *   Belcour–Barla use) rather than Schlick's: Schlick with F0 = 0 still
 *   reflects (1 − cosθ)⁵, so an index-matched film would add a grazing
 *   reflection of up to 100 % that no interface has;
 * - R12·R23 is clamped below only at 0 (the viewer's 1e-5 floor leaves a
 *   0.3 % ripple where the film vanishes);
 * - the result is clamped to [0, 1] per channel (the viewer clamps only
 *   negative, out-of-gamut values), so that 1 − F, the light the layer lets
 *   through to the diffuse base, is never negative.
 *   The clamp acts: over a grid of cosθ (0–1) × thickness (0–1200 nm) × film
 *   index (1.2–2.5) × F0 (0.02–0.99) the two-order sum exceeds 1 at 1.4 % of
 *   the points (up to 1.27, bright bases near grazing incidence) and is
 *   negative (out of the Rec. 709 gamut) at others, down to −0.19.
 *
 * Allocation-free: inputs and outputs live in a caller-owned ThinFilm record.
 */

/** One evaluation: set the inputs, call `thinFilmFresnel`, read r, g, b. */
export class ThinFilm {
  /** Index of refraction of the film (iridescenceIor). */
  eta = 1.3;
  /** Film thickness in nanometres. */
  thickness = 400;
  /**
   * Index of a dielectric base (glass) whose film → base reflectance is the
   * exact Fresnel; 0 to describe the base by its F0 below instead (Schlick,
   * the README's Fresnel0ToIor for metals and the specular layer).
   */
  baseIor = 0;
  /** F0 of the base under the film, per channel, in [0, 1] (when baseIor is 0). */
  f0r = 0.04;
  f0g = 0.04;
  f0b = 0.04;
  /** Cosine of the angle of incidence on the film (v·h), in [0, 1]. */
  cos = 1;
  /** The reflectance, per channel, in [0, 1]. */
  r = 0;
  g = 0;
  b = 0;
}
import { fresnelDielectric } from './fresnel.ts';

function schlick(f0: number, c: number): number {
  const m = 1 - c;
  const m2 = m * m;
  return f0 + (1 - f0) * m2 * m2 * m;
}

/** Index of the base seen from air, from its F0 (≤ 0.9999 so that it stays finite). */
function iorOfF0(f0: number): number {
  const s = Math.sqrt(Math.min(Math.max(f0, 0), 0.9999));
  return (1 + s) / (1 - s);
}

function f0Of(nt: number, ni: number): number {
  const k = (nt - ni) / (nt + ni);
  return k * k;
}

const TWO_PI = 2 * Math.PI;
// The Gaussian fits of the XYZ sensitivities in Fourier space (Belcour–Barla
// 2017, supplemental; the README's evalSensitivity): amplitude, centre, variance.
const VX = 5.4856e-13 * Math.sqrt(TWO_PI * 4.3278e9);
const VY = 4.4201e-13 * Math.sqrt(TWO_PI * 9.3046e9);
const VZ = 5.2481e-13 * Math.sqrt(TWO_PI * 6.6121e9);
const VX2 = 9.747e-14 * Math.sqrt(TWO_PI * 4.5282e9);
const NORM = 1 / 1.0685e-7;

/** One Airy term's spectral integral, in RGB, added ×2·cm into ACC. */
const ACC = { r: 0, g: 0, b: 0 };

function addSensitivity(
  opd: number,
  sr: number,
  sg: number,
  sb: number,
  cr: number,
  cg: number,
  cb: number,
): void {
  // The phase shift is per channel (base index per channel), the XYZ fits per
  // component: the README applies channel k's shift to component k.
  const phase = TWO_PI * opd * 1e-9;
  const p2 = phase * phase;
  let x = VX * Math.cos(1.681e6 * phase + sr) * Math.exp(-p2 * 4.3278e9);
  const y = VY * Math.cos(1.7953e6 * phase + sg) * Math.exp(-p2 * 9.3046e9);
  const z = VZ * Math.cos(2.2084e6 * phase + sb) * Math.exp(-p2 * 6.6121e9);
  x += VX2 * Math.cos(2.2399e6 * phase + sr) * Math.exp(-p2 * 4.5282e9);
  const X = x * NORM,
    Y = y * NORM,
    Z = z * NORM;
  // XYZ → linear Rec. 709.
  ACC.r += 2 * cr * (3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z);
  ACC.g += 2 * cg * (-0.969266 * X + 1.8760108 * Y + 0.041556 * Z);
  ACC.b += 2 * cb * (0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z);
}

/** Reflectance of the film over the base for incidence cosine t.cos, into t.r, t.g, t.b. */
export function thinFilmFresnel(t: ThinFilm): void {
  const cos1 = Math.min(Math.max(t.cos, 0), 1);
  const d = t.thickness;
  // smoothstep(0, 0.03, d): the film's index fades to the outside's as d → 0.
  const s = Math.min(Math.max(d / 0.03, 0), 1);
  const eta2 = 1 + (t.eta - 1) * s * s * (3 - 2 * s);
  const sin2Sq = (1 - cos1 * cos1) / (eta2 * eta2);
  const cos2Sq = 1 - sin2Sq;
  if (cos2Sq < 0) {
    // Total internal reflection at the film's top (a film of index below the outside's).
    t.r = 1;
    t.g = 1;
    t.b = 1;
    return;
  }
  const cos2 = Math.sqrt(cos2Sq);
  // Air → film.
  const r12 = fresnelDielectric(cos1, eta2);
  const t121 = 1 - r12;
  const phi21 = eta2 < 1 ? 0 : Math.PI;
  // Film → base, per channel.
  const glass = t.baseIor > 0;
  const nr = glass ? t.baseIor : iorOfF0(t.f0r),
    ng = glass ? t.baseIor : iorOfF0(t.f0g),
    nb = glass ? t.baseIor : iorOfF0(t.f0b);
  const r23r = glass ? fresnelDielectric(cos2, nr / eta2) : schlick(f0Of(nr, eta2), cos2);
  const r23g = glass ? r23r : schlick(f0Of(ng, eta2), cos2);
  const r23b = glass ? r23r : schlick(f0Of(nb, eta2), cos2);
  const phr = phi21 + (nr < eta2 ? Math.PI : 0);
  const phg = phi21 + (ng < eta2 ? Math.PI : 0);
  const phb = phi21 + (nb < eta2 ? Math.PI : 0);
  const opd = 2 * eta2 * d * cos2;
  const rr = Math.min(Math.max(r12 * r23r, 0), 0.9999);
  const rg = Math.min(Math.max(r12 * r23g, 0), 0.9999);
  const rb = Math.min(Math.max(r12 * r23b, 0), 0.9999);
  const tt = t121 * t121;
  const rsr = (tt * r23r) / (1 - rr);
  const rsg = (tt * r23g) / (1 - rg);
  const rsb = (tt * r23b) / (1 - rb);
  // m = 0: the incoherent (DC) part.
  ACC.r = r12 + rsr;
  ACC.g = r12 + rsg;
  ACC.b = r12 + rsb;
  // m = 1, 2: the interference terms, amplitude (Rs − T121)·r123^m.
  const sr = Math.sqrt(rr),
    sg = Math.sqrt(rg),
    sb = Math.sqrt(rb);
  let cr = (rsr - t121) * sr,
    cg = (rsg - t121) * sg,
    cb = (rsb - t121) * sb;
  addSensitivity(opd, phr, phg, phb, cr, cg, cb);
  cr *= sr;
  cg *= sg;
  cb *= sb;
  addSensitivity(2 * opd, 2 * phr, 2 * phg, 2 * phb, cr, cg, cb);
  t.r = Math.min(Math.max(ACC.r, 0), 1);
  t.g = Math.min(Math.max(ACC.g, 0), 1);
  t.b = Math.min(Math.max(ACC.b, 0), 1);
}
