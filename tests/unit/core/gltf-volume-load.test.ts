/**
 * Loading KHR_materials_volume, KHR_materials_dispersion and
 * KHR_materials_diffuse_transmission (src/core/gltf/materials-volume.ts): values into
 * the material table and the shading record, the warnings for combinations the
 * renderer does not model, the schemas' ranges refused with the JSON path, and the
 * extensions accepted when a file requires them.
 */
import { describe, expect, it } from 'vitest';
import { ShadingParams } from '../../../src/core/bsdf/shading.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import { HitAttributes, fillGltfShading } from '../../../src/core/gltf-material/shading-fill.ts';
import { memoryOptions } from '../../helpers/gltf.ts';

function file(materials: unknown[], required: string[] = []): Uint8Array {
  return new TextEncoder().encode(
    JSON.stringify({
      asset: { version: '2.0' },
      extensionsUsed: [
        'KHR_materials_transmission',
        'KHR_materials_volume',
        'KHR_materials_dispersion',
        'KHR_materials_diffuse_transmission',
      ],
      extensionsRequired: required,
      materials,
      scenes: [{ nodes: [] }],
      scene: 0,
    }),
  );
}

async function load(materials: unknown[], required: string[] = []) {
  return loadGltf(file(materials, required), 'm.gltf', await memoryOptions());
}

const GLASS = { KHR_materials_transmission: { transmissionFactor: 1 } };

describe('glTF volume, dispersion and diffuse transmission: loading', () => {
  it('fills the shading record: σa = −ln(colour)/distance, thin wall by default', async () => {
    const model = await load([
      {
        extensions: {
          ...GLASS,
          KHR_materials_volume: {
            thicknessFactor: 0.2,
            attenuationColor: [0.5, 1, 0.25],
            attenuationDistance: 2,
          },
          KHR_materials_dispersion: { dispersion: 0.5 },
        },
      },
      { extensions: { ...GLASS, KHR_materials_volume: { attenuationDistance: 2 } } },
      {
        extensions: {
          KHR_materials_diffuse_transmission: {
            diffuseTransmissionFactor: 0.6,
            diffuseTransmissionColorFactor: [0.2, 0.4, 0.8],
          },
        },
      },
    ]);
    expect(model.warnings.filter((w) => /ignored|not supported/.test(w))).toEqual([]);
    const sp = new ShadingParams();
    const hit = new HitAttributes();
    fillGltfShading(model.materials, model.textures, 0, hit, sp);
    expect(sp.thickness).toBe(0.2);
    expect(sp.sigmaAR).toBeCloseTo(Math.LN2 / 2, 15);
    expect(sp.sigmaAG).toBe(0);
    expect(sp.sigmaAB).toBeCloseTo((2 * Math.LN2) / 2, 15);
    expect(sp.dispersion).toBe(0.5);
    // The record is reused: the next material overwrites every field.
    fillGltfShading(model.materials, model.textures, 1, hit, sp);
    expect([sp.thickness, sp.sigmaAR, sp.sigmaAB, sp.dispersion]).toEqual([0, 0, 0, 0]);
    expect(sp.diffuseTransmission).toBe(0);
    fillGltfShading(model.materials, model.textures, 2, hit, sp);
    expect([sp.diffuseTransmission, sp.dtR, sp.dtG, sp.dtB]).toEqual([0.6, 0.2, 0.4, 0.8]);
  });

  it('warns where the renderer does not model a combination', async () => {
    const model = await load([
      { extensions: { ...GLASS, KHR_materials_dispersion: { dispersion: 1 } } },
      {
        extensions: {
          KHR_materials_volume: { thicknessFactor: 1 },
          KHR_materials_diffuse_transmission: { diffuseTransmissionFactor: 1 },
        },
      },
    ]);
    expect(model.warnings.join('\n')).toMatch(
      /materials\[0\]\.extensions\.KHR_materials_dispersion: the material is not a transmissive volume/,
    );
    expect(model.warnings.join('\n')).toMatch(
      /materials\[1\]\.extensions\.KHR_materials_diffuse_transmission: .*subsurface scattering is not modelled/,
    );
  });

  it.each([
    [
      { KHR_materials_volume: { attenuationDistance: 0 } },
      'KHR_materials_volume.attenuationDistance',
    ],
    [{ KHR_materials_volume: { thicknessFactor: -1 } }, 'KHR_materials_volume.thicknessFactor'],
    [
      { KHR_materials_volume: { attenuationColor: [1, 2, 1] } },
      'KHR_materials_volume.attenuationColor',
    ],
    [{ KHR_materials_dispersion: { dispersion: -0.1 } }, 'KHR_materials_dispersion.dispersion'],
    [
      { KHR_materials_diffuse_transmission: { diffuseTransmissionFactor: 1.5 } },
      'KHR_materials_diffuse_transmission.diffuseTransmissionFactor',
    ],
  ])('refuses %j naming the path', async (extensions, path) => {
    await expect(load([{ extensions }])).rejects.toThrow(`materials[0].extensions.${path}`);
  });

  it('loads a file that requires the three extensions', async () => {
    const model = await load(
      [{ extensions: { ...GLASS, KHR_materials_volume: { thicknessFactor: 1 } } }],
      ['KHR_materials_volume', 'KHR_materials_dispersion', 'KHR_materials_diffuse_transmission'],
    );
    expect(model.materials.length).toBeGreaterThan(0);
  });
});
