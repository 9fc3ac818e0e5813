/**
 * A glTF model against an independent reference: the canonical Cornell box rebuilt as
 * a glTF 2.0 file (made here with glTF-Transform) converges to Mitsuba 3's render of
 * the original scene (tests/references/cornell.pfm, 65,536 spp). Each quad becomes two
 * triangles of a glTF mesh (winding u × v, so normals and the light's emitting side are
 * the quad's); each diffuse material becomes a glTF material with no specular layer
 * (KHR_materials_specular, factor 0: Lambert), and the light's radiance is its emissive
 * colour times KHR_materials_emissive_strength. What it checks end to end: the loader,
 * the flattening into the BVH, glTF materials at triangle hits, emissive triangles found
 * by next-event estimation, and MIS — against a renderer that shares no code with
 * pathwise. The checks and thresholds are those of references.test.ts (per-channel
 * means within 1 %; 16×16 block χ² at p = 0.001, no block beyond |z| = 5.5).
 */
import { Document } from '@gltf-transform/core';
import { KHRMaterialsEmissiveStrength, KHRMaterialsSpecular } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { sceneWithFiles, toGlb } from '../helpers/gltf.ts';
import {
  blockChiSquare,
  chiSquareQuantile,
  imageMean,
  loadReference,
  loadScene,
  referenceMean,
  renderSampled,
} from '../helpers/render.ts';

type Vec3 = [number, number, number];
interface QuadShape {
  type: 'quad';
  corner: Vec3;
  u: Vec3;
  v: Vec3;
  material: string;
}
interface DiffuseDesc {
  albedo: Vec3;
  emission?: Vec3;
}

/** The Cornell box's quads, grouped by material into one glTF primitive each. */
function cornellAsGltf(quads: QuadShape[], materials: Record<string, DiffuseDesc>): Document {
  const doc = new Document();
  const buffer = doc.createBuffer();
  const specular = doc.createExtension(KHRMaterialsSpecular);
  const strength = doc.createExtension(KHRMaterialsEmissiveStrength);
  const mesh = doc.createMesh();
  for (const [name, m] of Object.entries(materials)) {
    const mine = quads.filter((q) => q.material === name);
    const positions: number[] = [];
    for (const q of mine) {
      const p = (a: number, b: number) =>
        [0, 1, 2].map((k) => q.corner[k] + a * q.u[k] + b * q.v[k]);
      // Two triangles wound as the quad: their normal is u × v.
      positions.push(...p(0, 0), ...p(1, 0), ...p(1, 1), ...p(0, 0), ...p(1, 1), ...p(0, 1));
    }
    const material = doc
      .createMaterial(name)
      .setBaseColorFactor([...m.albedo, 1])
      .setMetallicFactor(0)
      .setRoughnessFactor(1)
      .setExtension('KHR_materials_specular', specular.createSpecular().setSpecularFactor(0));
    if (m.emission) {
      const s = Math.max(...m.emission);
      material
        .setEmissiveFactor(m.emission.map((e) => e / s) as Vec3)
        .setExtension(
          'KHR_materials_emissive_strength',
          strength.createEmissiveStrength().setEmissiveStrength(s),
        );
    }
    mesh.addPrimitive(
      doc
        .createPrimitive()
        .setMaterial(material)
        .setAttribute(
          'POSITION',
          doc
            .createAccessor()
            .setType('VEC3')
            .setArray(new Float32Array(positions))
            .setBuffer(buffer),
        ),
    );
  }
  const scene = doc.createScene().addChild(doc.createNode().setMesh(mesh));
  doc.getRoot().setDefaultScene(scene);
  return doc;
}

const SPP = 64;

describe('the Cornell box as a glTF file converges to the Mitsuba reference', async () => {
  const original = loadScene('cornell');
  const ref = loadReference('cornell');
  const materials = original.materials as unknown as Record<string, DiffuseDesc>;
  const glb = await toGlb(cornellAsGltf(original.shapes as unknown as QuadShape[], materials));
  const scene = await sceneWithFiles(
    {
      format: 'pathwise-scene/1',
      name: 'Cornell box (glTF)',
      camera: original.camera,
      settings: original.settings,
      materials: {},
      shapes: [{ type: 'gltf', file: 'cornell.glb' }],
    },
    new Map([['cornell.glb', glb]]),
  );
  const img = renderSampled(scene, { width: ref.width, height: ref.height, spp: SPP, seed: 7 });

  it('is the same box: 18 quads as 36 triangles, glTF materials only', () => {
    expect(original.shapes.length).toBe(18);
    const shape = scene.shapes[0];
    expect(shape.type === 'gltf' && shape.data!.indices.length / 3).toBe(36);
  });

  it('has per-channel image means within 1% of the reference', () => {
    const ours = imageMean(img).mean;
    const theirs = referenceMean(ref);
    for (let c = 0; c < 3; c++) expect(Math.abs(ours[c] / theirs[c] - 1)).toBeLessThan(0.01);
  });

  it('matches the reference block by block within its own noise', () => {
    const { chi2, dof, maxAbsZ } = blockChiSquare(img, ref, 16, SPP / 65536);
    expect(dof).toBeGreaterThan(100);
    expect(chi2).toBeLessThan(chiSquareQuantile(dof, 3.09));
    expect(maxAbsZ).toBeLessThan(5.5);
  });

  it('rejects no sample', () => {
    expect(img.stats.rejected).toBe(0);
  });
});
