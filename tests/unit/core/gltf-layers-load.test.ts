/**
 * KHR_materials_clearcoat, KHR_materials_sheen, KHR_materials_unlit and
 * KHR_materials_pbrSpecularGlossiness from file to pixel: files made with glTF-Transform's
 * Document API load without an "ignored" warning, their numbers and textures land in
 * the material table and in the per-hit ShadingParams (layers-fill.ts), an unlit quad
 * shows exactly its base colour to the camera, and the reductions (clearcoat 0, black
 * sheen) render bit-identically to the plain material.
 */
import { Document, type Material } from '@gltf-transform/core';
import {
  KHRMaterialsClearcoat,
  KHRMaterialsPBRSpecularGlossiness,
  KHRMaterialsSheen,
  KHRMaterialsUnlit,
} from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { ShadingParams } from '../../../src/core/bsdf/shading.ts';
import {
  GM_BASE,
  GM_CLEARCOAT,
  GM_CLEARCOAT_NORMAL_SCALE,
  GM_CLEARCOAT_ROUGHNESS,
  GM_IOR,
  GM_METALLIC,
  GM_ROUGHNESS,
  GM_SHEEN_COLOR,
  GM_SHEEN_ROUGHNESS,
  GM_SPECULAR_COLOR,
  GM_STRIDE,
  GM_UNLIT,
  hasTexture,
  TEX_BASE_COLOR,
  TEX_CLEARCOAT_NORMAL,
  TEX_METALLIC_ROUGHNESS,
  TEX_SHEEN_COLOR,
  TEX_SPEC_GLOSS,
} from '../../../src/core/gltf-material/material-table.ts';
import { SHAPE_TRIANGLE } from '../../../src/core/geometry/ray.ts';
import { validateGltfJson } from '../../../src/core/gltf/validate.ts';
import { fillGltfShading, HitAttributes } from '../../../src/core/gltf-material/shading-fill.ts';
import { compileScene, PathTracer, RenderStats, type Scene } from '../../../src/core/index.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import {
  docWith,
  loadGlb,
  memoryOptions,
  png,
  quadPrimitive,
  sceneWithFiles,
  toGlb,
  toGltfFiles,
} from '../../helpers/gltf.ts';
import { drawLayersMaterial } from '../../validation/gltf-draw-layers.ts';
import { Rng } from '../../validation/rng.ts';

function texture(doc: Document, rgba: number[]) {
  return doc
    .createTexture()
    .setImage(png(2, 2, () => rgba))
    .setMimeType('image/png');
}

/** A document with one quad per material that `make` returns. */
function docOf(make: (doc: Document) => Material[]): Document {
  const doc = new Document();
  doc.createBuffer();
  const mats = make(doc);
  docWith(doc, ...mats.map((m) => quadPrimitive(doc).setMaterial(m)));
  return doc;
}

describe('the layer extensions: parsing', () => {
  it('fills the table and the shading record, with no extension ignored', async () => {
    const doc = docOf((d) => {
      const cc = d.createExtension(KHRMaterialsClearcoat);
      const sh = d.createExtension(KHRMaterialsSheen);
      const ul = d.createExtension(KHRMaterialsUnlit).setRequired(true);
      const sg = d.createExtension(KHRMaterialsPBRSpecularGlossiness);
      const coat = d.createMaterial('coat').setExtension(
        'KHR_materials_clearcoat',
        cc
          .createClearcoat()
          .setClearcoatFactor(0.7)
          .setClearcoatRoughnessFactor(0.2)
          .setClearcoatNormalScale(0.5)
          .setClearcoatNormalTexture(texture(d, [255, 128, 255, 255])),
      );
      const sheen = d.createMaterial('sheen').setExtension(
        'KHR_materials_sheen',
        sh
          .createSheen()
          .setSheenColorFactor([0.5, 0.25, 0])
          .setSheenRoughnessFactor(0.4)
          .setSheenColorTexture(texture(d, [255, 255, 255, 255])),
      );
      const unlit = d
        .createMaterial('unlit')
        .setBaseColorFactor([0.2, 0.5, 0.8, 1])
        .setExtension('KHR_materials_unlit', ul.createUnlit());
      const specGloss = d
        .createMaterial('specGloss')
        .setMetallicRoughnessTexture(texture(d, [0, 0, 0, 255]))
        .setExtension(
          'KHR_materials_pbrSpecularGlossiness',
          sg
            .createPBRSpecularGlossiness()
            .setDiffuseFactor([0.2, 0.4, 0.6, 1])
            .setSpecularFactor([0.1, 0.2, 0.3])
            .setGlossinessFactor(0.8)
            // Specular RGB white (sRGB 255), glossiness A = 0.5 (linear).
            .setSpecularGlossinessTexture(texture(d, [255, 255, 255, 128])),
        );
      return [coat, sheen, unlit, specGloss];
    });
    const model = await loadGlb(doc);
    expect(model.warnings.filter((w) => /ignored|not supported/.test(w))).toEqual([]);
    const t = model.materials;
    const row = (m: number, f: number): number => t[m * GM_STRIDE + f];
    expect(row(0, GM_CLEARCOAT)).toBeCloseTo(0.7, 6);
    expect(row(0, GM_CLEARCOAT_ROUGHNESS)).toBeCloseTo(0.2, 6);
    expect(row(0, GM_CLEARCOAT_NORMAL_SCALE)).toBe(0.5);
    expect(hasTexture(t, 0, TEX_CLEARCOAT_NORMAL)).toBe(true);
    expect([0, 1, 2].map((c) => row(1, GM_SHEEN_COLOR + c))).toEqual([0.5, 0.25, 0]);
    expect(row(1, GM_SHEEN_ROUGHNESS)).toBeCloseTo(0.4, 6);
    expect(hasTexture(t, 1, TEX_SHEEN_COLOR)).toBe(true);
    expect(row(2, GM_UNLIT)).toBe(1);
    expect(row(0, GM_UNLIT)).toBe(0);
    expect([0, 1, 2].map((c) => row(3, GM_BASE + c))).toEqual([0.2, 0.4, 0.6]);
    expect(row(3, GM_METALLIC)).toBe(0);
    expect(row(3, GM_ROUGHNESS)).toBeCloseTo(0.2, 6);
    expect(row(3, GM_IOR)).toBe(1e6);
    expect([0, 1, 2].map((c) => row(3, GM_SPECULAR_COLOR + c))).toEqual([0.1, 0.2, 0.3]);
    expect(hasTexture(t, 3, TEX_SPEC_GLOSS)).toBe(true);
    // The metallic–roughness texture of a specular–glossiness material is not read.
    expect(hasTexture(t, 3, TEX_METALLIC_ROUGHNESS)).toBe(false);
    expect(hasTexture(t, 3, TEX_BASE_COLOR)).toBe(false);

    const hit = new HitAttributes();
    const sp = new ShadingParams();
    fillGltfShading(t, model.textures, 0, hit, sp);
    expect(sp.clearcoat).toBeCloseTo(0.7, 6);
    expect(sp.clearcoatAlpha).toBeCloseTo(0.04, 6);
    // Texel (1, 128/255, 1) with scale 0.5: (0.5, ~0, 1), normalised.
    expect(sp.ccnx).toBeCloseTo(0.5 / Math.hypot(0.5, 1), 2);
    expect(sp.ccnz).toBeCloseTo(1 / Math.hypot(0.5, 1), 2);
    expect(sp.unlit).toBe(false);
    fillGltfShading(t, model.textures, 1, hit, sp);
    expect([sp.sheenR, sp.sheenG, sp.sheenB]).toEqual([0.5, 0.25, 0]);
    expect(sp.sheenRoughness).toBeCloseTo(0.4, 6);
    // Every field at every hit: the coat of material 0 is gone.
    expect([sp.clearcoat, sp.ccnx, sp.ccny, sp.ccnz]).toEqual([0, 0, 0, 1]);
    fillGltfShading(t, model.textures, 2, hit, sp);
    expect(sp.unlit).toBe(true);
    expect([sp.emR, sp.emG, sp.emB]).toEqual([0.2, 0.5, 0.8]);
    expect([sp.sheenR, sp.sheenG, sp.sheenB]).toEqual([0, 0, 0]);
    fillGltfShading(t, model.textures, 3, hit, sp);
    expect(sp.unlit).toBe(false);
    expect(sp.metallic).toBe(0);
    // roughness = 1 − 0.8 × 128/255.
    const rough = 1 - 0.8 * (128 / 255);
    expect(sp.alpha).toBeCloseTo(rough * rough, 3);
    expect(sp.specR).toBeCloseTo(0.1, 6);
  });

  it('refuses a required extension that is not listed as used (glTF 2.0 §3.12)', () => {
    const json = { asset: { version: '2.0' }, extensionsRequired: ['KHR_materials_unlit'] };
    expect(() => validateGltfJson(json)).toThrow(
      /extensionsRequired: "KHR_materials_unlit" is not listed in extensionsUsed/,
    );
    expect(() =>
      validateGltfJson({ ...json, extensionsUsed: ['KHR_materials_unlit'] }),
    ).not.toThrow();
  });

  it('refuses a factor out of range, naming its JSON path', async () => {
    const doc = docOf((d) => [
      d
        .createMaterial()
        .setExtension(
          'KHR_materials_clearcoat',
          d.createExtension(KHRMaterialsClearcoat).createClearcoat().setClearcoatFactor(1.5),
        ),
    ]);
    await expect(loadGlb(doc)).rejects.toThrow(
      /materials\[0\]\.extensions\.KHR_materials_clearcoat\.clearcoatFactor/,
    );
  });
});

const CAMERA = { position: [0.5, 0.5, 3], target: [0.5, 0.5, 0], up: [0, 1, 0], fovY: 10 };

async function quadScene(doc: Document): Promise<Scene> {
  const files = new Map([['m.glb', await toGlb(doc)]]);
  return sceneWithFiles(
    {
      format: 'pathwise-scene/1',
      camera: CAMERA,
      settings: { width: 4, height: 4, maxBounces: 4, spp: 1 },
      materials: {},
      shapes: [{ type: 'gltf', file: 'm.glb' }],
      environment: [1, 1, 1],
    },
    files,
  );
}

/** Every sample of every pixel of a 4×4 render, in order. */
function samples(scene: Scene, n: number): number[] {
  const tracer = new PathTracer(compileScene(scene), {
    width: 4,
    height: 4,
    maxBounces: 4,
    camera: scene.camera,
  });
  const stats = new RenderStats();
  const out: number[] = [];
  for (let y = 0; y < 4; y++)
    for (let x = 0; x < 4; x++)
      for (let s = 0; s < n; s++) {
        tracer.trace(x, y, s, stats);
        out.push(tracer.lr, tracer.lg, tracer.lb);
      }
  return out;
}

describe('the layer extensions: rendering', () => {
  it('an unlit quad shows exactly its base colour', async () => {
    const doc = docOf((d) => [
      d
        .createMaterial()
        .setBaseColorFactor([0.2, 0.5, 0.8, 1])
        .setExtension('KHR_materials_unlit', d.createExtension(KHRMaterialsUnlit).createUnlit()),
    ]);
    const scene = await quadScene(doc);
    // Not a light: nothing aims shadow rays at it.
    const lights = compileScene(scene).lights;
    expect(
      lights === null ? 0 : Array.from(lights.kind).filter((k) => k === SHAPE_TRIANGLE).length,
    ).toBe(0);
    const v = samples(scene, 4);
    for (let i = 0; i < v.length; i += 3)
      expect([v[i], v[i + 1], v[i + 2]]).toEqual([0.2, 0.5, 0.8]);
  });

  it('clearcoat 0 and black sheen render bit-identically to the plain material', async () => {
    const plain = (d: Document) =>
      d
        .createMaterial()
        .setBaseColorFactor([0.8, 0.4, 0.2, 1])
        .setRoughnessFactor(0.4)
        .setMetallicFactor(0);
    const base = samples(await quadScene(docOf((d) => [plain(d)])), 8);
    const coated = samples(
      await quadScene(
        docOf((d) => [
          plain(d)
            .setExtension(
              'KHR_materials_clearcoat',
              d
                .createExtension(KHRMaterialsClearcoat)
                .createClearcoat()
                .setClearcoatFactor(0)
                .setClearcoatRoughnessFactor(0.5),
            )
            .setExtension(
              'KHR_materials_sheen',
              d
                .createExtension(KHRMaterialsSheen)
                .createSheen()
                .setSheenColorFactor([0, 0, 0])
                .setSheenRoughnessFactor(0.5),
            ),
        ]),
      ),
      8,
    );
    expect(coated).toEqual(base);
    // …and a real coat and sheen change the picture, finitely.
    const layered = samples(
      await quadScene(
        docOf((d) => [
          plain(d)
            .setExtension(
              'KHR_materials_clearcoat',
              d.createExtension(KHRMaterialsClearcoat).createClearcoat().setClearcoatFactor(1),
            )
            .setExtension(
              'KHR_materials_sheen',
              d
                .createExtension(KHRMaterialsSheen)
                .createSheen()
                .setSheenColorFactor([1, 1, 1])
                .setSheenRoughnessFactor(0.5),
            ),
        ]),
      ),
      8,
    );
    expect(layered.every(Number.isFinite)).toBe(true);
    expect(layered).not.toEqual(base);
  });
});

describe("drawLayersMaterial (the validation suite's layered materials)", () => {
  it('draws glTF material JSON that loads with no warning, onto the furnace grids', async () => {
    const doc = docOf((d) => [d.createMaterial()]);
    const files = await toGltfFiles(doc, 'm');
    const base = JSON.parse(new TextDecoder().decode(files.get('m.gltf')!));
    const g = new Rng(25);
    for (let k = 0; k < 12; k++) {
      const mat = drawLayersMaterial(g);
      const cc = mat.extensions.KHR_materials_clearcoat;
      const sh = mat.extensions.KHR_materials_sheen;
      expect([0, 0.5, 1]).toContain(cc.clearcoatFactor);
      expect([0, 0.3, 0.7, 1]).toContain(cc.clearcoatRoughnessFactor);
      for (const c of sh.sheenColorFactor) expect([0, 0.5, 1]).toContain(c);
      expect([0.05, 0.3, 0.6, 1]).toContain(sh.sheenRoughnessFactor);
      const json = {
        ...base,
        materials: [mat],
        extensionsUsed: ['KHR_materials_clearcoat', 'KHR_materials_sheen'],
      };
      files.set('m.gltf', new TextEncoder().encode(JSON.stringify(json)));
      const model = await loadGltf(files.get('m.gltf')!, 'm.gltf', await memoryOptions(files));
      expect(model.warnings).toEqual([]);
      expect(model.materials[GM_CLEARCOAT]).toBe(cc.clearcoatFactor);
      expect(model.materials[GM_SHEEN_ROUGHNESS]).toBe(sh.sheenRoughnessFactor);
    }
  });
});
