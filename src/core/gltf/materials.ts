/**
 * glTF materials (glTF-Transform's Material with its KHR extensions) into
 * the material table of material-table.ts. Textures are only requested
 * here — one request per (image, colour space) — and decoded later by
 * textures.ts, which fills in each binding's image index.
 */
import type { Material, Texture, TextureInfo } from '@gltf-transform/core';
import type {
  Anisotropy,
  EmissiveStrength,
  IOR,
  Iridescence,
  Specular,
  Transform,
  Transmission,
} from '@gltf-transform/extensions';
import { compileLayers } from './materials-layers.ts';
import {
  ALPHA_BLEND,
  ALPHA_MASK,
  ALPHA_OPAQUE,
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
  GM_BASE,
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
  GM_TRANSMISSION,
  SLOT_NAMES,
  TEX_ANISOTROPY,
  TEX_BASE_COLOR,
  TEX_EMISSIVE,
  TEX_IRIDESCENCE,
  TEX_IRIDESCENCE_THICKNESS,
  TEX_METALLIC_ROUGHNESS,
  TEX_NORMAL,
  TEX_SPECULAR,
  TEX_SPECULAR_COLOR,
  TEX_TRANSMISSION,
  isColorSlot,
  writeDefaultMaterial,
} from '../gltf-material/material-table.ts';
import { readVolumeExtensions } from './materials-volume.ts';

/** A texture to decode: which glTF texture, in which colour space, and where its bindings are. */
export interface TextureRequest {
  texture: Texture;
  /** Index of the texture in the document (its `images[i]` for messages). */
  imageIndex: number;
  srgb: boolean;
  /** Offsets in the table of the bindings that use it (their B_IMAGE is filled on decode). */
  bindings: number[];
  /** `materials[2].normalTexture`, for messages. */
  firstUse: string;
}

export interface CompiledGltfMaterials {
  /** GM_STRIDE numbers per material; the last one is the glTF default material. */
  table: Float64Array;
  /** Index of the default material (for primitives without one). */
  defaultMaterial: number;
  requests: TextureRequest[];
}

/** The extensions whose material parameters are read here. */
export const HONOURED_MATERIAL_EXTENSIONS = [
  'KHR_materials_anisotropy',
  'KHR_materials_clearcoat',
  'KHR_materials_diffuse_transmission',
  'KHR_materials_dispersion',
  'KHR_materials_emissive_strength',
  'KHR_materials_ior',
  'KHR_materials_iridescence',
  'KHR_materials_pbrSpecularGlossiness',
  'KHR_materials_sheen',
  'KHR_materials_specular',
  'KHR_materials_transmission',
  'KHR_materials_unlit',
  'KHR_materials_volume',
  'KHR_texture_transform',
];

export function compileGltfMaterials(
  materials: Material[],
  textures: Texture[],
  warn: (message: string) => void = () => {},
): CompiledGltfMaterials {
  const n = materials.length + 1;
  const table = new Float64Array(n * GM_STRIDE);
  const requests = new Map<string, TextureRequest>();
  const bind = (
    m: number,
    slot: number,
    texture: Texture | null,
    info: TextureInfo | null,
  ): void => {
    if (texture === null || info === null) return;
    // Only TEXCOORD_0 and TEXCOORD_1 reach the renderer; a texture on another set is
    // ignored (validate.ts notes it, and refuses a set the primitive lacks).
    const setOf = info.getExtension<Transform>('KHR_texture_transform')?.getTexCoord() ?? null;
    if ((setOf ?? info.getTexCoord()) > 1) return;
    const b = m * GM_STRIDE + GM_TEXTURES + slot * BINDING_STRIDE;
    const imageIndex = textures.indexOf(texture);
    const srgb = isColorSlot(slot);
    const key = `${imageIndex}:${srgb}`;
    let r = requests.get(key);
    if (r === undefined) {
      r = {
        texture,
        imageIndex,
        srgb,
        bindings: [],
        firstUse: `materials[${m}].${SLOT_NAMES[slot]}`,
      };
      requests.set(key, r);
    }
    r.bindings.push(b);
    table[b + B_TEXCOORD] = info.getTexCoord();
    table[b + B_WRAP_S] = info.getWrapS();
    table[b + B_WRAP_T] = info.getWrapT();
    const tt = info.getExtension<Transform>('KHR_texture_transform');
    if (tt !== null) {
      const [ox, oy] = tt.getOffset();
      const [sx, sy] = tt.getScale();
      const r0 = tt.getRotation();
      const c = Math.cos(r0);
      const s = Math.sin(r0);
      // KHR_texture_transform: uv' = T · R · S · uv with R = [cos sin; −sin cos].
      table[b + B_TRANSFORM] = c * sx;
      table[b + B_TRANSFORM + 1] = s * sy;
      table[b + B_TRANSFORM + 2] = ox;
      table[b + B_TRANSFORM + 3] = -s * sx;
      table[b + B_TRANSFORM + 4] = c * sy;
      table[b + B_TRANSFORM + 5] = oy;
      const set = tt.getTexCoord();
      if (set !== null) table[b + B_TEXCOORD] = set;
    }
  };
  materials.forEach((mat, m) => {
    writeDefaultMaterial(table, m);
    const o = m * GM_STRIDE;
    table.set(mat.getBaseColorFactor(), o + GM_BASE);
    table[o + GM_METALLIC] = mat.getMetallicFactor();
    table[o + GM_ROUGHNESS] = mat.getRoughnessFactor();
    const strength = mat.getExtension<EmissiveStrength>('KHR_materials_emissive_strength');
    const k = strength === null ? 1 : strength.getEmissiveStrength();
    const e = mat.getEmissiveFactor();
    table[o + GM_EMISSIVE] = e[0] * k;
    table[o + GM_EMISSIVE + 1] = e[1] * k;
    table[o + GM_EMISSIVE + 2] = e[2] * k;
    const ior = mat.getExtension<IOR>('KHR_materials_ior');
    // KHR_materials_ior: 0 is allowed and means an infinite index (F0 = 1); 1e6 stands for it.
    if (ior !== null) table[o + GM_IOR] = ior.getIOR() === 0 ? 1e6 : ior.getIOR();
    const tr = mat.getExtension<Transmission>('KHR_materials_transmission');
    if (tr !== null) {
      table[o + GM_TRANSMISSION] = tr.getTransmissionFactor();
      bind(m, TEX_TRANSMISSION, tr.getTransmissionTexture(), tr.getTransmissionTextureInfo());
    }
    readVolumeExtensions(mat, m, table, bind, warn);
    const sp = mat.getExtension<Specular>('KHR_materials_specular');
    if (sp !== null) {
      table[o + GM_SPECULAR] = sp.getSpecularFactor();
      table.set(sp.getSpecularColorFactor(), o + GM_SPECULAR_COLOR);
      bind(m, TEX_SPECULAR, sp.getSpecularTexture(), sp.getSpecularTextureInfo());
      bind(m, TEX_SPECULAR_COLOR, sp.getSpecularColorTexture(), sp.getSpecularColorTextureInfo());
    }
    const ir = mat.getExtension<Iridescence>('KHR_materials_iridescence');
    if (ir !== null) {
      table[o + GM_IRIDESCENCE] = ir.getIridescenceFactor();
      table[o + GM_IRIDESCENCE_IOR] = ir.getIridescenceIOR();
      table[o + GM_IRIDESCENCE_THICKNESS_MIN] = ir.getIridescenceThicknessMinimum();
      table[o + GM_IRIDESCENCE_THICKNESS_MAX] = ir.getIridescenceThicknessMaximum();
      bind(m, TEX_IRIDESCENCE, ir.getIridescenceTexture(), ir.getIridescenceTextureInfo());
      bind(
        m,
        TEX_IRIDESCENCE_THICKNESS,
        ir.getIridescenceThicknessTexture(),
        ir.getIridescenceThicknessTextureInfo(),
      );
    }
    const an = mat.getExtension<Anisotropy>('KHR_materials_anisotropy');
    if (an !== null) {
      table[o + GM_ANISOTROPY_STRENGTH] = an.getAnisotropyStrength();
      table[o + GM_ANISOTROPY_ROTATION] = an.getAnisotropyRotation();
      bind(m, TEX_ANISOTROPY, an.getAnisotropyTexture(), an.getAnisotropyTextureInfo());
    }
    const mode = mat.getAlphaMode();
    table[o + GM_ALPHA_MODE] =
      mode === 'MASK' ? ALPHA_MASK : mode === 'BLEND' ? ALPHA_BLEND : ALPHA_OPAQUE;
    table[o + GM_ALPHA_CUTOFF] = mat.getAlphaCutoff();
    table[o + GM_NORMAL_SCALE] = mat.getNormalScale();
    // A specular–glossiness material brings its own base colour and roughness textures.
    if (mat.getExtension('KHR_materials_pbrSpecularGlossiness') === null) {
      bind(m, TEX_BASE_COLOR, mat.getBaseColorTexture(), mat.getBaseColorTextureInfo());
      bind(
        m,
        TEX_METALLIC_ROUGHNESS,
        mat.getMetallicRoughnessTexture(),
        mat.getMetallicRoughnessTextureInfo(),
      );
    }
    bind(m, TEX_NORMAL, mat.getNormalTexture(), mat.getNormalTextureInfo());
    bind(m, TEX_EMISSIVE, mat.getEmissiveTexture(), mat.getEmissiveTextureInfo());
    // Clearcoat, sheen, unlit and specular–glossiness (materials-layers.ts).
    compileLayers(mat, table, o, (slot, texture, info) => bind(m, slot, texture, info));
  });
  writeDefaultMaterial(table, n - 1);
  // Bindings keep B_IMAGE = −1 (writeDefaultMaterial) until their image is decoded.
  return { table, defaultMaterial: n - 1, requests: [...requests.values()] };
}

/** Whether material m is transmissive (needs the geometric side, like glass). */
export function isTransmissive(table: Float64Array, m: number): boolean {
  return table[m * GM_STRIDE + GM_TRANSMISSION] > 0;
}

/** Whether material m has KHR_materials_anisotropy (its primitives need tangents). */
export function usesAnisotropy(table: Float64Array, m: number): boolean {
  return table[m * GM_STRIDE + GM_ANISOTROPY_STRENGTH] > 0;
}
