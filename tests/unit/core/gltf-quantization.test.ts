/**
 * KHR_mesh_quantization (a file that requires it): positions stored as integers
 * (unnormalised Int16, scaled back by the node, as glTF-Transform's quantize writes
 * them) and normals as normalised Int8 read as the same triangles and unit normals as
 * the float file. Without the extension such accessors are invalid glTF; with it the
 * loader must decode them, not refuse the file.
 */
import { Document } from '@gltf-transform/core';
import { KHRMeshQuantization } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { loadGlb } from '../../helpers/gltf.ts';

describe('KHR_mesh_quantization', () => {
  it('decodes Int16 positions (scaled by the node) and normalised Int8 normals', async () => {
    const doc = new Document();
    doc.createExtension(KHRMeshQuantization).setRequired(true);
    const buffer = doc.createBuffer();
    // A quad of side 2 at z = 0.5, stored in units of 1/1000.
    const pos = new Int16Array([
      -1000, -1000, 500, 1000, -1000, 500, 1000, 1000, 500, -1000, 1000, 500,
    ]);
    // Normal (0, 0.6, 0.8) as Int8 normalised (×127, rounded).
    const nrm = new Int8Array([0, 76, 102, 0, 76, 102, 0, 76, 102, 0, 76, 102]);
    const prim = doc
      .createPrimitive()
      .setAttribute(
        'POSITION',
        doc.createAccessor().setType('VEC3').setArray(pos).setBuffer(buffer),
      )
      .setAttribute(
        'NORMAL',
        doc.createAccessor().setType('VEC3').setNormalized(true).setArray(nrm).setBuffer(buffer),
      )
      .setIndices(
        doc
          .createAccessor()
          .setType('SCALAR')
          .setArray(new Uint8Array([0, 1, 2, 0, 2, 3]))
          .setBuffer(buffer),
      );
    const node = doc
      .createNode()
      .setMesh(doc.createMesh().addPrimitive(prim))
      .setScale([0.001, 0.001, 0.001]);
    doc.getRoot().setDefaultScene(doc.createScene().addChild(node));
    const m = await loadGlb(doc);
    expect(m.warnings).toEqual([]);
    expect(m.indices.length).toBe(6);
    const want = [-1, -1, 0.5, 1, -1, 0.5, 1, 1, 0.5, -1, 1, 0.5];
    for (let i = 0; i < 12; i++) expect(m.positions[i]).toBeCloseTo(want[i], 12);
    // Normalised Int8 is c / 127; the loader renormalises shading normals.
    const n = Math.hypot(76, 102);
    for (let v = 0; v < 4; v++) {
      expect(m.normals![3 * v]).toBeCloseTo(0, 6);
      expect(m.normals![3 * v + 1]).toBeCloseTo(76 / n, 6);
      expect(m.normals![3 * v + 2]).toBeCloseTo(102 / n, 6);
    }
  });
});
