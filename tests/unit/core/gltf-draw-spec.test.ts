/**
 * drawSpecMaterial (tests/validation/gltf-draw-spec.ts), the validation suite's
 * source of anisotropic and iridescent glTF materials: every draw is a valid
 * material that loads without a warning on a mesh with TEXCOORD_0 and no
 * TANGENT (tangents generated), and its numbers reach the material table.
 */
import { describe, expect, it } from 'vitest';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import {
  GM_ANISOTROPY_STRENGTH,
  GM_IRIDESCENCE,
  GM_STRIDE,
} from '../../../src/core/gltf-material/material-table.ts';
import { drawSpecMaterial } from '../../validation/gltf-draw-spec.ts';
import { Rng } from '../../validation/rng.ts';
import { quadGltfDataUri } from '../../fuzz/gltf-samples.ts';
import { memoryOptions } from '../../helpers/gltf.ts';

/** The fuzz table's unit quad (.gltf, buffer in a data: URI) with `material` on it. */
function quadGltf(material: Record<string, unknown>, extensionsUsed: string[]): Uint8Array {
  return quadGltfDataUri({
    edit: (json) => {
      json.extensionsUsed = extensionsUsed;
      json.materials = [material];
      (json.meshes as { primitives: { material?: number }[] }[])[0].primitives[0].material = 0;
    },
  });
}

describe('drawSpecMaterial', () => {
  it('draws valid materials that load without warnings, over 24 seeds', async () => {
    const options = await memoryOptions();
    const kinds = new Set<string>();
    for (let seed = 0; seed < 24; seed++) {
      const d = drawSpecMaterial(new Rng(seed));
      kinds.add(d.extensionsUsed.join('+'));
      const m = await loadGltf(quadGltf(d.material, d.extensionsUsed), 'quad.gltf', options);
      expect(m.warnings).toEqual([]);
      const ext = d.material.extensions as Record<string, Record<string, number>>;
      const t = m.materials;
      expect(t[GM_ANISOTROPY_STRENGTH]).toBe(ext.KHR_materials_anisotropy?.anisotropyStrength ?? 0);
      expect(t[GM_IRIDESCENCE]).toBe(ext.KHR_materials_iridescence?.iridescenceFactor ?? 0);
      expect(d.needsTangents).toBe('KHR_materials_anisotropy' in ext);
      expect(t.length).toBeGreaterThanOrEqual(GM_STRIDE);
    }
    expect(kinds.size).toBe(3);
  });
});
