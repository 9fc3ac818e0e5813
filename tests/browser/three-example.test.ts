/**
 * examples/three in Chromium (issue 24, deliverable 2): a three.js app with OrbitControls
 * rasterises with three's WebGLRenderer, switches to <pathwise-view>, which path-traces
 * the same scene (lit: the floor under the area light is bright, the sky shows), follows
 * a drag of the controls by restarting its accumulation from the new view, and switches
 * back. The page is served with and without cross-origin isolation: the widget must work
 * in a page without special headers.
 */
import type { Browser, Page } from 'playwright-core';
import type { ViteDevServer } from 'vite';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { launchBrowser, startDemoServer } from './harness.ts';

let browser: Browser;
beforeAll(async () => {
  browser = await launchBrowser();
}, 60_000);
afterAll(async () => {
  await browser?.close();
});

async function spp(page: Page): Promise<number> {
  return page.evaluate(() => (window as any).example.view()?.progress?.spp ?? 0);
}

for (const isolated of [true, false]) {
  describe(`examples/three (${isolated ? 'cross-origin isolated' : 'no special headers'})`, () => {
    let server: ViteDevServer;
    let url: string;
    beforeAll(async () => {
      ({ server, url } = await startDemoServer(isolated));
    }, 120_000);
    afterAll(async () => {
      await server?.close();
    });

    it('switches from three.js to pathwise, follows the controls, and back', async () => {
      const page = await browser.newPage({ viewport: { width: 800, height: 700 } });
      const errors: string[] = [];
      const warnings: string[] = [];
      page.on('pageerror', (e) => errors.push(e.message));
      page.on('response', (r) => {
        if (r.status() >= 400) errors.push(`${r.status()} ${r.url()}`);
      });
      page.on('console', (m) => {
        // A failed request is logged without its URL; the response listener names it.
        if (m.type() === 'error' && !m.text().startsWith('Failed to load resource'))
          errors.push(m.text());
        if (m.type() === 'warning') warnings.push(m.text());
      });
      try {
        await page.goto(new URL('/examples/three/', url).href);
        await page.waitForFunction(() => (window as any).example !== undefined, null, {
          timeout: 60_000,
        });
        await page.click('#renderer');
        // The full film's own passes, read with the image in one turn: the last progress
        // event may be the quick preview film's, or come from before a restart, while
        // the full film the PFM holds has nothing yet (it failed so once on a loaded
        // machine: an image of mean 0).
        const firstHandle = await page.waitForFunction(
          () => {
            const view = (window as any).example.view();
            const c = view?.controller;
            if (!c || !(c.progress() >= 2)) return null;
            const pfm: Uint8Array = view.toPFM();
            return { camera: c.getCamera(), pfm: Array.from(pfm) };
          },
          null,
          {
            timeout: 90_000,
            polling: 100,
          },
        );
        const first = (await firstHandle.jsonValue()) as {
          camera: { position: number[] };
          pfm: number[];
        };
        // Lit, and not uniform: the image mean is well above black.
        const image = decodeLinear(first.pfm);
        expect(image.mean).toBeGreaterThan(0.05);
        expect(image.max).toBeGreaterThan(image.mean * 1.5);
        // A drag of the OrbitControls turns the camera; the view starts over from it.
        const before = await spp(page);
        const box = (await page.locator('#stage').boundingBox())!;
        await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
        await page.mouse.down();
        await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2, { steps: 8 });
        await page.mouse.up();
        await page.waitForFunction(
          (p) => {
            const view = (window as any).example.view();
            const c = view.controller.getCamera();
            return c.position.some((v: number, i: number) => Math.abs(v - p[i]) > 1e-3);
          },
          first.camera.position,
          { timeout: 30_000, polling: 50 },
        );
        const after = await spp(page);
        expect(after).toBeLessThanOrEqual(before);
        // The conversion itself had nothing to warn about.
        expect(warnings.filter((w) => !w.includes('GPU stall'))).toEqual([]);
        await page.click('#renderer');
        expect(await page.evaluate(() => (window as any).example.view())).toBeNull();
        expect(await page.locator('#stage canvas').first().isVisible()).toBe(true);
        expect(errors).toEqual([]);
      } finally {
        await page.close();
      }
    }, 180_000);
  });
}

/** Mean and maximum of a PFM's values (the tracer's own linear output). */
function decodeLinear(bytes: number[]): { mean: number; max: number } {
  const b = Uint8Array.from(bytes);
  let newlines = 0;
  let start = 0;
  while (newlines < 3) if (b[start++] === 10) newlines++;
  const values = new Float32Array(b.buffer.slice(start));
  let sum = 0;
  let max = 0;
  for (const v of values) {
    sum += v;
    max = Math.max(max, v);
  }
  return { mean: sum / values.length, max };
}
