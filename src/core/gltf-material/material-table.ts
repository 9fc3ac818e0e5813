/**
 * glTF materials compiled into one Float64Array, GM_STRIDE numbers each, so
 * the tracer reads them without touching objects (like bsdf/materials.ts).
 * A record holds the material's constant factors and up to seven texture
 * bindings; `fillGltfShading` (shading-fill.ts) turns a record and a hit's
 * texture coordinates into the per-hit ShadingParams the BSDF reads.
 */

/** baseColorFactor, RGBA (linear) */
export const GM_BASE = 0;
export const GM_METALLIC = 4;
export const GM_ROUGHNESS = 5;
/** emissiveFactor × KHR_materials_emissive_strength, RGB */
export const GM_EMISSIVE = 6;
/** KHR_materials_ior (default 1.5) */
export const GM_IOR = 9;
/** KHR_materials_transmission factor (default 0) */
export const GM_TRANSMISSION = 10;
/** KHR_materials_specular factor (default 1) */
export const GM_SPECULAR = 11;
/** KHR_materials_specular colour factor, RGB (default white) */
export const GM_SPECULAR_COLOR = 12;
/** ALPHA_OPAQUE, ALPHA_MASK or ALPHA_BLEND */
export const GM_ALPHA_MODE = 15;
export const GM_ALPHA_CUTOFF = 16;
/** normalTexture.scale */
export const GM_NORMAL_SCALE = 17;
/** First texture binding; TEX_COUNT bindings of BINDING_STRIDE numbers follow. */
export const GM_TEXTURES = 18;

export const ALPHA_OPAQUE = 0;
export const ALPHA_MASK = 1;
export const ALPHA_BLEND = 2;

/** The texture slots of a material, in binding order. */
export const TEX_BASE_COLOR = 0;
export const TEX_METALLIC_ROUGHNESS = 1;
export const TEX_NORMAL = 2;
export const TEX_EMISSIVE = 3;
export const TEX_TRANSMISSION = 4;
export const TEX_SPECULAR = 5;
export const TEX_SPECULAR_COLOR = 6;
export const TEX_COUNT = 7;

/**
 * One binding: the image in the TextureStore (−1 for none), the TEXCOORD set,
 * the sampler's wrap modes, and the affine uv transform of
 * KHR_texture_transform, uv' = (a·u + b·v + c, d·u + e·v + f).
 */
export const B_IMAGE = 0;
export const B_TEXCOORD = 1;
export const B_WRAP_S = 2;
export const B_WRAP_T = 3;
export const B_TRANSFORM = 4;
export const BINDING_STRIDE = 10;

export const GM_STRIDE = GM_TEXTURES + TEX_COUNT * BINDING_STRIDE;

/** Whether a texture slot of the colour kind (sRGB-encoded RGB). */
export function isColorSlot(slot: number): boolean {
  return slot === TEX_BASE_COLOR || slot === TEX_EMISSIVE || slot === TEX_SPECULAR_COLOR;
}

export const SLOT_NAMES = [
  'baseColorTexture',
  'metallicRoughnessTexture',
  'normalTexture',
  'emissiveTexture',
  'transmissionTexture',
  'specularTexture',
  'specularColorTexture',
];

/** A material record with the glTF defaults (what a primitive without a material gets). */
export function writeDefaultMaterial(table: Float64Array, m: number): void {
  const o = m * GM_STRIDE;
  table.fill(0, o, o + GM_STRIDE);
  table[o + GM_BASE] = 1;
  table[o + GM_BASE + 1] = 1;
  table[o + GM_BASE + 2] = 1;
  table[o + GM_BASE + 3] = 1;
  // The glTF default material is a rough metal (metallicFactor and roughnessFactor default to 1).
  table[o + GM_METALLIC] = 1;
  table[o + GM_ROUGHNESS] = 1;
  table[o + GM_IOR] = 1.5;
  table[o + GM_SPECULAR] = 1;
  table[o + GM_SPECULAR_COLOR] = 1;
  table[o + GM_SPECULAR_COLOR + 1] = 1;
  table[o + GM_SPECULAR_COLOR + 2] = 1;
  table[o + GM_ALPHA_MODE] = ALPHA_OPAQUE;
  table[o + GM_ALPHA_CUTOFF] = 0.5;
  table[o + GM_NORMAL_SCALE] = 1;
  for (let s = 0; s < TEX_COUNT; s++) {
    const b = o + GM_TEXTURES + s * BINDING_STRIDE;
    table[b + B_IMAGE] = -1;
    table[b + B_TRANSFORM] = 1;
    table[b + B_TRANSFORM + 4] = 1;
  }
}

/** Whether material m has a texture in `slot`. */
export function hasTexture(table: Float64Array, m: number, slot: number): boolean {
  return table[m * GM_STRIDE + GM_TEXTURES + slot * BINDING_STRIDE + B_IMAGE] >= 0;
}
