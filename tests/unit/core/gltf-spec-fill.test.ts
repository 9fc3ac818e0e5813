/**
 * KHR_materials_anisotropy and KHR_materials_iridescence from the file to the
 * BSDF's parameters: what compileGltfMaterials reads, what fillGltfShading
 * makes of factors and textures at a hit (README semantics: strength × B,
 * direction = rotation applied to normalize(2·RG − 1); thickness = mix(min,
 * max, G), the maximum without a texture), and the direction carried from the
 * tangent frame to the shading frame (anisotropy-frame.ts): rotation counter-
 * clockwise from T towards B = (N × T)·w.
 */
import { Document } from '@gltf-transform/core';
import { KHRMaterialsAnisotropy, KHRMaterialsIridescence } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { ShadingParams } from '../../../src/core/bsdf/shading.ts';
import {
  anisotropyToLocal,
  anisotropyToWorld,
} from '../../../src/core/gltf-material/anisotropy-frame.ts';
import { fillGltfShading, HitAttributes } from '../../../src/core/gltf-material/shading-fill.ts';
import { docWith, loadGlb, png, quadPrimitive } from '../../helpers/gltf.ts';

async function model(textures: boolean) {
  const doc = new Document();
  const mat = doc.createMaterial().setRoughnessFactor(0.5);
  const a = doc
    .createExtension(KHRMaterialsAnisotropy)
    .createAnisotropy()
    .setAnisotropyStrength(0.8)
    .setAnisotropyRotation(Math.PI / 6);
  const i = doc
    .createExtension(KHRMaterialsIridescence)
    .createIridescence()
    .setIridescenceFactor(0.9)
    .setIridescenceIOR(1.7)
    .setIridescenceThicknessMinimum(200)
    .setIridescenceThicknessMaximum(600);
  if (textures) {
    // Direction (0, 1) (R 0.5, G 1), strength ×0.5; film weight ×0.5, thickness at G = 0.25.
    const tex = (rgba: number[]) =>
      doc
        .createTexture()
        .setImage(png(1, 1, () => rgba))
        .setMimeType('image/png');
    a.setAnisotropyTexture(tex([128, 255, 128, 255]));
    i.setIridescenceTexture(tex([128, 0, 0, 255]));
    i.setIridescenceThicknessTexture(tex([0, 64, 0, 255]));
  }
  mat.setExtension('KHR_materials_anisotropy', a).setExtension('KHR_materials_iridescence', i);
  const m = await loadGlb(docWith(doc, quadPrimitive(doc).setMaterial(mat)));
  const sp = new ShadingParams();
  fillGltfShading(m.materials, m.textures, 0, new HitAttributes(), sp);
  return { sp, warnings: m.warnings };
}

describe('anisotropy and iridescence parameters', () => {
  it('factors alone: the rotated tangent, the full strength, the maximum thickness', async () => {
    const { sp, warnings } = await model(false);
    expect(warnings).toEqual([]);
    expect(sp.anisotropy).toBe(0.8);
    expect(sp.anisotropyCos).toBeCloseTo(Math.cos(Math.PI / 6), 12);
    expect(sp.anisotropySin).toBeCloseTo(Math.sin(Math.PI / 6), 12);
    expect([sp.iridescence, sp.iridescenceIor, sp.iridescenceThickness]).toEqual([0.9, 1.7, 600]);
  });

  it('textures: strength × B, direction rotated by the rotation, thickness mix(min, max, G)', async () => {
    const { sp } = await model(true);
    const b = 128 / 255;
    expect(sp.anisotropy).toBeCloseTo(0.8 * b, 6);
    // The texture's direction is (2·128/255 − 1, 1) normalised, then rotated by 30°.
    const dx = 2 * b - 1;
    const l = Math.hypot(dx, 1);
    const phi = Math.atan2(1 / l, dx / l) + Math.PI / 6;
    expect(sp.anisotropyCos).toBeCloseTo(Math.cos(phi), 6);
    expect(sp.anisotropySin).toBeCloseTo(Math.sin(phi), 6);
    expect(sp.iridescence).toBeCloseTo(0.9 * b, 6);
    expect(sp.iridescenceThickness).toBeCloseTo(200 + 400 * (64 / 255), 4);
  });

  it('the direction goes from tangent space to world to the shading frame', () => {
    const sp = new ShadingParams();
    const out = { x: 0, y: 0, z: 0 };
    // N = z, T = x: rotation 90° is B = N × T = y, or −y for a mirrored frame (w = −1).
    sp.anisotropyCos = 0;
    sp.anisotropySin = 1;
    expect(anisotropyToWorld(Float64Array.of(1, 0, 0, 1), 0, 0, 1, sp, out)).toBe(true);
    expect([out.x, out.y, out.z].map((v) => Math.round(v * 1e12) / 1e12)).toEqual([0, 1, 0]);
    anisotropyToWorld(Float64Array.of(1, 0, 0.3, -1), 0, 0, 1, sp, out);
    expect(out.y).toBeCloseTo(-1, 12);
    // A tangent along N, or no tangent, gives no frame.
    expect(anisotropyToWorld(Float64Array.of(0, 0, 1, 1), 0, 0, 1, sp, out)).toBe(false);
    expect(anisotropyToWorld(Float64Array.of(1, 0, 0, 0), 0, 0, 1, sp, out)).toBe(false);
    // Onto a frame whose tangents are (0, 1, 0) and (−1, 0, 0): world y is φ = 0.
    sp.anisotropy = 1;
    anisotropyToLocal({ x: 0, y: 1, z: 0 }, 0, 1, 0, -1, 0, 0, sp);
    expect([sp.anisotropyCos, sp.anisotropySin]).toEqual([1, 0]);
    anisotropyToLocal({ x: 1, y: 0, z: 0 }, 0, 1, 0, -1, 0, 0, sp);
    expect([sp.anisotropyCos, sp.anisotropySin]).toEqual([0, -1]);
  });
});
