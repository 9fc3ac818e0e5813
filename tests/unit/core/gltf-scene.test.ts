/**
 * The `gltf` shape of pathwise-scene/1 end to end: validation of the shape, loading
 * its file through the scene's reader, compiling (one mesh per glTF material, glTF
 * material records, textures and vertex attributes in the packed scene), and what the
 * tracer does at glTF triangles — textures, alpha as stochastic opacity (paths and
 * shadow rays), normal maps — checked against answers known in closed form.
 */
import { Document } from '@gltf-transform/core';
import { KHRMaterialsSpecular } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { MATERIAL_GLTF, MATERIAL_STRIDE, M_TYPE } from '../../../src/core/bsdf/materials.ts';
import {
  PathTracer,
  RenderStats,
  SceneError,
  compileScene,
  packScene,
  parseScene,
  unpackScene,
  type Scene,
} from '../../../src/core/index.ts';
import { loadGltf } from '../../../src/core/gltf/load.ts';
import {
  docWith,
  memoryOptions,
  png,
  quadPrimitive,
  sceneWithFiles,
  toGlb,
} from '../../helpers/gltf.ts';

const CAMERA = { position: [0.5, 0.5, 3], target: [0.5, 0.5, 0], up: [0, 1, 0], fovY: 10 };

function sceneJson(shapes: unknown[], extra: Record<string, unknown> = {}) {
  return {
    format: 'pathwise-scene/1',
    camera: CAMERA,
    settings: { width: 8, height: 8, maxBounces: 4, spp: 16 },
    materials: { white: { type: 'diffuse', albedo: [0.5, 0.5, 0.5] } },
    shapes,
    environment: [1, 1, 1],
    ...extra,
  };
}

async function glbScene(doc: Document, extra: Record<string, unknown> = {}): Promise<Scene> {
  const files = new Map([['models/m.glb', await toGlb(doc)]]);
  return sceneWithFiles(sceneJson([{ type: 'gltf', file: 'models/m.glb' }], extra), files);
}

/** Mean radiance of pixel (x, y) over n samples. */
function pixel(scene: Scene, x: number, y: number, n: number, estimator?: 'bsdf'): number[] {
  const tracer = new PathTracer(compileScene(scene), {
    width: scene.settings.width,
    height: scene.settings.height,
    maxBounces: scene.settings.maxBounces,
    camera: scene.camera,
    estimator,
  });
  const stats = new RenderStats();
  const sum = [0, 0, 0];
  for (let s = 0; s < n; s++) {
    tracer.trace(x, y, s, stats);
    sum[0] += tracer.lr;
    sum[1] += tracer.lg;
    sum[2] += tracer.lb;
  }
  return sum.map((v) => v / n);
}

describe('the gltf shape', () => {
  it('validates its keys; it names no material', () => {
    const problems = (shape: unknown): string => {
      try {
        parseScene(JSON.stringify(sceneJson([shape])));
        return '';
      } catch (e) {
        expect(e).toBeInstanceOf(SceneError);
        return (e as Error).message;
      }
    };
    expect(problems({ type: 'gltf', file: 'a.glb' })).toBe('');
    expect(
      problems({
        type: 'gltf',
        file: 'a.GLTF',
        transform: [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1],
      }),
    ).toBe('');
    expect(problems({ type: 'gltf' })).toMatch(/shapes\[0\] needs file/);
    expect(problems({ type: 'gltf', file: 'a.obj' })).toMatch(
      /shapes\[0\]\.file must name a \.gltf or \.glb file, got "a\.obj"/,
    );
    expect(problems({ type: 'gltf', file: 'a.glb', material: 'white' })).toMatch(
      /shapes\[0\]\.material is not a known key/,
    );
    expect(problems({ type: 'gltf', file: 'a.glb', transform: [1, 2, 3] })).toMatch(
      /shapes\[0\]\.transform must be an array of 16 numbers/,
    );
  });

  it('a file that cannot be read or parsed is one error naming the shape and the file', async () => {
    const json = sceneJson([{ type: 'gltf', file: 'm.glb' }]);
    await expect(sceneWithFiles(json, new Map())).rejects.toThrow(
      /shapes\[0\]\.file "m\.glb": no such file/,
    );
    const bad = new Map([['m.glb', new Uint8Array([0x67, 0x6c, 0x54, 0x46, 2, 0, 0, 0])]]);
    await expect(sceneWithFiles(json, bad)).rejects.toThrow(/shapes\[0\]\.file "m\.glb": glTF: /);
  });

  it("counts against what is left of the scene's triangle limit, before reading geometry", async () => {
    const doc = new Document();
    docWith(doc, quadPrimitive(doc));
    const bytes = await toGlb(doc);
    const options = await memoryOptions();
    await expect(loadGltf(bytes, 'm.glb', { ...options, maxTriangles: 1 })).rejects.toThrow(
      "glTF: scene: instances 2 triangles, more than the 1 left of the scene's limit",
    );
    const scene = await glbScene(doc);
    const shape = scene.shapes[0];
    expect(shape.type === 'gltf' && shape.data!.indices.length / 3).toBe(2);
  });
});

describe('compiling glTF shapes', () => {
  it('makes one mesh per glTF material and MATERIAL_GLTF records after the named ones', async () => {
    const doc = new Document();
    const red = doc.createMaterial().setBaseColorFactor([1, 0, 0, 1]);
    const blue = doc.createMaterial().setBaseColorFactor([0, 0, 1, 1]);
    docWith(doc, quadPrimitive(doc).setMaterial(red), quadPrimitive(doc).setMaterial(blue));
    const scene = await glbScene(doc);
    const c = compileScene(scene);
    // 1 named material + 2 glTF ones + glTF's default material.
    expect(c.materials.length / MATERIAL_STRIDE).toBe(4);
    expect(c.materials[1 * MATERIAL_STRIDE + M_TYPE]).toBe(MATERIAL_GLTF);
    expect(Array.from(c.data.meshMaterial)).toEqual([1, 2]);
    expect(c.gltf).not.toBeNull();
    expect(c.gltf!.hasAlpha).toBe(false);
    // No texture reads texture coordinates, so none are kept.
    expect(c.gltf!.uv0).toBeNull();
  });

  it('costs nothing in a scene without glTF', () => {
    const c = compileScene(parseScene(JSON.stringify(sceneJson([]))));
    expect(c.gltf).toBeNull();
    for (const k of [
      'triUV0',
      'triUV1',
      'triColors',
      'triTangents',
      'gltfMaterials',
      'texels',
    ] as const) {
      expect(c.data[k].length).toBe(0);
    }
  });

  it('textures and attributes travel in the packed scene: bit-identical renders after unpacking', async () => {
    const doc = new Document();
    const tex = doc
      .createTexture()
      .setImage(png(2, 2, (x, y) => [x * 255, y * 255, 100, 255]))
      .setMimeType('image/png');
    docWith(
      doc,
      quadPrimitive(doc).setMaterial(
        doc.createMaterial().setBaseColorTexture(tex).setMetallicFactor(0),
      ),
    );
    const scene = await glbScene(doc);
    const c = compileScene(scene);
    expect(c.gltf!.textures.texels.length).toBe(2 * 2 * 4);
    for (const shared of [true, false]) {
      const u = unpackScene(packScene(c, shared));
      const opts = { width: 8, height: 8, maxBounces: 3, camera: scene.camera };
      const a = new PathTracer(c, opts);
      const b = new PathTracer(u, opts);
      const stats = new RenderStats();
      for (let p = 0; p < 64; p++) {
        a.trace(p % 8, p >> 3, p, stats);
        b.trace(p % 8, p >> 3, p, stats);
        expect([b.lr, b.lg, b.lb]).toEqual([a.lr, a.lg, a.lb]);
      }
    }
  });
});

describe('glTF materials in the tracer', () => {
  // The camera sees the middle of a frontal unit quad (u, v ∈ [0.24, 0.76]) under a
  // white environment of radiance 1. A glTF surface without specular layer (metallic 0,
  // KHR_materials_specular 0) is Lambert's: with one bounce and BSDF sampling every
  // sample reads exactly the base colour at its hit point.
  it('base colour texture: each sample reads the bilinear texel at its hit', async () => {
    const doc = new Document();
    const tex = doc
      .createTexture()
      .setImage(png(2, 1, (x) => (x === 0 ? [255, 0, 0, 255] : [0, 255, 0, 255])))
      .setMimeType('image/png');
    const spec = doc.createExtension(KHRMaterialsSpecular);
    const mat = doc
      .createMaterial()
      .setBaseColorTexture(tex)
      .setMetallicFactor(0)
      .setRoughnessFactor(1);
    mat.setExtension('KHR_materials_specular', spec.createSpecular().setSpecularFactor(0));
    docWith(doc, quadPrimitive(doc).setMaterial(mat));
    const scene = await glbScene(doc, { settings: { width: 8, height: 8, maxBounces: 1, spp: 1 } });
    // Columns 1 and 6 see u ≈ 0.34 and 0.66: mostly the red (left) and the green
    // (right) texel, and red + green is 1 everywhere (bilinear weights sum to 1).
    const left = pixel(scene, 1, 4, 32, 'bsdf');
    const right = pixel(scene, 6, 4, 32, 'bsdf');
    expect(left[2]).toBe(0);
    expect(right[2]).toBe(0);
    expect(left[0]).toBeGreaterThan(0.5);
    expect(right[1]).toBeGreaterThan(0.5);
    expect(left[0] + left[1]).toBeCloseTo(1, 9);
    expect(right[0] + right[1]).toBeCloseTo(1, 9);
  });
});
