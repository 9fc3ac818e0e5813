/**
 * <pathwise-view variant="…"> in Chromium (docs/gltf.md, Material variants): the
 * attribute reaches the model worker, so a known name loads (the scene's shape records
 * it) with no note, and an unknown one is the element's error listing the file's names.
 */
import type { Browser } from 'playwright-core';
import type { ViteDevServer } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { launchBrowser, startDemoServer } from './harness.ts';
import { openWidgetPage } from './widget-page.ts';

const SOFA = '/tests/corpus/GlamVelvetSofa/GlamVelvetSofa.glb';

let server: ViteDevServer;
let url: string;
let browser: Browser;
beforeAll(async () => {
  ({ server, url } = await startDemoServer(true));
  browser = await launchBrowser();
});
afterAll(async () => {
  await browser?.close();
  await server?.close();
});

describe('<pathwise-view variant> (Chromium)', () => {
  it('loads the named variant, and refuses an unknown name with the file’s names', async () => {
    const opened = await openWidgetPage(browser, url);
    try {
      const load = (variant: string) =>
        opened.page.evaluate(
          async ([src, v]) => {
            const el = document.createElement('pathwise-view') as any;
            el.setAttribute('spp', '1');
            el.setAttribute('variant', v);
            el.setAttribute('src', src);
            el.style.width = '16px';
            el.style.height = '12px';
            const events: { type: string; detail: any }[] = [];
            for (const t of ['load', 'warning', 'error']) {
              el.addEventListener(t, (e: CustomEvent) =>
                events.push({ type: t, detail: e.detail }),
              );
            }
            document.body.append(el);
            await new Promise<void>((resolve) => {
              const poll = () =>
                events.some((e) => e.type === 'load' || e.type === 'error')
                  ? resolve()
                  : setTimeout(poll, 50);
              poll();
            });
            const loaded = events.find((e) => e.type === 'load')?.detail;
            const result = {
              error: events.find((e) => e.type === 'error')?.detail.message ?? null,
              variant: loaded ? (loaded.scene.shapes[0].variant ?? null) : null,
              warnings: loaded ? (loaded.warnings as string[]) : [],
            };
            el.remove();
            return result;
          },
          [SOFA, variant] as const,
        );
      const known = await load('Pale Pink');
      expect(known.error).toBeNull();
      expect(known.variant).toBe('Pale Pink');
      expect(known.warnings.filter((w) => w.includes('KHR_materials_variants'))).toEqual([]);
      const unknown = await load('Purple');
      expect(unknown.error).toContain(
        'extensions.KHR_materials_variants.variants: has no variant "Purple"; the file\'s ' +
          'variants are "Champagne", "Navy", "Gray", "Black", "Pale Pink"',
      );
      expect(opened.errors).toEqual([]);
    } finally {
      await opened.context.close();
    }
  });
});
