/**
 * The browser demo end to end in Chromium: isolation, progress, the
 * picture, bit-identity with the Node core, the controls, and the
 * fallbacks. Renders are 64×64 so the suite stays short on two cores;
 * nothing here asserts on timing.
 */
import type { Browser, Page } from 'playwright-core';
import type { ViteDevServer } from 'vite';
import { afterAll, afterEach, beforeAll, describe, expect, it } from 'vitest';
import {
  bitDifferences,
  launchBrowser,
  maxByteDifference,
  meanRgb,
  openDemo,
  pageErrors,
  readDisplay,
  readLinear,
  spp,
  startDemoServer,
  waitForSpp,
} from './harness.ts';
import { toDisplayByte } from '../../src/core/index.ts';
import { nodeRender } from './node-reference.ts';

const SIZE = 64;
const SEED = 1;
const PASSES = 8;
const fixed = `width=${SIZE}&height=${SIZE}&seed=${SEED}`;

let server: ViteDevServer;
let url: string;
let browser: Browser;
let reference: Float32Array;

beforeAll(async () => {
  ({ server, url } = await startDemoServer(true));
  browser = await launchBrowser();
  reference = nodeRender('cornell', SIZE, SIZE, SEED, PASSES);
});

afterAll(async () => {
  await browser?.close();
  await server?.close();
});

afterEach(() => {
  expect(pageErrors).toEqual([]);
});

async function converged(query: string): Promise<Page> {
  const page = await openDemo(browser, url, `${fixed}&spp=${PASSES}&${query}`);
  await waitForSpp(page, PASSES);
  return page;
}

describe('browser demo (Chromium)', () => {
  it('loads cross-origin isolated, spp rises, and shows the Cornell box red left and green right', async () => {
    const page = await openDemo(browser, url, `${fixed}&spp=${PASSES}`);
    expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
    const mode = await page.evaluate(() => (window as any).__pathwise.controller.mode);
    expect(mode.compute).toBe('shared');
    expect(mode.display).toBe('webgl2');
    await waitForSpp(page, 1);
    const first = await spp(page);
    await waitForSpp(page, first + 1);
    await waitForSpp(page, PASSES);
    const img = await readDisplay(page);
    expect(img.width).toBe(SIZE);
    const all = meanRgb(img, 0, 0, SIZE, SIZE);
    expect(all[0] + all[1] + all[2]).toBeGreaterThan(30);
    const left = meanRgb(img, 3, 24, 10, 40);
    const right = meanRgb(img, 54, 24, 61, 40);
    expect(left[0]).toBeGreaterThan(left[1] * 1.5);
    expect(right[1]).toBeGreaterThan(right[0] * 1.5);
    expect(await page.locator('#mode').textContent()).toContain('WebGL2');
    await page.close();
  });

  it('reads back linear data equal to the Node core render bit for bit', async () => {
    const page = await converged('');
    const img = await readLinear(page);
    expect(img.width).toBe(SIZE);
    expect(img.rgb.length).toBe(reference.length);
    expect(bitDifferences(img.rgb, reference)).toBe(0);
    // And the canvas shows that image through the core's display transform,
    // every row of it (rows reach the texture incrementally, as they finish).
    const shown = await readDisplay(page);
    const expected = new Uint8Array(SIZE * SIZE * 4);
    for (let p = 0; p < SIZE * SIZE; p++) {
      for (let c = 0; c < 3; c++) expected[p * 4 + c] = toDisplayByte(reference[p * 3 + c], 1);
      expected[p * 4 + 3] = 255;
    }
    expect(maxByteDifference(shown.rgba, expected)).toBeLessThanOrEqual(1);
    await page.close();
  });

  it('pauses, resumes and resets', async () => {
    const page = await openDemo(browser, url, `${fixed}&spp=100000`);
    await waitForSpp(page, 2);
    await page.click('#pause');
    expect(await page.locator('#pause').textContent()).toBe('Resume');
    // Stripes already in hand may still finish their pass; after that nothing moves.
    await page.waitForTimeout(500);
    const paused = await spp(page);
    await page.waitForTimeout(1000);
    expect(await spp(page)).toBe(paused);
    await page.click('#pause');
    await waitForSpp(page, paused + 2);
    const after = await page.evaluate(() => {
      const c = (window as any).__pathwise.controller;
      c.reset();
      return c.stats().spp;
    });
    expect(after).toBe(0);
    await waitForSpp(page, 1);
    await page.close();
  });

  it('resets on a bounce change but not on an exposure change', async () => {
    const page = await openDemo(browser, url, `${fixed}&spp=100000`);
    await waitForSpp(page, 3);
    // Paused, the counts only move when something resets them.
    await page.click('#pause');
    await page.waitForTimeout(300);
    const before = await spp(page);
    expect(before).toBeGreaterThanOrEqual(3);
    const dark = await readDisplay(page);
    await page.locator('#exposure').fill('2.5');
    expect(await spp(page)).toBe(before);
    const bright = await readDisplay(page);
    const d = meanRgb(dark, 0, 0, SIZE, SIZE);
    const b = meanRgb(bright, 0, 0, SIZE, SIZE);
    expect(b[0] + b[1] + b[2]).toBeGreaterThan(d[0] + d[1] + d[2] + 20);
    await page.locator('#bounces').fill('2');
    expect(await spp(page)).toBe(0);
    await page.click('#pause');
    await waitForSpp(page, 1);
    await page.close();
  });

  it('switches scenes with the preset buttons', async () => {
    const page = await converged('');
    const cornell = await readDisplay(page);
    await page.click('[data-preset="spheres"]');
    await page.waitForFunction(
      () => (window as any).__pathwise.controller.scene.name !== 'Cornell box',
    );
    await waitForSpp(page, PASSES);
    const spheres = await readDisplay(page);
    const name = await page.evaluate(() => (window as any).__pathwise.controller.scene.name);
    expect(name).not.toBe('Cornell box');
    let changed = 0;
    for (let i = 0; i < cornell.rgba.length; i += 4) {
      if (Math.abs(cornell.rgba[i] - spheres.rgba[i]) > 24) changed++;
    }
    expect(changed).toBeGreaterThan((SIZE * SIZE) / 4);
    await page.close();
  });

  it('orbits on a drag with a low-resolution preview, resetting to the new view', async () => {
    const page = await converged('');
    const before = await page.evaluate(() => (window as any).__pathwise.controller.getCamera());
    const image = await readLinear(page);
    // Paused, nothing renders: the reset by the drag stays visible as 0 spp.
    await page.click('#pause');
    const box = (await page.locator('#view').boundingBox())!;
    const cx = box.x + box.width / 2;
    const cy = box.y + box.height / 2;
    // Record the render width every frame: the preview lasts from the first
    // move until the pointer rests or is released.
    await page.evaluate(() => {
      const c = (window as any).__pathwise.controller;
      const widths = new Set<number>();
      (window as any).__widths = widths;
      const tick = () => {
        widths.add(c.stats().width);
        if ((window as any).__widths === widths) requestAnimationFrame(tick);
      };
      tick();
    });
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    await page.mouse.move(cx + 20, cy, { steps: 4 });
    await page.mouse.move(cx + 60, cy + 10, { steps: 4 });
    await page.mouse.up();
    const widths: number[] = await page.evaluate(() => {
      const w = [...(window as any).__widths];
      (window as any).__widths = null;
      return w;
    });
    expect(Math.min(...widths)).toBeLessThan(SIZE);
    const after = await page.evaluate(() => (window as any).__pathwise.controller.getCamera());
    expect(after.position).not.toEqual(before.position);
    expect(after.target).toEqual(before.target);
    const rested = await page.evaluate(() => (window as any).__pathwise.controller.stats());
    expect(rested.width).toBe(SIZE);
    expect(rested.spp).toBe(0);
    await page.click('#pause');
    await waitForSpp(page, PASSES);
    const moved = await readLinear(page);
    expect(bitDifferences(moved.rgb, image.rgb)).toBeGreaterThan(moved.rgb.length / 4);
    // The new view is exactly the Node core's render from the orbited camera.
    expect(bitDifferences(moved.rgb, nodeRender('cornell', SIZE, SIZE, SEED, PASSES, after))).toBe(
      0,
    );
    await page.close();
  });

  it('draws the same picture with the Canvas 2D fallback', async () => {
    const gl = await converged('');
    const cpu = await converged('display=canvas2d');
    expect(await cpu.evaluate(() => (window as any).__pathwise.controller.mode.display)).toBe(
      'canvas2d',
    );
    expect(bitDifferences((await readLinear(cpu)).rgb, reference)).toBe(0);
    const a = await readDisplay(gl);
    const b = await readDisplay(cpu);
    expect(b.width).toBe(a.width);
    expect(maxByteDifference(a.rgba, b.rgba)).toBeLessThanOrEqual(1);
    await gl.close();
    await cpu.close();
  });

  it('renders the same bits with shared memory switched off (shared=off)', async () => {
    const page = await converged('shared=off');
    const mode = await page.evaluate(() => (window as any).__pathwise.controller.mode);
    expect(mode.compute).toBe('transfer');
    expect(await page.locator('#mode').textContent()).toContain('shared=off');
    expect(bitDifferences((await readLinear(page)).rgb, reference)).toBe(0);
    await page.close();
  });

  it('renders the same bits on a page served without COOP/COEP', async () => {
    const plain = await startDemoServer(false);
    try {
      const page = await openDemo(browser, plain.url, `${fixed}&spp=${PASSES}`);
      expect(await page.evaluate(() => crossOriginIsolated)).toBe(false);
      await waitForSpp(page, PASSES);
      const mode = await page.evaluate(() => (window as any).__pathwise.controller.mode);
      expect(mode.compute).toBe('transfer');
      expect(mode.reason).toContain('not cross-origin isolated');
      expect(bitDifferences((await readLinear(page)).rgb, reference)).toBe(0);
      await page.close();
    } finally {
      await plain.server.close();
    }
  });

  it('shows the loader error for a bad scene file and keeps rendering the current scene', async () => {
    const page = await openDemo(browser, url, `${fixed}&spp=100000`);
    await waitForSpp(page, 1);
    const bad = {
      format: 'pathwise-scene/1',
      camera: { position: [0, 0, 0] },
      materials: {},
      shapes: [],
    };
    await page.setInputFiles('#file', {
      name: 'bad.json',
      mimeType: 'application/json',
      buffer: Buffer.from(JSON.stringify(bad)),
    });
    const error = page.locator('#error');
    await error.waitFor({ state: 'visible' });
    const text = (await error.textContent()) ?? '';
    expect(text).toContain('bad.json');
    expect(text).toContain('camera');
    expect(await page.evaluate(() => (window as any).__pathwise.controller.scene.name)).toBe(
      'Cornell box',
    );
    const now = await spp(page);
    await waitForSpp(page, now + 1);
    await page.close();
  });
});
