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
import { memoryOptions } from '../../helpers/gltf.ts';

/** A unit quad (positions, normals, TEXCOORD_0, indices) as one base64 buffer. */
function quadGltf(material: Record<string, unknown>, extensionsUsed: string[]): Uint8Array {
  const f = new Float32Array([
    0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 1, 1, 1, 0, 0, 0,
  ]);
  const i = new Uint16Array([0, 1, 2, 0, 2, 3]);
  const bytes = new Uint8Array(f.byteLength + i.byteLength);
  bytes.set(new Uint8Array(f.buffer), 0);
  bytes.set(new Uint8Array(i.buffer), f.byteLength);
  const json = {
    asset: { version: '2.0' },
    extensionsUsed,
    buffers: [
      {
        byteLength: bytes.length,
        uri: `data:application/octet-stream;base64,${Buffer.from(bytes).toString('base64')}`,
      },
    ],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: 48 },
      { buffer: 0, byteOffset: 48, byteLength: 48 },
      { buffer: 0, byteOffset: 96, byteLength: 32 },
      { buffer: 0, byteOffset: 128, byteLength: 12 },
    ],
    accessors: [
      {
        bufferView: 0,
        componentType: 5126,
        count: 4,
        type: 'VEC3',
        min: [0, 0, 0],
        max: [1, 1, 0],
      },
      { bufferView: 1, componentType: 5126, count: 4, type: 'VEC3' },
      { bufferView: 2, componentType: 5126, count: 4, type: 'VEC2' },
      { bufferView: 3, componentType: 5123, count: 6, type: 'SCALAR' },
    ],
    materials: [material],
    meshes: [
      {
        primitives: [
          { attributes: { POSITION: 0, NORMAL: 1, TEXCOORD_0: 2 }, indices: 3, material: 0 },
        ],
      },
    ],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
    scene: 0,
  };
  return new TextEncoder().encode(JSON.stringify(json));
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
