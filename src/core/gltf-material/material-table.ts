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

// The material extensions of issue 25, each with the default its specification gives
// (writeDefaultMaterial). A default record makes every layer vanish, so a material
// without an extension renders exactly as the plain metallic–roughness model.
/** KHR_materials_clearcoat: clearcoatFactor (default 0: no coat). */
export const GM_CLEARCOAT = 18;
/** KHR_materials_clearcoat: clearcoatRoughnessFactor (default 0). */
export const GM_CLEARCOAT_ROUGHNESS = 19;
/** KHR_materials_clearcoat: clearcoatNormalTexture.scale (default 1). */
export const GM_CLEARCOAT_NORMAL_SCALE = 20;
/** KHR_materials_sheen: sheenColorFactor, RGB linear (default black: no sheen). */
export const GM_SHEEN_COLOR = 21;
/** KHR_materials_sheen: sheenRoughnessFactor (default 0). */
export const GM_SHEEN_ROUGHNESS = 24;
/** KHR_materials_volume: thicknessFactor (default 0: thin-walled). */
export const GM_THICKNESS = 25;
/** KHR_materials_volume: attenuationColor, RGB linear (default white). */
export const GM_ATTENUATION_COLOR = 26;
/** KHR_materials_volume: attenuationDistance (default +∞: no absorption). */
export const GM_ATTENUATION_DISTANCE = 29;
/** KHR_materials_iridescence: iridescenceFactor (default 0). */
export const GM_IRIDESCENCE = 30;
/** KHR_materials_iridescence: iridescenceIor (default 1.3). */
export const GM_IRIDESCENCE_IOR = 31;
/** KHR_materials_iridescence: iridescenceThicknessMinimum in nm (default 100). */
export const GM_IRIDESCENCE_THICKNESS_MIN = 32;
/** KHR_materials_iridescence: iridescenceThicknessMaximum in nm (default 400). */
export const GM_IRIDESCENCE_THICKNESS_MAX = 33;
/** KHR_materials_anisotropy: anisotropyStrength (default 0). */
export const GM_ANISOTROPY_STRENGTH = 34;
/** KHR_materials_anisotropy: anisotropyRotation in radians (default 0). */
export const GM_ANISOTROPY_ROTATION = 35;
/** KHR_materials_diffuse_transmission: diffuseTransmissionFactor (default 0). */
export const GM_DIFFUSE_TRANSMISSION = 36;
/** KHR_materials_diffuse_transmission: diffuseTransmissionColorFactor, RGB (default white). */
export const GM_DIFFUSE_TRANSMISSION_COLOR = 37;
/** KHR_materials_dispersion: dispersion = 20 / Abbe number (default 0: none). */
export const GM_DISPERSION = 40;
/** KHR_materials_unlit: 1 when present (default 0). */
export const GM_UNLIT = 41;
/** First texture binding; TEX_COUNT bindings of BINDING_STRIDE numbers follow. */
export const GM_TEXTURES = 42;

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
/** KHR_materials_clearcoat: clearcoatTexture (R), clearcoatRoughnessTexture (G), clearcoatNormalTexture. */
export const TEX_CLEARCOAT = 7;
export const TEX_CLEARCOAT_ROUGHNESS = 8;
export const TEX_CLEARCOAT_NORMAL = 9;
/** KHR_materials_sheen: sheenColorTexture (RGB, sRGB), sheenRoughnessTexture (A). */
export const TEX_SHEEN_COLOR = 10;
export const TEX_SHEEN_ROUGHNESS = 11;
/** KHR_materials_volume: thicknessTexture (G). */
export const TEX_THICKNESS = 12;
/** KHR_materials_iridescence: iridescenceTexture (R), iridescenceThicknessTexture (G). */
export const TEX_IRIDESCENCE = 13;
export const TEX_IRIDESCENCE_THICKNESS = 14;
/** KHR_materials_anisotropy: anisotropyTexture (RG direction, B strength). */
export const TEX_ANISOTROPY = 15;
/** KHR_materials_diffuse_transmission: diffuseTransmissionTexture (A), …ColorTexture (RGB, sRGB). */
export const TEX_DIFFUSE_TRANSMISSION = 16;
export const TEX_DIFFUSE_TRANSMISSION_COLOR = 17;
/** KHR_materials_pbrSpecularGlossiness: specularGlossinessTexture (RGB sRGB specular, A glossiness). */
export const TEX_SPEC_GLOSS = 18;
export const TEX_COUNT = 19;

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
  return (
    slot === TEX_BASE_COLOR ||
    slot === TEX_EMISSIVE ||
    slot === TEX_SPECULAR_COLOR ||
    slot === TEX_SHEEN_COLOR ||
    slot === TEX_DIFFUSE_TRANSMISSION_COLOR ||
    // Its RGB is the sRGB specular colour; the decoder leaves A (glossiness) linear.
    slot === TEX_SPEC_GLOSS
  );
}

export const SLOT_NAMES = [
  'baseColorTexture',
  'metallicRoughnessTexture',
  'normalTexture',
  'emissiveTexture',
  'transmissionTexture',
  'specularTexture',
  'specularColorTexture',
  'clearcoatTexture',
  'clearcoatRoughnessTexture',
  'clearcoatNormalTexture',
  'sheenColorTexture',
  'sheenRoughnessTexture',
  'thicknessTexture',
  'iridescenceTexture',
  'iridescenceThicknessTexture',
  'anisotropyTexture',
  'diffuseTransmissionTexture',
  'diffuseTransmissionColorTexture',
  'specularGlossinessTexture',
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
  table[o + GM_CLEARCOAT_NORMAL_SCALE] = 1;
  table[o + GM_ATTENUATION_COLOR] = 1;
  table[o + GM_ATTENUATION_COLOR + 1] = 1;
  table[o + GM_ATTENUATION_COLOR + 2] = 1;
  table[o + GM_ATTENUATION_DISTANCE] = Infinity;
  table[o + GM_IRIDESCENCE_IOR] = 1.3;
  table[o + GM_IRIDESCENCE_THICKNESS_MIN] = 100;
  table[o + GM_IRIDESCENCE_THICKNESS_MAX] = 400;
  table[o + GM_DIFFUSE_TRANSMISSION_COLOR] = 1;
  table[o + GM_DIFFUSE_TRANSMISSION_COLOR + 1] = 1;
  table[o + GM_DIFFUSE_TRANSMISSION_COLOR + 2] = 1;
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
