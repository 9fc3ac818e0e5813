/**
 * A random glTF material with KHR_materials_clearcoat and KHR_materials_sheen for the
 * generated-scene validation suite, over the parameter grids of the layered BSDF's
 * white-furnace test (tests/statistical/gltf-layers.test.ts): clearcoat ∈ {0, .5, 1} ×
 * clearcoatRoughness ∈ {0, .3, .7, 1}, sheen colour ∈ {0, .5, 1}³ × sheenRoughness ∈
 * {.05, .3, .6, 1}, over a base of metallic ∈ {0, 1} × roughness ∈ {0, .3, 1} with a
 * random base colour. Zero coats and black sheens are drawn too: they are the
 * reductions, rendered through the same path as the layered materials.
 */
import type { Rng } from './rng.ts';

export interface LayersMaterialJson {
  pbrMetallicRoughness: {
    baseColorFactor: [number, number, number, number];
    metallicFactor: number;
    roughnessFactor: number;
  };
  extensions: {
    KHR_materials_clearcoat: { clearcoatFactor: number; clearcoatRoughnessFactor: number };
    KHR_materials_sheen: {
      sheenColorFactor: [number, number, number];
      sheenRoughnessFactor: number;
    };
  };
}

const LEVELS = [0, 0.5, 1] as const;

/** One glTF material JSON drawn from the furnace grids with the suite's stream `g`. */
export function drawLayersMaterial(g: Rng): LayersMaterialJson {
  return {
    pbrMetallicRoughness: {
      baseColorFactor: [g.uniform(0.05, 1), g.uniform(0.05, 1), g.uniform(0.05, 1), 1],
      metallicFactor: g.pick([0, 1]),
      roughnessFactor: g.pick([0, 0.3, 1]),
    },
    extensions: {
      KHR_materials_clearcoat: {
        clearcoatFactor: g.pick(LEVELS),
        clearcoatRoughnessFactor: g.pick([0, 0.3, 0.7, 1]),
      },
      KHR_materials_sheen: {
        sheenColorFactor: [g.pick(LEVELS), g.pick(LEVELS), g.pick(LEVELS)],
        sheenRoughnessFactor: g.pick([0.05, 0.3, 0.6, 1]),
      },
    },
  };
}
