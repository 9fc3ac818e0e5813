/**
 * <pathwise-view denoise> in Chromium, on a cross-origin isolated page (shared memory)
 * and on one without COOP/COEP (transferred stripes, no SharedArrayBuffer): the element
 * forwards `denoised` events, its stats name the picture on screen, the picture is a
 * plausible image of the film (finite, its mean luminance within 10 % of the film's:
 * a denoiser keeps the brightness), the attribute turns it off, and removing the element
 * ends the denoiser's thread. The element is the sources' (as the dev server serves
 * them), added to the demo's page. The 2-second bar is timed
 * alone in tests/timing/denoise-demo.test.ts.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Browser } from 'playwright-core';
import type { ViteDevServer } from 'vite';
import { launchBrowser, startDemoServer } from './harness.ts';
import { WAIT, addView } from './widget-page.ts';

let browser: Browser;
const servers: { isolated: boolean; server: ViteDevServer; url: string }[] = [];

beforeAll(async () => {
  browser = await launchBrowser();
  for (const isolated of [true, false])
    servers.push({ isolated, ...(await startDemoServer(isolated)) });
});

afterAll(async () => {
  await browser?.close();
  for (const s of servers) await s.server.close();
});

describe('<pathwise-view denoise> (Chromium)', () => {
  for (const isolated of [true, false]) {
    it(`${isolated ? 'isolated page (shared memory)' : 'page without COOP/COEP (transferred stripes)'}: denoised pictures, switched off, no worker left`, async () => {
      const { url } = servers.find((s) => s.isolated === isolated)!;
      const context = await browser.newContext({ viewport: { width: 800, height: 600 } });
      const page = await context.newPage();
      const errors: string[] = [];
      page.on('pageerror', (e) => errors.push(e.message));
      // The denoiser's threads, and those that ended.
      const denoisers = { started: 0, closed: 0 };
      page.on('worker', (w) => {
        if (!w.url().includes('denoise-worker')) return;
        denoisers.started++;
        w.on('close', () => denoisers.closed++);
      });
      try {
        await page.goto(`${url}?width=32&height=32&spp=1`);
        await page.waitForFunction(() => 'controller' in ((window as any).__pathwise ?? {}));
        await page.addScriptTag({ type: 'module', content: "import '/src/widget/register.ts';" });
        await page.waitForFunction(() => customElements.get('pathwise-view') !== undefined);
        const view = await addView(page, 'v', {
          src: '/scenes/cornell.json',
          denoise: '',
          spp: '8',
          seed: '3',
        });
        await page.evaluate(`(() => {
          const el = document.querySelector('#v');
          el.denoisedLog = [];
          el.addEventListener('denoised', (e) => el.denoisedLog.push(e.detail));
        })()`);
        await page.waitForFunction(
          `document.querySelector('#v').denoisedLog.some((d) => d.spp >= 8)`,
          undefined,
          WAIT,
        );
        const r = (await page.evaluate(`(() => {
          const el = document.querySelector('#v');
          const c = el.controller;
          const d = c.denoisedSnapshot();
          const film = c.readLinear();
          const lum = (a, i) => 0.2126 * a[i] + 0.7152 * a[i + 1] + 0.0722 * a[i + 2];
          let dl = 0, fl = 0, finite = true;
          for (let p = 0; p < film.width * film.height; p++) {
            dl += lum(d.sums, 4 * p);
            fl += lum(film.rgb, 3 * p);
            if (!Number.isFinite(d.sums[4 * p]) || !Number.isFinite(d.sums[4 * p + 1]) || !Number.isFinite(d.sums[4 * p + 2])) finite = false;
          }
          return { mode: c.mode.compute, property: el.denoise, stats: c.stats().denoised, size: [d.width, d.height], film: [film.width, film.height], finite, ratio: dl / fl };
        })()`)) as {
          mode: string;
          property: boolean;
          stats: { spp: number } | null;
          size: number[];
          film: number[];
          finite: boolean;
          ratio: number;
        };
        expect(r.mode).toBe(isolated ? 'shared' : 'transfer');
        expect(r.property).toBe(true);
        expect(r.stats?.spp).toBe(8);
        expect(r.size).toEqual(r.film);
        expect(r.finite).toBe(true);
        expect(Math.abs(r.ratio - 1)).toBeLessThan(0.1);
        // Off: the film's own picture, and no more denoised ones.
        await page.evaluate(`document.querySelector('#v').removeAttribute('denoise')`);
        await page.waitForFunction(
          `document.querySelector('#v').controller.stats().denoised === null`,
          undefined,
          WAIT,
        );
        expect(await page.evaluate(`document.querySelector('#v').denoise`)).toBe(false);
        expect(denoisers.started).toBe(1);
        await page.evaluate(`document.querySelector('${view}').remove()`);
        await expect.poll(() => denoisers.closed).toBe(1);
        expect(errors).toEqual([]);
      } finally {
        await context.close();
      }
    });
  }
});
