/**
 * The per-hit parameters of the glTF metallic–roughness material, in one
 * caller-owned record. The integrator fills it at each hit — from the
 * material's constant factors, or from its textures at the hit's texture
 * coordinates (see src/core/gltf-material/shading-fill.ts) — and the glTF BSDF
 * (gltf-pbr.ts) reads only this record, so per-triangle and per-texel
 * parameters cost no allocation and no change of the BSDF interface.
 *
 * Like pbrt's `MaterialEvalContext` → `BSDF` step (pbr-book 4e §10.5), the
 * textures are looked up once per hit, not once per BSDF call.
 */
export class ShadingParams {
  /** Linear base colour (glTF baseColorFactor × texture × COLOR_0). */
  baseR = 1;
  baseG = 1;
  baseB = 1;
  /** glTF metallic ∈ [0, 1]. */
  metallic = 0;
  /** GGX α = roughness²; 0 is a perfectly smooth surface (Dirac lobes). */
  alpha = 0;
  /** KHR_materials_transmission factor ∈ [0, 1]. */
  transmission = 0;
  /** KHR_materials_ior: index of refraction of the inside (default 1.5). */
  ior = 1.5;
  /** KHR_materials_specular: weight of the dielectric specular layer (default 1). */
  specular = 1;
  /** KHR_materials_specular: colour scaling the dielectric F0 (default white). */
  specR = 1;
  specG = 1;
  specB = 1;

  // The layers and lobes of issue 25's material extensions. Each default makes its
  // layer vanish, so a material without the extension is the plain model above.
  /** KHR_materials_clearcoat: coat weight ∈ [0, 1] (0: no coat). */
  clearcoat = 0;
  /** Coat GGX α = clearcoatRoughness²; 0 is a smooth coat (a Dirac lobe). */
  clearcoatAlpha = 0;
  /**
   * Coat normal (clearcoatNormalTexture): in tangent space from fillGltfShading ((0, 0, 1)
   * without one), in world space after shadeGltfHit, in the BSDF's local frame when the
   * BSDF reads it (trace-path.ts converts it; clearcoat.ts).
   */
  ccnx = 0;
  ccny = 0;
  ccnz = 1;
  /** KHR_materials_sheen: sheen colour, linear (black: no sheen). */
  sheenR = 0;
  sheenG = 0;
  sheenB = 0;
  /** KHR_materials_sheen: sheen roughness ∈ [0, 1]. */
  sheenRoughness = 0;
  /** KHR_materials_volume: 0 thin-walled, else the medium behind the surface is a volume. */
  thickness = 0;
  /** Absorption coefficient σa (1/m, per channel) of the volume: −ln(attenuationColor)/distance. */
  sigmaAR = 0;
  sigmaAG = 0;
  sigmaAB = 0;
  /** KHR_materials_iridescence: thin-film weight ∈ [0, 1], film ior and thickness (nm). */
  iridescence = 0;
  iridescenceIor = 1.3;
  iridescenceThickness = 400;
  /** KHR_materials_anisotropy: strength ∈ [0, 1] and direction (cos φ, sin φ) in tangent space. */
  anisotropy = 0;
  anisotropyCos = 1;
  anisotropySin = 0;
  /** KHR_materials_diffuse_transmission: weight ∈ [0, 1] and colour (linear). */
  diffuseTransmission = 0;
  dtR = 1;
  dtG = 1;
  dtB = 1;
  /** KHR_materials_dispersion: 20 / Abbe number (0: none). */
  dispersion = 0;
  /** KHR_materials_unlit: the surface shows its base colour and scatters nothing. */
  unlit = false;

  // Not read by the BSDF: what the integrator needs at the same hit.
  /** Coverage ∈ [0, 1] (alpha MASK and BLEND); 1 is opaque. */
  opacity = 1;
  /** Emitted radiance (emissiveFactor × texture × KHR_materials_emissive_strength). */
  emR = 0;
  emG = 0;
  emB = 0;
  /** Tangent-space shading normal from the normal map, (0, 0, 1) without one. */
  nx = 0;
  ny = 0;
  nz = 1;

  /** Back to the glTF defaults (a white, smooth, opaque dielectric). */
  reset(): void {
    this.baseR = 1;
    this.baseG = 1;
    this.baseB = 1;
    this.metallic = 0;
    this.alpha = 0;
    this.transmission = 0;
    this.ior = 1.5;
    this.specular = 1;
    this.specR = 1;
    this.specG = 1;
    this.specB = 1;
    this.clearcoat = 0;
    this.clearcoatAlpha = 0;
    this.ccnx = 0;
    this.ccny = 0;
    this.ccnz = 1;
    this.sheenR = 0;
    this.sheenG = 0;
    this.sheenB = 0;
    this.sheenRoughness = 0;
    this.thickness = 0;
    this.sigmaAR = 0;
    this.sigmaAG = 0;
    this.sigmaAB = 0;
    this.iridescence = 0;
    this.iridescenceIor = 1.3;
    this.iridescenceThickness = 400;
    this.anisotropy = 0;
    this.anisotropyCos = 1;
    this.anisotropySin = 0;
    this.diffuseTransmission = 0;
    this.dtR = 1;
    this.dtG = 1;
    this.dtB = 1;
    this.dispersion = 0;
    this.unlit = false;
    this.opacity = 1;
    this.emR = 0;
    this.emG = 0;
    this.emB = 0;
    this.nx = 0;
    this.ny = 0;
    this.nz = 1;
  }
}
