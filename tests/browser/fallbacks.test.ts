/**
 * The fallbacks and the machinery behind the demo, in Chromium: Canvas 2D
 * display, transferred stripes without shared memory (asked for, or on a
 * page served without COOP/COEP), bursts of changes, two views sharing the
 * worker pool, and the production build under `vite preview`. Each must
 * render the Node core's image bit for bit.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { PASSES, SEED, SIZE, WEBGL, fixed, useDemo } from './context.ts';
import {
  bitDifferences,
  maxByteDifference,
  openDemo,
  readDisplay,
  readLinear,
  root,
  startDemoServer,
  startPreviewServer,
  waitForSpp,
} from './harness.ts';
import { nodeRender } from './node-reference.ts';

const ctx = useDemo();

describe('browser demo fallbacks and pool (Chromium)', () => {
  it('draws the same picture with the Canvas 2D fallback', async () => {
    const gl = await ctx.converged(WEBGL);
    const cpu = await ctx.converged('display=canvas2d');
    expect(await cpu.evaluate(() => (window as any).__pathwise.controller.mode.display)).toBe(
      'canvas2d',
    );
    expect(bitDifferences((await readLinear(cpu)).rgb, ctx.reference)).toBe(0);
    const a = await readDisplay(gl);
    const b = await readDisplay(cpu);
    expect(b.width).toBe(a.width);
    expect(maxByteDifference(a.rgba, b.rgba)).toBeLessThanOrEqual(1);
    await gl.close();
    await cpu.close();
  });

  it('renders the same bits with shared memory switched off (shared=off)', async () => {
    const page = await ctx.converged('shared=off');
    const mode = await page.evaluate(() => (window as any).__pathwise.controller.mode);
    expect(mode.compute).toBe('transfer');
    expect(await page.locator('#mode').textContent()).toContain('shared=off');
    expect(bitDifferences((await readLinear(page)).rgb, ctx.reference)).toBe(0);
    await page.close();
  });

  it('renders the same bits on a page served without COOP/COEP', async () => {
    const plain = await startDemoServer(false);
    try {
      const page = await openDemo(ctx.browser, plain.url, `${fixed}&spp=${PASSES}`);
      expect(await page.evaluate(() => crossOriginIsolated)).toBe(false);
      await waitForSpp(page, PASSES);
      const mode = await page.evaluate(() => (window as any).__pathwise.controller.mode);
      expect(mode.compute).toBe('transfer');
      expect(mode.reason).toContain('not cross-origin isolated');
      expect(bitDifferences((await readLinear(page)).rgb, ctx.reference)).toBe(0);
      await page.close();
    } finally {
      await plain.server.close();
    }
  });

  for (const query of ['', 'shared=off']) {
    it(`survives a burst of changes and still converges to the exact image (${query || 'shared'})`, async () => {
      const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}&${query}`);
      await waitForSpp(page, 1);
      // Orbits, previews, pauses, resets, bounce and target changes and pool
      // resizes, interleaved with rendering: no stale row may survive them.
      for (let i = 0; i < 45; i++) {
        await page.evaluate(async (i) => {
          const c = (window as any).__pathwise.controller;
          const op = i % 9;
          if (op === 0) c.orbit(3, 1);
          if (op === 1) {
            c.beginPreview();
            c.orbit(-2, 0);
          }
          if (op === 2) c.endPreview();
          if (op === 3) c.pause();
          if (op === 4) c.resume();
          if (op === 5) await c.setWorkers(1 + (i % 3));
          if (op === 6) c.reset();
          if (op === 7) c.setBounces(2 + (i % 5));
          if (op === 8) c.setTargetSpp(3 + (i % 7));
        }, i);
        await page.waitForTimeout(10 + ((i * 7) % 23));
      }
      const camera = await page.evaluate(async (passes) => {
        const c = (window as any).__pathwise.controller;
        c.endPreview();
        c.resume();
        c.setTargetSpp(passes);
        await c.setWorkers(2);
        return c.getCamera();
      }, PASSES);
      await waitForSpp(page, PASSES);
      const bounces = await page.evaluate(
        () => (window as any).__pathwise.controller.config.maxBounces,
      );
      expect(bounces).toBe(2 + (43 % 5));
      const expected = nodeRender('cornell', SIZE, SIZE, SEED, PASSES, camera, bounces);
      expect(bitDifferences((await readLinear(page)).rgb, expected)).toBe(0);
      await page.close();
    });
  }

  it('shares one worker pool between two views on a page, each rendering its exact image', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}`);
    const spheres = JSON.parse(readFileSync(join(root, 'scenes', 'spheres.json'), 'utf8'));
    await page.evaluate(
      ({ scene, passes }) => {
        const w = window as any;
        const canvas = document.createElement('canvas');
        canvas.style.width = '48px';
        document.body.append(canvas);
        w.__second = w.__pathwise.createPathTracer(canvas, {
          scene,
          width: 40,
          height: 24,
          seed: 7,
          spp: passes,
        });
      },
      { scene: spheres, passes: PASSES },
    );
    await page.waitForFunction((n) => (window as any).__second.stats().spp >= n, PASSES, {
      timeout: 60_000,
    });
    await waitForSpp(page, PASSES);
    const workers = await page.evaluate(() => [
      (window as any).__pathwise.controller.stats().workers,
      (window as any).__second.stats().workers,
    ]);
    expect(workers[0]).toBe(workers[1]);
    const second = await page.evaluate(() => Array.from((window as any).__second.readLinear().rgb));
    expect(
      bitDifferences(Float32Array.from(second), nodeRender('spheres', 40, 24, 7, PASSES)),
    ).toBe(0);
    expect(bitDifferences((await readLinear(page)).rgb, ctx.reference)).toBe(0);
    // Destroying one view leaves the pool to the other.
    const after = await page.evaluate(() => {
      const w = window as any;
      w.__second.destroy();
      w.__pathwise.controller.reset();
      return w.__pathwise.controller.stats().spp;
    });
    expect(after).toBe(0);
    await waitForSpp(page, PASSES);
    expect(bitDifferences((await readLinear(page)).rgb, ctx.reference)).toBe(0);
    await page.close();
  });

  it('serves the production build with COOP/COEP from vite preview, isolated and rendering', async () => {
    const built = await startPreviewServer();
    try {
      const response = await fetch(built.url);
      expect(response.headers.get('cross-origin-opener-policy')).toBe('same-origin');
      expect(response.headers.get('cross-origin-embedder-policy')).toBe('require-corp');
      const page = await openDemo(ctx.browser, built.url, `${fixed}&spp=${PASSES}`);
      expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
      await waitForSpp(page, PASSES);
      // The bundled worker renders the same bits as the Node core.
      expect(bitDifferences((await readLinear(page)).rgb, ctx.reference)).toBe(0);
      await page.close();
    } finally {
      await built.server.close();
    }
  });
});
