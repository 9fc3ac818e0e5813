/**
 * The layer extensions of a glTF material into its record of the material table
 * (material-table.ts), for materials.ts:
 * - KHR_materials_clearcoat: factor, roughness factor, normal scale and their textures;
 * - KHR_materials_sheen: colour factor, roughness factor and their textures;
 * - KHR_materials_unlit: the GM_UNLIT flag (shading-fill.ts turns the base colour into
 *   the surface's emission, gltf-layers.ts zeroes the BSDF);
 * - KHR_materials_pbrSpecularGlossiness (archived), converted to metallic–roughness with
 *   KHR_materials_specular as glTF-Transform's `metalRough()` does, without rewriting
 *   the textures: baseColor ← diffuse (factor × diffuseTexture), metallic ← 0,
 *   specular ← 1, specularColor ← specularFactor × texture.rgb, roughness ←
 *   1 − glossinessFactor × texture.a, and an infinite ior (0, stored as 1e6 like
 *   KHR_materials_ior's 0), so that F0 is the specular colour itself — glTF-Transform
 *   writes ior 1000, F0 = 0.996 × specular. The specularGlossinessTexture has its own
 *   slot (TEX_SPEC_GLOSS) read by shading-fill.ts.
 */
import type { Material, Texture, TextureInfo } from '@gltf-transform/core';
import type { Clearcoat, PBRSpecularGlossiness, Sheen } from '@gltf-transform/extensions';
import {
  GM_BASE,
  GM_CLEARCOAT,
  GM_CLEARCOAT_NORMAL_SCALE,
  GM_CLEARCOAT_ROUGHNESS,
  GM_IOR,
  GM_METALLIC,
  GM_ROUGHNESS,
  GM_SHEEN_COLOR,
  GM_SHEEN_ROUGHNESS,
  GM_SPECULAR,
  GM_SPECULAR_COLOR,
  GM_UNLIT,
  TEX_BASE_COLOR,
  TEX_CLEARCOAT,
  TEX_CLEARCOAT_NORMAL,
  TEX_CLEARCOAT_ROUGHNESS,
  TEX_SHEEN_COLOR,
  TEX_SHEEN_ROUGHNESS,
  TEX_SPEC_GLOSS,
} from '../gltf-material/material-table.ts';

/** Binds a texture to a slot of the material being compiled (materials.ts's `bind`). */
export type BindSlot = (slot: number, texture: Texture | null, info: TextureInfo | null) => void;

/** Writes the layer extensions of `mat` into the record at table offset `o`. */
export function compileLayers(mat: Material, table: Float64Array, o: number, bind: BindSlot): void {
  const cc = mat.getExtension<Clearcoat>('KHR_materials_clearcoat');
  if (cc !== null) {
    table[o + GM_CLEARCOAT] = cc.getClearcoatFactor();
    table[o + GM_CLEARCOAT_ROUGHNESS] = cc.getClearcoatRoughnessFactor();
    table[o + GM_CLEARCOAT_NORMAL_SCALE] = cc.getClearcoatNormalScale();
    bind(TEX_CLEARCOAT, cc.getClearcoatTexture(), cc.getClearcoatTextureInfo());
    bind(
      TEX_CLEARCOAT_ROUGHNESS,
      cc.getClearcoatRoughnessTexture(),
      cc.getClearcoatRoughnessTextureInfo(),
    );
    bind(TEX_CLEARCOAT_NORMAL, cc.getClearcoatNormalTexture(), cc.getClearcoatNormalTextureInfo());
  }
  const sh = mat.getExtension<Sheen>('KHR_materials_sheen');
  if (sh !== null) {
    table.set(sh.getSheenColorFactor(), o + GM_SHEEN_COLOR);
    table[o + GM_SHEEN_ROUGHNESS] = sh.getSheenRoughnessFactor();
    bind(TEX_SHEEN_COLOR, sh.getSheenColorTexture(), sh.getSheenColorTextureInfo());
    bind(TEX_SHEEN_ROUGHNESS, sh.getSheenRoughnessTexture(), sh.getSheenRoughnessTextureInfo());
  }
  if (mat.getExtension('KHR_materials_unlit') !== null) table[o + GM_UNLIT] = 1;
  const sg = mat.getExtension<PBRSpecularGlossiness>('KHR_materials_pbrSpecularGlossiness');
  if (sg !== null) {
    table.set(sg.getDiffuseFactor(), o + GM_BASE);
    table[o + GM_METALLIC] = 0;
    table[o + GM_ROUGHNESS] = 1 - sg.getGlossinessFactor();
    table[o + GM_SPECULAR] = 1;
    table.set(sg.getSpecularFactor(), o + GM_SPECULAR_COLOR);
    table[o + GM_IOR] = 1e6;
    bind(TEX_BASE_COLOR, sg.getDiffuseTexture(), sg.getDiffuseTextureInfo());
    bind(TEX_SPEC_GLOSS, sg.getSpecularGlossinessTexture(), sg.getSpecularGlossinessTextureInfo());
  }
}
