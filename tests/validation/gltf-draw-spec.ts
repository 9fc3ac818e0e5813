/**
 * Random glTF materials with KHR_materials_anisotropy and/or
 * KHR_materials_iridescence for the generated-scene validation suite (the lead
 * wires `drawSpecMaterial` into a generated glTF family). The parameters come
 * from the grids of tests/statistical/gltf-bsdf-spec.test.ts, where χ²,
 * reciprocity and the white furnace hold.
 *
 * Tangents: an anisotropic material needs a tangent frame. The loader takes
 * the mesh's TANGENT, or generates MikkTSpace tangents for anisotropic
 * primitives (src/core/gltf/flatten.ts) — which needs TEXCOORD_0 (or the
 * anisotropy texture's set). So a mesh carrying a material with
 * `KHR_materials_anisotropy` MUST have TEXCOORD_0 (TANGENT optional; without
 * both the lobe falls back to isotropic with a warning). Iridescence needs
 * neither. No textures are drawn: factors only, so the material JSON stands
 * alone (no images to add to the document).
 */
import type { Rng } from './rng.ts';

/** A glTF 2.0 material object (JSON) and what its mesh must carry. */
export interface SpecMaterial {
  material: Record<string, unknown>;
  /** The extensions it uses (for the document's extensionsUsed). */
  extensionsUsed: string[];
  /** The mesh must have TEXCOORD_0 (for generated tangents) or TANGENT. */
  needsTangents: boolean;
}

export function drawSpecMaterial(g: Rng): SpecMaterial {
  const kind = g.pick(['anisotropy', 'iridescence', 'both'] as const);
  const metallic = g.pick([0, 0.5, 1]);
  const roughness = g.pick([0, 0.1, 0.3, 0.5, 0.7, 1]);
  const base = [g.uniform(0.2, 1), g.uniform(0.2, 1), g.uniform(0.2, 1), 1];
  const extensions: Record<string, unknown> = {};
  if (kind !== 'iridescence') {
    extensions.KHR_materials_anisotropy = {
      anisotropyStrength: g.pick([0.25, 0.5, 0.8, 1]),
      anisotropyRotation: g.uniform(-Math.PI, Math.PI),
    };
  }
  if (kind !== 'anisotropy') {
    const min = g.pick([0, 100, 200]);
    extensions.KHR_materials_iridescence = {
      iridescenceFactor: g.pick([0.5, 1]),
      iridescenceIor: g.pick([1.3, 1.5, 1.8, 2]),
      iridescenceThicknessMinimum: min,
      iridescenceThicknessMaximum: min + g.pick([100, 300, 600]),
    };
  }
  return {
    material: {
      name: `spec-${kind}`,
      pbrMetallicRoughness: {
        baseColorFactor: base,
        metallicFactor: metallic,
        roughnessFactor: roughness,
      },
      extensions,
    },
    extensionsUsed: Object.keys(extensions),
    needsTangents: kind !== 'iridescence',
  };
}
