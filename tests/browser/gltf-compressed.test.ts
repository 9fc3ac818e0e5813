/**
 * Compressed models in the browser (Chromium, the demo served by Vite): a meshopt `.glb`
 * and a Draco `.gltf` with its buffer, dropped on the demo, load in the model worker with
 * the browser's decoders (gltf-browser.ts: meshopt's module and Draco's glue as lazy
 * chunks, Draco's WebAssembly as an asset) and render bit for bit what the Node core
 * renders for the same bare model with the Node decoders; the Draco one again from the
 * production build (Vite's CommonJS conversion of the glue, the hashed wasm asset).
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { ROOT } from '../helpers/render.ts';
import { PASSES, SEED, SIZE, fixed, useDemo } from './context.ts';
import { bitDifferences, openDemo, readLinear, startPreviewServer, waitForSpp } from './harness.ts';
import { nodeModelRender } from './node-reference.ts';

const ctx = useDemo();
const FIXTURES = join(ROOT, 'tests/fixtures/compressed');

const nodeReference = (file: string): Promise<Float32Array> =>
  nodeModelRender(
    new Uint8Array(readFileSync(join(FIXTURES, file))),
    file,
    FIXTURES,
    SIZE,
    SIZE,
    SEED,
    PASSES,
  );

describe('compressed glTF in the demo (Chromium)', () => {
  it('a meshopt .glb and a Draco .gltf: the Node core image bit for bit', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}`);
    await waitForSpp(page, 1);
    for (const files of [['BoxMeshopt.glb'], ['Box.gltf', 'Box.bin']]) {
      await page.setInputFiles(
        '#file',
        files.map((f) => join(FIXTURES, f)),
      );
      await page.waitForFunction(
        (name) => (window as any).__pathwise.controller.scene.name === name,
        files[0],
      );
      await waitForSpp(page, PASSES);
      expect(await page.textContent('#error')).toBe('');
      const reference = await nodeReference(files[0]);
      expect(bitDifferences((await readLinear(page)).rgb, reference)).toBe(0);
    }
    await page.close();
  });

  it('the production build: the Draco glue as a CommonJS chunk, its WebAssembly as an asset', async () => {
    const built = await startPreviewServer();
    try {
      const page = await openDemo(ctx.browser, built.url, `${fixed}&spp=${PASSES}`);
      await waitForSpp(page, 1);
      await page.setInputFiles(
        '#file',
        ['Box.gltf', 'Box.bin'].map((f) => join(FIXTURES, f)),
      );
      await page.waitForFunction(
        () => (window as any).__pathwise.controller.scene.name === 'Box.gltf',
      );
      await waitForSpp(page, PASSES);
      expect(await page.textContent('#error')).toBe('');
      expect(bitDifferences((await readLinear(page)).rgb, await nodeReference('Box.gltf'))).toBe(0);
      await page.close();
    } finally {
      await built.server.close();
    }
  });
});
