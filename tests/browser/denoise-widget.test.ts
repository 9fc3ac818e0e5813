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
let isolatedServer: { server: ViteDevServer; url: string } | undefined;

beforeAll(async () => {
  browser = await launchBrowser();
  isolatedServer = await startDemoServer(true);
});

afterAll(async () => {
  await browser?.close();
  await isolatedServer?.server.close();
});

describe('<pathwise-view denoise> (Chromium)', () => {
  for (const isolated of [true, false]) {
    it(`${isolated ? 'isolated page (shared memory)' : 'page without COOP/COEP (transferred stripes)'}: denoised pictures, switched off, no worker left`, async () => {
      // The plain server is started for this test alone, as tests/browser/fallbacks.test.ts
      // does (one started long before its page loads could leave the page waiting).
      const plain = isolated ? null : await startDemoServer(false);
      const url = plain?.url ?? isolatedServer!.url;
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
        // The picture on screen from the target's samples (an automatic rescale may
        // restart the film once after a picture: wait for the one on screen).
        await page.waitForFunction(
          `document.querySelector('#v').controller.denoisedSnapshot()?.spp >= 8`,
          undefined,
          WAIT,
        );
        const r = (await page.evaluate(`(() => {
          const el = document.querySelector('#v');
          const c = el.controller;
          const d = c.denoisedSnapshot();
          if (!d) return { lost: true };
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
          lost?: boolean;
          mode: string;
          property: boolean;
          stats: { spp: number } | null;
          size: number[];
          film: number[];
          finite: boolean;
          ratio: number;
        };
        expect(r.lost).toBeUndefined();
        expect(r.mode).toBe(isolated ? 'shared' : 'transfer');
        expect(r.property).toBe(true);
        expect(r.stats?.spp).toBe(8);
        expect(r.size).toEqual(r.film);
        expect(r.finite).toBe(true);
        expect(Math.abs(r.ratio - 1)).toBeLessThan(0.1);
        // The PNG is the picture on screen: denoised now, the film's own once switched off.
        const png = `(async () => Array.from(new Uint8Array(await (await document.querySelector('#v').toBlob()).arrayBuffer())))()`;
        const denoisedPng = (await page.evaluate(png)) as number[];
        // Off: the film's own picture, and no more denoised ones.
        await page.evaluate(`document.querySelector('#v').removeAttribute('denoise')`);
        await page.waitForFunction(
          `document.querySelector('#v').controller.stats().denoised === null`,
          undefined,
          WAIT,
        );
        expect(await page.evaluate(`document.querySelector('#v').denoise`)).toBe(false);
        const rawPng = (await page.evaluate(png)) as number[];
        expect(rawPng.length).toBeGreaterThan(0);
        expect(rawPng).not.toEqual(denoisedPng);
        expect(denoisers.started).toBe(1);
        await page.evaluate(`document.querySelector('${view}').remove()`);
        await expect.poll(() => denoisers.closed).toBe(1);
        expect(errors).toEqual([]);
      } finally {
        await context.close();
        await plain?.server.close();
      }
    });
  }

  it('the same bits from 1 and 2 denoise workers (a 768×512 film: two overlapped tiles, on one worker or one each)', async () => {
    const { url } = isolatedServer!;
    const page = await browser.newPage();
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    try {
      await page.goto(`${url}?width=32&height=32&spp=1`);
      await page.waitForFunction(() => 'controller' in ((window as any).__pathwise ?? {}));
      const r = (await page.evaluate(`(async () => {
        const { createPathTracer } = window.__pathwise;
        const run = (workers) => new Promise((resolve, reject) => {
          const canvas = document.createElement('canvas');
          document.body.append(canvas);
          const c = createPathTracer(canvas, {
            src: '/scenes/cornell.json', width: 768, height: 512, spp: 1, seed: 4,
            denoise: true, denoiseWorkers: workers,
          });
          c.addEventListener('error', (e) => reject(new Error(e.detail.message)));
          c.addEventListener('denoised', (e) => {
            if (e.detail.spp < 1) return;
            const d = c.denoisedSnapshot();
            const bits = new Uint32Array(d.sums.buffer.slice(0));
            c.destroy();
            canvas.remove();
            resolve(bits);
          });
        });
        const one = await run(1);
        const two = await run(2);
        const diff = (a, b) => { let n = a.length === b.length ? 0 : -1; for (let i = 0; n >= 0 && i < a.length; i++) if (a[i] !== b[i]) n++; return n; };
        let finite = true;
        const f = new Float32Array(one.buffer);
        for (let i = 0; i < f.length; i++) if (!Number.isFinite(f[i])) finite = false;
        return { length: one.length, two: diff(one, two), finite };
      })()`)) as { length: number; two: number; finite: boolean };
      expect(r.length).toBe(768 * 512 * 4);
      expect(r.finite).toBe(true);
      expect(r.two).toBe(0);
      expect(errors).toEqual([]);
    } finally {
      await page.close();
    }
  });

  it("weights that cannot be fetched: one error, the film's own picture, denoising off, the render goes on", async () => {
    const { url } = isolatedServer!;
    const page = await browser.newPage();
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.route('**/rt_hdr_alb_nrm_small.tza*', (route) => route.fulfill({ status: 404 }));
    try {
      await page.goto(`${url}?width=32&height=32&spp=1`);
      await page.waitForFunction(() => 'controller' in ((window as any).__pathwise ?? {}));
      const r = (await page.evaluate(`(async () => {
        const { createPathTracer } = window.__pathwise;
        const canvas = document.createElement('canvas');
        document.body.append(canvas);
        const c = createPathTracer(canvas, {
          src: '/scenes/cornell.json', width: 64, height: 64, spp: 4, seed: 2, denoise: true,
        });
        const messages = [];
        c.addEventListener('error', (e) => messages.push(e.detail.message));
        const until = async (test) => { while (!test()) await new Promise((r) => setTimeout(r, 20)); };
        await until(() => messages.length > 0);
        await until(() => c.stats().spp >= 4);
        const out = { messages, denoise: c.denoise, shown: c.stats().denoised, spp: c.stats().spp };
        c.destroy();
        return out;
      })()`)) as { messages: string[]; denoise: boolean; shown: unknown; spp: number };
      expect(r.messages).toHaveLength(1);
      expect(r.messages[0]).toMatch(/denoising failed: denoiser weights: HTTP 404/);
      expect(r.denoise).toBe(false);
      expect(r.shown).toBeNull();
      expect(r.spp).toBe(4);
      expect(errors).toEqual([]);
    } finally {
      await page.close();
    }
  });
});
