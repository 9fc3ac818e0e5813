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
    this.opacity = 1;
    this.emR = 0;
    this.emG = 0;
    this.emB = 0;
    this.nx = 0;
    this.ny = 0;
    this.nz = 1;
  }
}
