/**
 * The layer fields of ShadingParams from a material record, for fillGltfShading
 * (shading-fill.ts), every field at every hit (the record is reused across materials):
 *
 * - KHR_materials_clearcoat: clearcoat = factor × clearcoatTexture.r; clearcoatRoughness
 *   = factor × clearcoatRoughnessTexture.g, α = roughness² (as the base's, with the
 *   same MIN_ALPHA floor); the coat normal from clearcoatNormalTexture exactly as the
 *   normal map (scale on x and y), in tangent space — gltf-surface.ts takes it to world
 *   space through the same TBN frame as the normal map, and the integrator into the
 *   BSDF's local frame. Without a texture the coat keeps the unmapped surface normal
 *   (README: "If clearcoatNormalTexture is not given, no normal mapping is applied to
 *   the clear coat layer").
 * - KHR_materials_sheen: colour = factor × sheenColorTexture.rgb (sRGB, decoded),
 *   roughness = factor × sheenRoughnessTexture.a.
 * - KHR_materials_unlit: the base colour (factor × texture × COLOR_0) becomes the
 *   emission, and the flag zeroes the BSDF (gltf-layers.ts).
 * - KHR_materials_pbrSpecularGlossiness (converted in gltf/materials-layers.ts):
 *   specularColor ×= specularGlossinessTexture.rgb, roughness = 1 − glossiness ×
 *   texture.a, where the record's roughness holds 1 − glossinessFactor.
 */
import { MIN_ALPHA } from '../bsdf/materials.ts';
import type { ShadingParams } from '../bsdf/shading.ts';
import type { Texel } from '../texture/bilinear.ts';
import type { TextureStore } from '../texture/texture-store.ts';
import {
  GM_CLEARCOAT,
  GM_CLEARCOAT_NORMAL_SCALE,
  GM_CLEARCOAT_ROUGHNESS,
  GM_ROUGHNESS,
  GM_SHEEN_COLOR,
  GM_SHEEN_ROUGHNESS,
  GM_UNLIT,
  TEX_CLEARCOAT,
  TEX_CLEARCOAT_NORMAL,
  TEX_CLEARCOAT_ROUGHNESS,
  TEX_SHEEN_COLOR,
  TEX_SHEEN_ROUGHNESS,
  TEX_SPEC_GLOSS,
} from './material-table.ts';
import type { HitAttributes } from './shading-fill.ts';

/** shading-fill.ts's texture lookup into its texel T (passed in: no import cycle). */
export type Lookup = (
  table: Float64Array,
  o: number,
  slot: number,
  textures: TextureStore,
  hit: HitAttributes,
) => boolean;

function clamp01(x: number): number {
  return x < 0 ? 0 : x > 1 ? 1 : x;
}

function alphaOf(roughness: number): number {
  return roughness === 0 ? 0 : Math.max(MIN_ALPHA, roughness * roughness);
}

/** Fills the clearcoat, sheen, unlit and specular–glossiness fields of sp (record at o). */
export function fillLayers(
  table: Float64Array,
  textures: TextureStore,
  o: number,
  hit: HitAttributes,
  sp: ShadingParams,
  lookup: Lookup,
  T: Texel,
): void {
  let c = table[o + GM_CLEARCOAT];
  if (c > 0 && lookup(table, o, TEX_CLEARCOAT, textures, hit)) c *= T.r;
  sp.clearcoat = clamp01(c);
  sp.clearcoatAlpha = 0;
  sp.ccnx = 0;
  sp.ccny = 0;
  sp.ccnz = 1;
  if (sp.clearcoat > 0) {
    let r = table[o + GM_CLEARCOAT_ROUGHNESS];
    if (lookup(table, o, TEX_CLEARCOAT_ROUGHNESS, textures, hit)) r *= T.g;
    sp.clearcoatAlpha = alphaOf(clamp01(r));
    if (lookup(table, o, TEX_CLEARCOAT_NORMAL, textures, hit)) {
      const scale = table[o + GM_CLEARCOAT_NORMAL_SCALE];
      const nx = (2 * T.r - 1) * scale;
      const ny = (2 * T.g - 1) * scale;
      const nz = 2 * T.b - 1;
      const l = Math.sqrt(nx * nx + ny * ny + nz * nz);
      // As for the normal map: a texel with no direction, or one below, is "unperturbed".
      if (l > 0 && nz > 0) {
        sp.ccnx = nx / l;
        sp.ccny = ny / l;
        sp.ccnz = nz / l;
      }
    }
  }

  let sr = table[o + GM_SHEEN_COLOR];
  let sg = table[o + GM_SHEEN_COLOR + 1];
  let sb = table[o + GM_SHEEN_COLOR + 2];
  let sheenRoughness = table[o + GM_SHEEN_ROUGHNESS];
  if (sr > 0 || sg > 0 || sb > 0) {
    if (lookup(table, o, TEX_SHEEN_COLOR, textures, hit)) {
      sr *= T.r;
      sg *= T.g;
      sb *= T.b;
    }
    if (lookup(table, o, TEX_SHEEN_ROUGHNESS, textures, hit)) sheenRoughness *= T.a;
  }
  sp.sheenR = clamp01(sr);
  sp.sheenG = clamp01(sg);
  sp.sheenB = clamp01(sb);
  sp.sheenRoughness = clamp01(sheenRoughness);

  sp.unlit = table[o + GM_UNLIT] !== 0;
  if (sp.unlit) {
    sp.emR = sp.baseR;
    sp.emG = sp.baseG;
    sp.emB = sp.baseB;
  }

  if (lookup(table, o, TEX_SPEC_GLOSS, textures, hit)) {
    sp.specR *= T.r;
    sp.specG *= T.g;
    sp.specB *= T.b;
    sp.alpha = alphaOf(clamp01(1 - (1 - table[o + GM_ROUGHNESS]) * T.a));
  }
}
