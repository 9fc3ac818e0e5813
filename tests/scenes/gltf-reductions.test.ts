/**
 * Reductions of the glTF material that must hold in a whole render (issue 13): one
 * scene modelled two ways — a sphere as a glTF file with a glTF material, and the same
 * triangles as a `mesh` shape with the scene format's material — rendered with
 * independent seeds and compared by a block test (4×4-pixel block means z-scored by
 * both renders' own sample variances, independent samples; Σz² below the χ² quantile
 * at p = 0.001 and no block beyond |z| = 5, so about 2e-3 false alarms per case, fixed
 * seeds; a deliberately wrong pair shows the test can fail):
 * - metallic 1 is the conductor with F0 = baseColor (rough and smooth);
 * - a dielectric layer without specular (KHR_materials_specular 0) is the diffuse
 *   material;
 * - transmission 1 with roughness 0 on a volume (KHR_materials_volume thicknessFactor > 0)
 *   is the smooth dielectric of the same index.
 * The scene: the sphere over a diffuse floor, under a constant environment, and for
 * the opaque cases also an emissive quad, so both next-event estimation and BSDF
 * sampling (with MIS) take part.
 */
import { Document } from '@gltf-transform/core';
import {
  KHRMaterialsIOR,
  KHRMaterialsSpecular,
  KHRMaterialsTransmission,
  KHRMaterialsVolume,
} from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import type { Scene } from '../../src/core/index.ts';
import { docWith, meshPrimitive, sceneWithFiles, toGlb } from '../helpers/gltf.ts';
import { icosphere } from '../helpers/mesh-gen.ts';
import { blockChiSquarePair, chiSquareQuantile, renderSampled } from '../helpers/render.ts';

const SIZE = 32;
const SPP = 64;

// The sphere's triangles in float32 (what a glTF file stores), with smooth normals.
const sphere = icosphere(3, 0.6, [0, 0.6, 0]);
const positions = Array.from(Float32Array.from(sphere.positions));
const normals: number[] = [];
for (let i = 0; i < positions.length; i += 3) {
  const x = positions[i],
    y = positions[i + 1] - 0.6,
    z = positions[i + 2];
  const l = Math.hypot(x, y, z);
  normals.push(x / l, y / l, z / l);
}
const indices = Array.from(sphere.indices);

function baseScene(light: boolean) {
  return {
    format: 'pathwise-scene/1',
    camera: { position: [0, 1.4, 3], target: [0, 0.5, 0], up: [0, 1, 0], fovY: 35 },
    settings: { width: SIZE, height: SIZE, maxBounces: 6, spp: SPP },
    materials: {
      floor: { type: 'diffuse', albedo: [0.7, 0.7, 0.7] },
      lamp: { type: 'diffuse', albedo: [0, 0, 0], emission: [6, 6, 6] },
    },
    shapes: [
      { type: 'quad', corner: [-3, 0, 3], u: [6, 0, 0], v: [0, 0, -6], material: 'floor' },
      ...(light
        ? [
            {
              type: 'quad',
              corner: [-0.5, 2.5, -0.5],
              u: [0, 0, 1],
              v: [1, 0, 0],
              material: 'lamp',
            },
          ]
        : []),
    ],
    environment: [0.3, 0.35, 0.4],
  };
}

/** The sphere as a glTF file whose material `setup` makes. */
async function gltfVersion(
  light: boolean,
  setup: (doc: Document) => ReturnType<Document['createMaterial']>,
): Promise<Scene> {
  const doc = new Document();
  const prim = meshPrimitive(doc, positions, indices, { normals }).setMaterial(setup(doc));
  const files = new Map([['sphere.glb', await toGlb(docWith(doc, prim))]]);
  const json = baseScene(light);
  json.shapes.push({ type: 'gltf', file: 'sphere.glb' } as never);
  return sceneWithFiles(json, files);
}

/** The sphere as a mesh with a scene-format material. */
async function meshVersion(light: boolean, material: Record<string, unknown>): Promise<Scene> {
  const json = baseScene(light) as ReturnType<typeof baseScene> & {
    materials: Record<string, unknown>;
  };
  json.materials.sphere = material;
  json.shapes.push({ type: 'mesh', material: 'sphere', positions, indices, normals } as never);
  return sceneWithFiles(json, new Map());
}

async function compare(a: Promise<Scene>, b: Promise<Scene>) {
  // Independent samples, so that the sample variances are the errors' (see renderSampled).
  const ia = renderSampled(await a, { spp: SPP, seed: 11, sampler: 'independent' });
  const ib = renderSampled(await b, { spp: SPP, seed: 12, sampler: 'independent' });
  expect(ia.stats.rejected + ib.stats.rejected).toBe(0);
  return blockChiSquarePair(ia, ib, 4);
}

async function expectSameImage(a: Promise<Scene>, b: Promise<Scene>): Promise<void> {
  const { chi2, dof, maxAbsZ } = await compare(a, b);
  expect(dof).toBeGreaterThan(150);
  expect(chi2).toBeLessThan(chiSquareQuantile(dof, 3.09));
  expect(maxAbsZ).toBeLessThan(5);
}

const BASE = [0.9, 0.6, 0.3] as const;

const metal = (base: readonly number[]) => (doc: Document) =>
  doc
    .createMaterial()
    .setBaseColorFactor([base[0], base[1], base[2], 1])
    .setMetallicFactor(1)
    .setRoughnessFactor(0.3);

describe('glTF material reductions, rendered both ways', () => {
  it('has power: a base colour 5% off in red is rejected', async () => {
    // Measured when written: Σz² ≈ 1000 against a quantile of 226 (164 dof).
    const { chi2, dof } = await compare(
      gltfVersion(true, metal(BASE)),
      meshVersion(true, { type: 'conductor', color: [0.85, 0.6, 0.3], roughness: 0.3 }),
    );
    expect(chi2).toBeGreaterThan(chiSquareQuantile(dof, 3.09));
  });

  for (const roughness of [0.3, 0]) {
    it(`metallic 1 is the conductor with F0 = baseColor (roughness ${roughness})`, () =>
      expectSameImage(
        gltfVersion(true, (doc) => metal(BASE)(doc).setRoughnessFactor(roughness)),
        meshVersion(true, { type: 'conductor', color: BASE, roughness }),
      ));
  }

  it('no specular layer is the diffuse material', () =>
    expectSameImage(
      gltfVersion(true, (doc) => {
        const m = doc
          .createMaterial()
          .setBaseColorFactor([...BASE, 1] as [number, number, number, number])
          .setMetallicFactor(0)
          .setRoughnessFactor(0.5);
        const ext = doc.createExtension(KHRMaterialsSpecular);
        return m.setExtension('KHR_materials_specular', ext.createSpecular().setSpecularFactor(0));
      }),
      meshVersion(true, { type: 'diffuse', albedo: BASE }),
    ));

  it('transmission 1 with roughness 0 on a volume is the smooth dielectric', () =>
    expectSameImage(
      gltfVersion(false, (doc) => {
        const m = doc
          .createMaterial()
          .setBaseColorFactor([...BASE, 1] as [number, number, number, number])
          .setMetallicFactor(0)
          .setRoughnessFactor(0);
        const tr = doc.createExtension(KHRMaterialsTransmission).createTransmission();
        const ior = doc.createExtension(KHRMaterialsIOR).createIOR().setIOR(1.5);
        const volume = doc.createExtension(KHRMaterialsVolume).createVolume().setThicknessFactor(1);
        m.setExtension('KHR_materials_transmission', tr.setTransmissionFactor(1));
        m.setExtension('KHR_materials_volume', volume);
        return m.setExtension('KHR_materials_ior', ior);
      }),
      meshVersion(false, { type: 'dielectric', ior: 1.5, color: BASE }),
    ));
});
