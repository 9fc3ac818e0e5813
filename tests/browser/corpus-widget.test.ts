/**
 * Three models of the glTF corpus (tests/corpus/) through <pathwise-view> in Chromium,
 * served from the checkout by the dev server as a page would fetch them: each prints
 * exactly the messages tests/cli/corpus-pending.ts lists for it (as the CLI does), and
 * one that loads renders finite and not blank. The whole corpus goes through the widget
 * in `node scripts/corpus.mjs`; this is its cheap guard in npm test.
 */
import type { Browser } from 'playwright-core';
import type { ViteDevServer } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { pendingDiff, widgetMessages } from '../cli/corpus-pending.ts';
import { launchBrowser, startDemoServer } from './harness.ts';
import { openWidgetPage } from './widget-page.ts';

const MODELS: [string, string][] = [
  ['TextureTransformTest', 'tests/corpus/TextureTransformTest/TextureTransformTest.gltf'],
  ['AttenuationTest', 'tests/corpus/AttenuationTest/AttenuationTest.glb'],
  ['Box-Draco', 'tests/corpus/Box-Draco/Box.gltf'],
];

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

describe('corpus models in <pathwise-view> (Chromium)', () => {
  for (const [name, file] of MODELS) {
    it(`${name}: the listed messages, and a finite image that is not blank`, async () => {
      const opened = await openWidgetPage(browser, url);
      try {
        const r = await opened.page.evaluate(async (src) => {
          const el = document.createElement('pathwise-view') as any;
          el.setAttribute('spp', '1');
          el.setAttribute('src', src);
          el.style.width = '32px';
          el.style.height = '24px';
          const events: { type: string; detail: any }[] = [];
          for (const t of ['warning', 'converged', 'error']) {
            el.addEventListener(t, (e: CustomEvent) => events.push({ type: t, detail: e.detail }));
          }
          document.body.append(el);
          await new Promise<void>((resolve) => {
            const poll = () =>
              events.some((e) => e.type === 'converged' || e.type === 'error')
                ? resolve()
                : setTimeout(poll, 50);
            poll();
          });
          const error = events.find((e) => e.type === 'error')?.detail.message ?? null;
          const warnings = events
            .filter((e) => e.type === 'warning')
            .flatMap((e) => e.detail.messages as string[]);
          let finite = true;
          let min = Infinity;
          let max = -Infinity;
          if (!error) {
            for (const v of el.controller.readLinear().rgb as Float32Array) {
              if (!Number.isFinite(v)) finite = false;
              if (v < min) min = v;
              if (v > max) max = v;
            }
          }
          return { error, warnings, finite, uniform: !(max > min) };
        }, `/${file}`);
        const { unexpected, gone } = pendingDiff(name, widgetMessages(r.warnings, r.error));
        expect(unexpected, 'messages not in PENDING (tests/cli/corpus-pending.ts)').toEqual([]);
        expect(gone, 'PENDING lists messages that are gone: remove them').toEqual([]);
        if (!r.error) {
          expect(r.finite).toBe(true);
          expect(r.uniform).toBe(false);
        }
        expect(opened.errors).toEqual([]);
      } finally {
        await opened.context.close();
      }
    });
  }
});
