/**
 * The validation suite's volume-material generator (gltf-draw-volume.ts): each draw is
 * a valid glTF material that pathwise loads without ignoring anything, with the
 * parameters it was drawn with in the material table.
 */
import { describe, expect, it } from 'vitest';
import { loadGltf } from '../../src/core/gltf/load.ts';
import {
  GM_ATTENUATION_DISTANCE,
  GM_DIFFUSE_TRANSMISSION,
  GM_DISPERSION,
  GM_STRIDE,
  GM_THICKNESS,
  GM_TRANSMISSION,
} from '../../src/core/gltf-material/material-table.ts';
import { memoryOptions } from '../helpers/gltf.ts';
import { drawVolumeMaterial, VOLUME_EXTENSIONS } from './gltf-draw-volume.ts';
import { Rng } from './rng.ts';

describe('drawVolumeMaterial', () => {
  it('is a function of the stream alone', () => {
    expect(drawVolumeMaterial(new Rng(5))).toEqual(drawVolumeMaterial(new Rng(5)));
  });

  it('loads 40 draws with every kind, nothing ignored, parameters in the table', async () => {
    const rng = new Rng(20261203);
    const draws = Array.from({ length: 40 }, () => drawVolumeMaterial(rng));
    expect(new Set(draws.map((d) => d.kind)).size).toBe(4);
    const materials = draws.map(({ kind: _kind, ...m }) => m);
    const json = {
      asset: { version: '2.0' },
      extensionsUsed: VOLUME_EXTENSIONS,
      materials,
      scenes: [{ nodes: [] }],
      scene: 0,
    };
    const model = await loadGltf(
      new TextEncoder().encode(JSON.stringify(json)),
      'm.gltf',
      await memoryOptions(),
    );
    expect(model.warnings.filter((w) => /ignored|not supported/.test(w))).toEqual([]);
    const t = model.materials;
    draws.forEach((d, m) => {
      const o = m * GM_STRIDE;
      const ext = d.extensions as Record<string, Record<string, number>>;
      expect(t[o + GM_TRANSMISSION]).toBe(ext.KHR_materials_transmission?.transmissionFactor ?? 0);
      expect(t[o + GM_THICKNESS]).toBe(ext.KHR_materials_volume?.thicknessFactor ?? 0);
      expect(t[o + GM_ATTENUATION_DISTANCE]).toBe(
        ext.KHR_materials_volume?.attenuationDistance ?? Infinity,
      );
      expect(t[o + GM_DISPERSION]).toBe(ext.KHR_materials_dispersion?.dispersion ?? 0);
      expect(t[o + GM_DIFFUSE_TRANSMISSION]).toBe(
        ext.KHR_materials_diffuse_transmission?.diffuseTransmissionFactor ?? 0,
      );
    });
  });
});
