/**
 * Compressed textures in the browser (Chromium): a `.glb` whose textures use
 * EXT_texture_webp (decoded by createImageBitmap) and KHR_texture_basisu (the vendored
 * Basis Universal transcoder, fetched by the model worker) renders bit for bit what the
 * Node core renders with libwebp and the same transcoder: Chromium's libwebp and
 * @jsquash's give the same texels for this (opaque, lossy) WebP, and the transcoder is
 * the same WebAssembly. (An image with alpha below 255 would not compare exactly: the
 * browser's decode goes through a canvas, which stores premultiplied alpha; this holds
 * for PNG as much as for WebP.)
 */
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { EXTTextureWebP, KHRTextureBasisu } from '@gltf-transform/extensions';
import { describe, expect, it } from 'vitest';
import { addFloor, docWith, quadPrimitive, toGlb } from '../helpers/gltf.ts';
import { ROOT } from '../helpers/render.ts';
import { PASSES, SEED, SIZE, fixed, useDemo } from './context.ts';
import { bitDifferences, openDemo, readLinear, waitForSpp } from './harness.ts';
import { nodeModelRender } from './node-reference.ts';

const ctx = useDemo();
const fixture = (name: string) =>
  new Uint8Array(readFileSync(join(ROOT, 'tests/fixtures/compressed-textures', name)));

/** A WebP-textured quad in front of a KTX2-textured floor; both extensions required. */
function model(): Document {
  const doc = new Document();
  doc.createExtension(EXTTextureWebP).setRequired(true);
  doc.createExtension(KHRTextureBasisu).setRequired(true);
  const webp = doc.createTexture().setImage(fixture('test-lossy.webp')).setMimeType('image/webp');
  const ktx2 = doc.createTexture().setImage(fixture('2d_uastc.ktx2')).setMimeType('image/ktx2');
  const quad = doc.createMaterial().setBaseColorTexture(webp).setMetallicFactor(0);
  const floor = doc.createMaterial().setBaseColorTexture(ktx2).setMetallicFactor(0);
  docWith(doc, quadPrimitive(doc).setMaterial(quad));
  addFloor(doc, floor);
  return doc;
}

describe('compressed glTF textures in the demo (Chromium)', () => {
  it('WebP and KTX2: the Node core image bit for bit, no warning', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-gltf-compressed-'));
    const glb = await toGlb(model());
    writeFileSync(join(dir, 'tiles.glb'), glb);
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}`);
    await waitForSpp(page, 1);
    await page.evaluate(() => {
      const w = window as any;
      w.warnings = null;
      w.__pathwise.controller.addEventListener(
        'warning',
        (e: CustomEvent) => (w.warnings = e.detail.messages),
      );
    });
    await page.setInputFiles('#file', [join(dir, 'tiles.glb')]);
    await page.waitForFunction(
      () => (window as any).__pathwise.controller.scene.name === 'tiles.glb',
    );
    await waitForSpp(page, PASSES);
    expect(await page.textContent('#error')).toBe('');
    expect(await page.evaluate(() => (window as any).warnings)).toBe(null);
    const reference = await nodeModelRender(glb, 'tiles.glb', dir, SIZE, SIZE, SEED, PASSES);
    expect(bitDifferences((await readLinear(page)).rgb, reference)).toBe(0);
    await page.close();
  });
});
