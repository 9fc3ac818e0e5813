/**
 * Meshes and environment maps in the browser demo (Chromium): the Sky preset (a mesh
 * under a map, its files served as bundled assets) renders bit for bit what the Node
 * core renders; a scene loaded by URL reads its files relative to that URL (what the
 * widget's `src` does); a scene opened together with its files uses the files given.
 */
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import type { Scene } from '../../src/core/index.ts';
import { loadSceneWithFiles } from '../helpers/render.ts';
import { PASSES, SEED, SIZE, fixed, useDemo } from './context.ts';
import { bitDifferences, openDemo, readLinear, root, waitForSpp } from './harness.ts';
import { nodeSceneRender } from './node-reference.ts';

const ctx = useDemo();
const render = (scene: Scene): Float32Array => nodeSceneRender(scene, SIZE, SIZE, SEED, PASSES);

describe('meshes and environment maps in the demo (Chromium)', () => {
  it('renders the Sky preset (a mesh under a map) bit for bit like the Node core', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}&scene=sky`);
    await waitForSpp(page, PASSES);
    const name = await page.evaluate(() => (window as any).__pathwise.controller.scene.name);
    expect(name).toBe('Copper torus under the sky');
    const image = await readLinear(page);
    const reference = render(await loadSceneWithFiles('metal-sky'));
    expect(bitDifferences(image.rgb, reference)).toBe(0);
    await page.close();
  });

  it('loads a scene by URL with its files relative to that URL', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}`);
    await waitForSpp(page, 1);
    await page.evaluate(() => (window as any).__pathwise.controller.load('/scenes/metal-sky.json'));
    await page.waitForFunction(
      () => (window as any).__pathwise.controller.scene.name === 'Copper torus under the sky',
    );
    await waitForSpp(page, PASSES);
    const reference = render(await loadSceneWithFiles('metal-sky'));
    expect(bitDifferences((await readLinear(page)).rgb, reference)).toBe(0);
    await page.close();
  });

  it('opens a scene together with its files, and says which file is missing', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-drop-'));
    const scene = JSON.parse(readFileSync(join(root, 'scenes/metal-sky.json'), 'utf8'));
    scene.name = 'Dropped torus';
    writeFileSync(join(dir, 'scene.json'), JSON.stringify(scene));
    writeFileSync(join(dir, 'torus.obj'), readFileSync(join(root, 'scenes/meshes/torus.obj')));
    writeFileSync(join(dir, 'sky.hdr'), readFileSync(join(root, 'scenes/sky.hdr')));
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}`);
    await waitForSpp(page, 1);
    await page.setInputFiles('#file', [join(dir, 'scene.json'), join(dir, 'torus.obj')]);
    await page.waitForFunction(() =>
      document.getElementById('error')!.textContent!.startsWith('scene.json:'),
    );
    expect(await page.textContent('#error')).toBe(
      'scene.json: environment.file "sky.hdr": it was not among the dropped files; ' +
        'drop the scene together with sky.hdr',
    );
    await page.setInputFiles('#file', [
      join(dir, 'scene.json'),
      join(dir, 'torus.obj'),
      join(dir, 'sky.hdr'),
    ]);
    await page.waitForFunction(
      () => (window as any).__pathwise.controller.scene.name === 'Dropped torus',
    );
    await waitForSpp(page, PASSES);
    const reference = render(await loadSceneWithFiles('metal-sky'));
    expect(bitDifferences((await readLinear(page)).rgb, reference)).toBe(0);
    await page.close();
  });
});
