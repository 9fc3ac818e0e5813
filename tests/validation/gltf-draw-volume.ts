/**
 * A random glTF material for the generated scenes (generate.ts) that uses the
 * transport of issue 25's volume piece: the thin-walled transmission of
 * KHR_materials_transmission, a KHR_materials_volume solid with Beer–Lambert
 * absorption, KHR_materials_dispersion on such a solid, and
 * KHR_materials_diffuse_transmission. Parameters come from the grids of
 * tests/statistical/gltf-transmission-chi2.test.ts (roughness, transmission,
 * diffuse transmission) and tests/scenes/gltf-volume.test.ts (absorption,
 * dispersion). One draw of the suite's seeded stream (rng.ts) per material.
 *
 * A volume only makes sense on a closed mesh (docs/gltf.md): give the
 * `volume` kinds to closed shapes (spheres, boxes) and the others to anything.
 */
import type { Rng } from './rng.ts';

/** The extensions a drawn material may use (for the file's `extensionsUsed`). */
export const VOLUME_EXTENSIONS = [
  'KHR_materials_transmission',
  'KHR_materials_ior',
  'KHR_materials_volume',
  'KHR_materials_dispersion',
  'KHR_materials_diffuse_transmission',
];

export type VolumeKind = 'thin glass' | 'volume' | 'dispersive volume' | 'diffuse transmission';

const ROUGHNESS = [0, 0.05, 0.3, 0.7, 1];
const IOR = [1, 1.33, 1.5, 2.4];

function color(g: Rng, lo: number): [number, number, number] {
  return [g.uniform(lo, 1), g.uniform(lo, 1), g.uniform(lo, 1)];
}

/** A glTF material (JSON) of `kind`, or of a kind drawn from the stream. */
export function drawVolumeMaterial(
  g: Rng,
  kind: VolumeKind = g.pick([
    'thin glass',
    'volume',
    'dispersive volume',
    'diffuse transmission',
  ] as const),
): { name: string; kind: VolumeKind } & Record<string, unknown> {
  const roughness = g.pick(ROUGHNESS);
  const extensions: Record<string, unknown> = {};
  const pbr = {
    baseColorFactor: [...color(g, 0.3), 1],
    metallicFactor: g.chance(0.2) ? 0.5 : 0,
    roughnessFactor: roughness,
  };
  if (kind === 'diffuse transmission') {
    extensions.KHR_materials_diffuse_transmission = {
      diffuseTransmissionFactor: g.pick([0.25, 0.5, 1]),
      diffuseTransmissionColorFactor: color(g, 0.2),
    };
    if (g.chance(0.3)) extensions.KHR_materials_transmission = { transmissionFactor: 0.5 };
  } else {
    extensions.KHR_materials_transmission = { transmissionFactor: g.pick([0.5, 1, 1]) };
    extensions.KHR_materials_ior = { ior: g.pick(IOR) };
    if (kind !== 'thin glass') {
      const volume: Record<string, unknown> = { thicknessFactor: g.pick([0.1, 1]) };
      // Absorption about half the time: otherwise the default infinite distance.
      if (g.chance(0.5)) {
        volume.attenuationColor = color(g, 0.1);
        volume.attenuationDistance = g.logUniform(0.1, 10);
      }
      extensions.KHR_materials_volume = volume;
      if (kind === 'dispersive volume')
        extensions.KHR_materials_dispersion = { dispersion: g.pick([0.5, 1, 5]) };
    }
  }
  return {
    name: `${kind}, roughness ${roughness}`,
    kind,
    pbrMetallicRoughness: pbr,
    extensions,
  };
}
