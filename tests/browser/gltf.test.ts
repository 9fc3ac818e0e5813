/**
 * glTF models in the browser (Chromium): a `.gltf` opened in the demo together with its
 * buffer and images renders bit for bit what the Node core renders for the same bare
 * model (images decoded by createImageBitmap there, by the pure-JS decoders here;
 * MikkTSpace tangents from the same WebAssembly), with its load stages reported and
 * the extension it ignores shown as a note; a `.glb`, and the same model as a `.gltf`
 * with its buffer and images fetched relative to it (the same bits), given as the widget's `src`
 * renders on pages with and without cross-origin isolation (shared and transferred
 * textures); a broken model is one message naming the file. Models load in the model
 * worker (parse, decode, BVH), not on the page's thread.
 */
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { Document } from '@gltf-transform/core';
import { KHRXMP } from '@gltf-transform/extensions';
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { addFloor, docWith, png, quadPrimitive, toGlb, toGltfFiles } from '../helpers/gltf.ts';
import { PASSES, SEED, SIZE, fixed, useDemo } from './context.ts';
import { bitDifferences, openDemo, readLinear, startDemoServer, waitForSpp } from './harness.ts';
import { nodeModelRender } from './node-reference.ts';

const ctx = useDemo();

/**
 * A checker-textured, normal-mapped quad (no tangents: MikkTSpace makes them) in front
 * of a floor placed by a TRS node, with metadata (KHR_xmp_json_ld) that pathwise ignores.
 */
function model(): Document {
  const doc = new Document();
  const base = doc
    .createTexture()
    .setImage(png(4, 4, (x, y) => ((x + y) % 2 ? [220, 40, 30, 255] : [40, 200, 60, 255])))
    .setMimeType('image/png');
  const normal = doc
    .createTexture()
    .setImage(png(2, 2, (x) => (x ? [200, 128, 230, 255] : [60, 128, 230, 255])))
    .setMimeType('image/png');
  const xmp = doc
    .createExtension(KHRXMP)
    .createPacket()
    .setContext({ dc: 'http://purl.org/dc/elements/1.1/' });
  const mat = doc
    .createMaterial()
    .setBaseColorTexture(base)
    .setNormalTexture(normal)
    .setRoughnessFactor(0.4)
    .setExtension('KHR_xmp_json_ld', xmp);
  const floor = doc.createMaterial().setBaseColorFactor([0.7, 0.7, 0.7, 1]).setMetallicFactor(0);
  docWith(doc, quadPrimitive(doc).setMaterial(mat));
  addFloor(doc, floor);
  return doc;
}

/** Records the controller's load stages and warnings on the page. */
async function recordLoad(page: Page): Promise<void> {
  await page.evaluate(() => {
    const w = window as any;
    w.stages = [];
    w.warnings = null;
    const c = w.__pathwise.controller;
    c.addEventListener('loadprogress', (e: CustomEvent) => w.stages.push(e.detail.stage));
    c.addEventListener('warning', (e: CustomEvent) => (w.warnings = e.detail.messages));
  });
}

describe('glTF models in the demo and the widget (Chromium)', () => {
  it('opens a .gltf with its buffer and images: the Node core image bit for bit, stages and a note', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'pathwise-gltf-drop-'));
    const files = await toGltfFiles(model(), 'chair');
    for (const [name, bytes] of files) writeFileSync(join(dir, name), bytes);
    const names = [...files.keys()];
    expect(names.length).toBe(4); // .gltf, .bin, two images
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}`);
    const workers: string[] = [];
    page.on('worker', (w) => workers.push(w.url()));
    await waitForSpp(page, 1);
    await recordLoad(page);
    // Without its images the model cannot load, and the message says which file.
    await page.setInputFiles(
      '#file',
      names.filter((n) => !n.endsWith('.png')).map((n) => join(dir, n)),
    );
    await page.waitForFunction(() => document.getElementById('error')!.textContent !== '');
    expect(await page.textContent('#error')).toMatch(
      /^chair\.gltf: glTF: images\[\d\]\.uri: cannot read ".*\.png": it was not among the dropped files/,
    );
    await page.setInputFiles(
      '#file',
      names.map((n) => join(dir, n)),
    );
    await page.waitForFunction(
      () => (window as any).__pathwise.controller.scene.name === 'chair.gltf',
    );
    await waitForSpp(page, PASSES);
    const stages = await page.evaluate(() => (window as any).stages as string[]);
    for (const s of ['parse', 'textures', 'geometry', 'compile']) expect(stages).toContain(s);
    expect(await page.evaluate(() => (window as any).warnings)).toEqual([
      'shapes[0] (chair.gltf): extension "KHR_xmp_json_ld" is not supported; its content is ignored',
    ]);
    expect(await page.textContent('#notice')).toContain('KHR_xmp_json_ld');
    // The page keeps the scene without the model's arrays: the packed scene has them.
    expect(
      await page.evaluate(() => (window as any).__pathwise.controller.scene.shapes[0].data),
    ).toBe(null);
    // Parsed, decoded and built off the page's thread: in the model worker.
    expect(workers.filter((u) => u.includes('model-worker')).length).toBe(2);
    const reference = await nodeModelRender(
      files.get('chair.gltf')!,
      'chair.gltf',
      dir,
      SIZE,
      SIZE,
      SEED,
      PASSES,
    );
    expect(bitDifferences((await readLinear(page)).rgb, reference)).toBe(0);
    await page.close();
  });

  async function widgetOnPage(url: string) {
    const glb = await toGlb(model());
    const page = await ctx.browser.newPage();
    const workers: string[] = [];
    page.on('worker', (w) => workers.push(w.url()));
    // The model is served by the page's own origin (as the dev server would).
    await page.route('**/models/chair.glb', (route) =>
      route.fulfill({ body: Buffer.from(glb), contentType: 'model/gltf-binary' }),
    );
    // The same model as a .gltf with its buffer and images beside it.
    const gltf = await toGltfFiles(model(), 'chair');
    await page.route('**/models/gltf/**', (route) => {
      const name = decodeURIComponent(new URL(route.request().url()).pathname.split('/').pop()!);
      const body = gltf.get(name);
      return body ? route.fulfill({ body: Buffer.from(body) }) : route.fulfill({ status: 404 });
    });
    await page.route('**/models/broken.glb', (route) =>
      route.fulfill({ body: Buffer.from(glb.subarray(0, 100)), contentType: 'model/gltf-binary' }),
    );
    await page.goto(`${url}?${fixed}&spp=1`);
    await page.waitForFunction(() => 'controller' in ((window as any).__pathwise ?? {}));
    // The element from the sources, as the dev server serves them to a page.
    await page.addScriptTag({ type: 'module', content: "import '/src/widget/register.ts';" });
    await page.waitForFunction(() => customElements.get('pathwise-view') !== undefined);
    const result = await page.evaluate(async () => {
      const view = (src: string) => {
        const el = document.createElement('pathwise-view') as any;
        el.setAttribute('spp', '2');
        el.setAttribute('src', src);
        el.style.width = '48px';
        el.style.height = '32px';
        const events: { type: string; detail: any }[] = [];
        const shown: string[] = [];
        for (const t of ['load', 'loadprogress', 'warning', 'converged', 'error']) {
          el.addEventListener(t, (e: CustomEvent) => events.push({ type: t, detail: e.detail }));
        }
        // What the element's status line says while the model loads.
        el.addEventListener('loadprogress', () => {
          const status = el.shadowRoot.querySelector('[part=status]');
          if (!status.hidden) shown.push(status.textContent);
        });
        (el as any).shown = shown;
        document.body.append(el);
        return { el, events };
      };
      const good = view('models/chair.glb');
      const separate = view('models/gltf/chair.gltf');
      const bad = view('models/broken.glb');
      const until = (v: typeof good, type: string) =>
        new Promise<void>((resolve) => {
          const poll = () =>
            v.events.some((e) => e.type === type) ? resolve() : setTimeout(poll, 50);
          poll();
        });
      await Promise.all([
        until(good, 'converged'),
        until(separate, 'converged'),
        until(bad, 'error'),
      ]);
      const pixels = good.el.controller.readLinear();
      let sum = 0;
      for (const x of pixels.rgb) sum += x;
      const other = separate.el.controller.readLinear().rgb;
      let same = other.length === pixels.rgb.length;
      for (let i = 0; same && i < other.length; i++) same = other[i] === pixels.rgb[i];
      return {
        isolated: crossOriginIsolated,
        compute: good.el.mode.compute,
        name: good.events.find((e) => e.type === 'load')!.detail.scene.name,
        stages: good.events.filter((e) => e.type === 'loadprogress').map((e) => e.detail.stage),
        warnings: good.events.find((e) => e.type === 'warning')?.detail.messages,
        status: good.el.shadowRoot.querySelector('[part=status]').hidden,
        shown: good.el.shown as string[],
        mean: sum / pixels.rgb.length,
        gltfName: separate.events.find((e) => e.type === 'load')?.detail.scene.name,
        gltfSameBits: same,
        error: bad.events.find((e) => e.type === 'error')!.detail.message,
        message: bad.el.shadowRoot.querySelector('[part=message]').textContent,
      };
    });
    await page.close();
    return { ...result, modelWorkers: workers.filter((u) => u.includes('model-worker')).length };
  }

  for (const isolated of [true, false]) {
    it(`<pathwise-view src="chair.glb"> renders ${isolated ? 'with' : 'without'} COOP/COEP, with warnings and a clear error`, async () => {
      const plain = isolated ? null : await startDemoServer(false);
      try {
        const r = await widgetOnPage(plain?.url ?? ctx.url);
        expect(r.isolated).toBe(isolated);
        expect(r.compute).toBe(isolated ? 'shared' : 'transfer');
        expect(r.name).toBe('chair.glb');
        expect(r.stages).toEqual(
          expect.arrayContaining(['read', 'parse', 'textures', 'geometry', 'compile']),
        );
        expect(r.stages[0]).toBe('read');
        expect(r.shown).toEqual(
          expect.arrayContaining(['Loading: parsing', 'Loading: building the BVH']),
        );
        expect(r.shown.some((t) => t.startsWith('Loading: decoding textures'))).toBe(true);
        expect(r.status).toBe(true); // the progress line is gone once loaded
        expect(r.modelWorkers).toBe(3); // one per model, the broken one included
        // The .gltf with its files beside it (fetched relative to it) is the same scene.
        expect(r.gltfName).toBe('chair.gltf');
        expect(r.gltfSameBits).toBe(true);
        expect(r.warnings).toEqual([
          'shapes[0] (chair.glb): extension "KHR_xmp_json_ld" is not supported; its content is ignored',
        ]);
        // Lit by the studio: neither black nor absurd.
        expect(r.mean).toBeGreaterThan(0.05);
        expect(r.mean).toBeLessThan(10);
        expect(r.error).toMatch(
          /^broken\.glb: glTF: GLB header: says \d+ bytes, but the file has 100/,
        );
        expect(r.message).toBe(r.error);
      } finally {
        await plain?.server.close();
      }
    });
  }
});
