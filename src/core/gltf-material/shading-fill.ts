/**
 * Fills the per-hit ShadingParams of a glTF material from its record in the
 * material table and, where it has textures, from bilinear lookups at the
 * hit's texture coordinates (pbr-book 4e §10.5: textures are evaluated once
 * per hit, before the BSDF is used). Allocation-free.
 *
 * glTF semantics (glTF 2.0 §3.9, and each extension's text):
 * baseColor = factor × texture (sRGB, decoded to linear at load) × COLOR_0;
 * roughness = factor × texture.g, metallic = factor × texture.b;
 * emissive = factor × texture × strength; transmission = factor × texture.r;
 * specular = factor × texture.a, specularColor = factor × texture.rgb;
 * normal = normalize((2·texture.rgb − 1) × (scale, scale, 1)) in tangent space;
 * opacity = baseColor.a for BLEND, (a ≥ cutoff) for MASK, 1 for OPAQUE.
 */
import { MIN_ALPHA } from '../bsdf/materials.ts';
import type { ShadingParams } from '../bsdf/shading.ts';
import { Texel, textureBilinear } from '../texture/bilinear.ts';
import { fillLayers } from './layers-fill.ts';
import type { TextureStore } from '../texture/texture-store.ts';
import {
  ALPHA_BLEND,
  ALPHA_MASK,
  BINDING_STRIDE,
  B_IMAGE,
  B_TEXCOORD,
  B_TRANSFORM,
  B_WRAP_S,
  B_WRAP_T,
  GM_ALPHA_CUTOFF,
  GM_ALPHA_MODE,
  GM_ANISOTROPY_ROTATION,
  GM_ANISOTROPY_STRENGTH,
  GM_ATTENUATION_COLOR,
  GM_ATTENUATION_DISTANCE,
  GM_BASE,
  GM_DIFFUSE_TRANSMISSION,
  GM_DIFFUSE_TRANSMISSION_COLOR,
  GM_DISPERSION,
  GM_EMISSIVE,
  GM_IOR,
  GM_IRIDESCENCE,
  GM_IRIDESCENCE_IOR,
  GM_IRIDESCENCE_THICKNESS_MAX,
  GM_IRIDESCENCE_THICKNESS_MIN,
  GM_METALLIC,
  GM_NORMAL_SCALE,
  GM_ROUGHNESS,
  GM_SPECULAR,
  GM_SPECULAR_COLOR,
  GM_STRIDE,
  GM_TEXTURES,
  GM_THICKNESS,
  GM_TRANSMISSION,
  TEX_ANISOTROPY,
  TEX_BASE_COLOR,
  TEX_DIFFUSE_TRANSMISSION,
  TEX_DIFFUSE_TRANSMISSION_COLOR,
  TEX_EMISSIVE,
  TEX_IRIDESCENCE,
  TEX_IRIDESCENCE_THICKNESS,
  TEX_METALLIC_ROUGHNESS,
  TEX_NORMAL,
  TEX_SPECULAR,
  TEX_SPECULAR_COLOR,
  TEX_TRANSMISSION,
} from './material-table.ts';

/** What the integrator interpolates at a hit for `fillGltfShading`. */
export class HitAttributes {
  /** TEXCOORD_0 and TEXCOORD_1. */
  u0 = 0;
  v0 = 0;
  u1 = 0;
  v1 = 0;
  /** COLOR_0 (linear RGBA), white without one. */
  r = 1;
  g = 1;
  b = 1;
  a = 1;
}

const T = new Texel();

/** Looks up binding `slot` of the record at `o` into T; false when it has no texture. */
function lookup(
  table: Float64Array,
  o: number,
  slot: number,
  textures: TextureStore,
  hit: HitAttributes,
): boolean {
  const b = o + GM_TEXTURES + slot * BINDING_STRIDE;
  const image = table[b + B_IMAGE];
  if (image < 0) return false;
  const set = table[b + B_TEXCOORD];
  const u = set === 0 ? hit.u0 : hit.u1;
  const v = set === 0 ? hit.v0 : hit.v1;
  const tu =
    table[b + B_TRANSFORM] * u + table[b + B_TRANSFORM + 1] * v + table[b + B_TRANSFORM + 2];
  const tv =
    table[b + B_TRANSFORM + 3] * u + table[b + B_TRANSFORM + 4] * v + table[b + B_TRANSFORM + 5];
  textureBilinear(textures, image, tu, tv, table[b + B_WRAP_S], table[b + B_WRAP_T], T);
  return true;
}

/**
 * Absorption coefficient of one channel (KHR_materials_volume): the colour a
 * white ray has after `distance`, so exp(−σ·distance) = c. A black channel
 * absorbs everything: a huge finite σ keeps exp(−σ·0) = 1 (∞ · 0 is NaN).
 */
function sigmaA(c: number, distance: number): number {
  if (!(c < 1)) return 0;
  return c > 0 ? Math.min(-Math.log(c) / distance, 1e300) : 1e300;
}

function clamp01(x: number): number {
  return x < 0 ? 0 : x > 1 ? 1 : x;
}

/** Coverage of material m at a hit (glTF alpha modes): 1 opaque, 0 cut away, else BLEND's alpha. */
export function gltfOpacity(
  table: Float64Array,
  textures: TextureStore,
  m: number,
  hit: HitAttributes,
): number {
  const o = m * GM_STRIDE;
  const mode = table[o + GM_ALPHA_MODE];
  if (mode !== ALPHA_BLEND && mode !== ALPHA_MASK) return 1;
  let a = table[o + GM_BASE + 3] * hit.a;
  if (lookup(table, o, TEX_BASE_COLOR, textures, hit)) a *= T.a;
  if (mode === ALPHA_MASK) return a >= table[o + GM_ALPHA_CUTOFF] ? 1 : 0;
  return clamp01(a);
}

/**
 * What a light sample on material m sees at a hit: the emitted radiance
 * (factor × texture × strength) times the coverage — a surface that is only
 * partly there emits in proportion (stochastic opacity's expected value).
 */
export function gltfEmission(
  table: Float64Array,
  textures: TextureStore,
  m: number,
  hit: HitAttributes,
  out: { r: number; g: number; b: number },
): void {
  const o = m * GM_STRIDE;
  let er = table[o + GM_EMISSIVE];
  let eg = table[o + GM_EMISSIVE + 1];
  let eb = table[o + GM_EMISSIVE + 2];
  if ((er > 0 || eg > 0 || eb > 0) && lookup(table, o, TEX_EMISSIVE, textures, hit)) {
    er *= T.r;
    eg *= T.g;
    eb *= T.b;
  }
  const opacity = gltfOpacity(table, textures, m, hit);
  out.r = er * opacity;
  out.g = eg * opacity;
  out.b = eb * opacity;
}

export function fillGltfShading(
  table: Float64Array,
  textures: TextureStore,
  m: number,
  hit: HitAttributes,
  sp: ShadingParams,
): void {
  const o = m * GM_STRIDE;
  let r = table[o + GM_BASE] * hit.r;
  let g = table[o + GM_BASE + 1] * hit.g;
  let b = table[o + GM_BASE + 2] * hit.b;
  let a = table[o + GM_BASE + 3] * hit.a;
  if (lookup(table, o, TEX_BASE_COLOR, textures, hit)) {
    r *= T.r;
    g *= T.g;
    b *= T.b;
    a *= T.a;
  }
  sp.baseR = clamp01(r);
  sp.baseG = clamp01(g);
  sp.baseB = clamp01(b);
  const mode = table[o + GM_ALPHA_MODE];
  sp.opacity =
    mode === ALPHA_BLEND
      ? clamp01(a)
      : mode === ALPHA_MASK
        ? a >= table[o + GM_ALPHA_CUTOFF]
          ? 1
          : 0
        : 1;

  let metallic = table[o + GM_METALLIC];
  let roughness = table[o + GM_ROUGHNESS];
  if (lookup(table, o, TEX_METALLIC_ROUGHNESS, textures, hit)) {
    roughness *= T.g;
    metallic *= T.b;
  }
  sp.metallic = clamp01(metallic);
  roughness = clamp01(roughness);
  sp.alpha = roughness === 0 ? 0 : Math.max(MIN_ALPHA, roughness * roughness);

  let er = table[o + GM_EMISSIVE];
  let eg = table[o + GM_EMISSIVE + 1];
  let eb = table[o + GM_EMISSIVE + 2];
  if ((er > 0 || eg > 0 || eb > 0) && lookup(table, o, TEX_EMISSIVE, textures, hit)) {
    er *= T.r;
    eg *= T.g;
    eb *= T.b;
  }
  sp.emR = er;
  sp.emG = eg;
  sp.emB = eb;

  sp.ior = table[o + GM_IOR];
  let transmission = table[o + GM_TRANSMISSION];
  if (transmission > 0 && lookup(table, o, TEX_TRANSMISSION, textures, hit)) transmission *= T.r;
  sp.transmission = clamp01(transmission);

  let specular = table[o + GM_SPECULAR];
  if (lookup(table, o, TEX_SPECULAR, textures, hit)) specular *= T.a;
  sp.specular = clamp01(specular);
  let sr = table[o + GM_SPECULAR_COLOR];
  let sg = table[o + GM_SPECULAR_COLOR + 1];
  let sb = table[o + GM_SPECULAR_COLOR + 2];
  if (lookup(table, o, TEX_SPECULAR_COLOR, textures, hit)) {
    sr *= T.r;
    sg *= T.g;
    sb *= T.b;
  }
  sp.specR = sr;
  sp.specG = sg;
  sp.specB = sb;
  // Clearcoat, sheen, unlit, specular–glossiness: every field, every hit.
  fillLayers(table, textures, o, hit, sp, lookup, T);

  // KHR_materials_volume: only the factor decides thin wall or solid (materials-volume.ts);
  // σa = −ln(attenuationColor) / attenuationDistance, 0 at the default infinite distance.
  const thickness = table[o + GM_THICKNESS];
  sp.thickness = thickness;
  const distance = table[o + GM_ATTENUATION_DISTANCE];
  if (thickness > 0 && distance < Infinity) {
    sp.sigmaAR = sigmaA(table[o + GM_ATTENUATION_COLOR], distance);
    sp.sigmaAG = sigmaA(table[o + GM_ATTENUATION_COLOR + 1], distance);
    sp.sigmaAB = sigmaA(table[o + GM_ATTENUATION_COLOR + 2], distance);
  } else {
    sp.sigmaAR = 0;
    sp.sigmaAG = 0;
    sp.sigmaAB = 0;
  }
  // KHR_materials_dispersion "only applies to volumetric transmission" (dispersion.ts).
  sp.dispersion = thickness > 0 && table[o + GM_TRANSMISSION] > 0 ? table[o + GM_DISPERSION] : 0;
  let dt = table[o + GM_DIFFUSE_TRANSMISSION];
  let dtr = 1,
    dtg = 1,
    dtb = 1;
  if (dt > 0) {
    if (lookup(table, o, TEX_DIFFUSE_TRANSMISSION, textures, hit)) dt *= T.a;
    dtr = table[o + GM_DIFFUSE_TRANSMISSION_COLOR];
    dtg = table[o + GM_DIFFUSE_TRANSMISSION_COLOR + 1];
    dtb = table[o + GM_DIFFUSE_TRANSMISSION_COLOR + 2];
    if (lookup(table, o, TEX_DIFFUSE_TRANSMISSION_COLOR, textures, hit)) {
      dtr *= T.r;
      dtg *= T.g;
      dtb *= T.b;
    }
  }
  sp.diffuseTransmission = clamp01(dt);
  sp.dtR = clamp01(dtr);
  sp.dtG = clamp01(dtg);
  sp.dtB = clamp01(dtb);

  // KHR_materials_iridescence: factor × texture.r; thickness = mix(min, max,
  // thicknessTexture.g), the maximum without a texture. A film of thickness 0
  // is no film (the Sample Viewer sets the factor to 0 there too).
  let iridescence = table[o + GM_IRIDESCENCE];
  let film = table[o + GM_IRIDESCENCE_THICKNESS_MAX];
  if (iridescence > 0) {
    if (lookup(table, o, TEX_IRIDESCENCE, textures, hit)) iridescence *= T.r;
    if (lookup(table, o, TEX_IRIDESCENCE_THICKNESS, textures, hit)) {
      const lo = table[o + GM_IRIDESCENCE_THICKNESS_MIN];
      film = lo + (film - lo) * T.g;
    }
    if (!(film > 0)) iridescence = 0;
  }
  sp.iridescence = clamp01(iridescence);
  sp.iridescenceIor = table[o + GM_IRIDESCENCE_IOR];
  sp.iridescenceThickness = film;

  // KHR_materials_anisotropy: strength × texture.b; direction (cos, sin) in
  // tangent space, the rotation applied to the texture's normalised RG
  // (mapped to [−1, 1]) or, without a texture, to the tangent (1, 0). The
  // integrator turns it into the local shading frame (gltf-surface.ts).
  let anisotropy = table[o + GM_ANISOTROPY_STRENGTH];
  let ac = 1,
    as = 0;
  if (anisotropy > 0) {
    const rotation = table[o + GM_ANISOTROPY_ROTATION];
    ac = Math.cos(rotation);
    as = Math.sin(rotation);
    if (lookup(table, o, TEX_ANISOTROPY, textures, hit)) {
      anisotropy *= T.b;
      const dx = 2 * T.r - 1,
        dy = 2 * T.g - 1;
      const l = Math.sqrt(dx * dx + dy * dy);
      // A texel with no direction keeps the rotated tangent.
      if (l > 0) {
        const c = ac;
        ac = (c * dx - as * dy) / l;
        as = (as * dx + c * dy) / l;
      }
    }
  }
  sp.anisotropy = clamp01(anisotropy);
  sp.anisotropyCos = ac;
  sp.anisotropySin = as;
  // A smooth surface stretched along one direction is rough along it: the
  // anisotropic lobe needs α > 0 across it too (README: the line of a
  // fully anisotropic smooth surface has zero width in the limit).
  if (sp.anisotropy > 0 && sp.alpha === 0) sp.alpha = MIN_ALPHA;

  if (lookup(table, o, TEX_NORMAL, textures, hit)) {
    const scale = table[o + GM_NORMAL_SCALE];
    const nx = (2 * T.r - 1) * scale;
    const ny = (2 * T.g - 1) * scale;
    const nz = 2 * T.b - 1;
    const l = Math.sqrt(nx * nx + ny * ny + nz * nz);
    // A texel that decodes to no direction (or one below the surface) means "unperturbed".
    if (l > 0 && nz > 0) {
      sp.nx = nx / l;
      sp.ny = ny / l;
      sp.nz = nz / l;
      return;
    }
  }
  sp.nx = 0;
  sp.ny = 0;
  sp.nz = 1;
}
