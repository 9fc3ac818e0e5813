/**
 * Two small published models that use the layer extensions (tests/fixtures/gltf-layers,
 * with their licences): UnlitTest.glb requires KHR_materials_unlit, BoxTextured-SpecGloss
 * uses KHR_materials_pbrSpecularGlossiness. Each loads with no extension ignored and
 * renders finite and not blank as a bare model (studio lighting, framed camera).
 */
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import type { GltfModel } from '../../../src/core/scene/format/gltf-model.ts';
import { loadBareModel } from '../../../src/core/scene/load/bare-scene.ts';
import { memoryOptions } from '../../helpers/gltf.ts';
import { renderSampled } from '../../helpers/render.ts';

const DIR = fileURLToPath(new URL('../../fixtures/gltf-layers/', import.meta.url));

async function load(file: string, dir = '') {
  const files = new Map<string, Uint8Array>();
  for (const f of readdirSync(DIR + dir).filter((f) => statSync(DIR + dir + f).isFile()))
    files.set(dir + f, new Uint8Array(readFileSync(DIR + dir + f)));
  const options = await memoryOptions(files);
  return loadBareModel(files.get(dir + file)!, dir + file, options.reader, {
    width: 24,
    height: 24,
    generateTangents: options.generateTangents,
  });
}

function warnings(scene: Awaited<ReturnType<typeof load>>): string[] {
  return ((scene.shapes[0] as { data: GltfModel }).data as GltfModel).warnings;
}

describe('published models with the layer extensions', () => {
  for (const [file, dir] of [
    ['UnlitTest.glb', ''],
    ['BoxTextured.gltf', 'BoxTextured-SpecGloss/'],
  ]) {
    it(`${file}: no extension ignored, finite and not blank`, async () => {
      const scene = await load(file, dir);
      expect(warnings(scene).filter((w) => /extension/.test(w))).toEqual([]);
      const image = renderSampled(scene, { spp: 2 });
      expect(image.stats.rejected).toBe(0);
      expect(Array.from(image.mean).every(Number.isFinite)).toBe(true);
      expect(Math.max(...image.mean)).toBeGreaterThan(0.05);
    });
  }
});
