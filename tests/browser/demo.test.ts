/**
 * The browser demo end to end in Chromium: isolation, progress, the
 * picture, bit-identity with the Node core, and the controls. Renders are
 * 64×64 so the suite stays short on two cores; nothing here asserts on
 * timing.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { decodePfm, toDisplayByte } from '../../src/core/index.ts';
import { PASSES, SEED, SIZE, WEBGL, fixed, useDemo } from './context.ts';
import {
  bitDifferences,
  maxByteDifference,
  meanRgb,
  openDemo,
  readDisplay,
  readLinear,
  spp,
  waitForPauseSettled,
  waitForSpp,
} from './harness.ts';
import { nodePick, nodeRender } from './node-reference.ts';
import { ROOT } from '../helpers/render.ts';

const ctx = useDemo();

describe('browser demo (Chromium)', () => {
  it('loads cross-origin isolated, spp rises, and shows the Cornell box red left and green right', async () => {
    // A target it cannot reach, so "rises" never races the end of the render.
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=100000&${WEBGL}`);
    expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
    const mode = await page.evaluate(() => (window as any).__pathwise.controller.mode);
    expect(mode.compute).toBe('shared');
    expect(mode.display).toBe('webgl2');
    await waitForSpp(page, 1);
    const first = await spp(page);
    await waitForSpp(page, first + 1);
    await waitForSpp(page, PASSES);
    await page.click('#pause');
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
    // Left to choose, the page names the mode it picked and why.
    const auto = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=1`);
    const picked = await auto.evaluate(() => (window as any).__pathwise.controller.mode);
    const shown = (await auto.locator('#mode').textContent()) ?? '';
    expect(shown).toContain(picked.display === 'webgl2' ? 'WebGL2' : 'Canvas 2D');
    expect(shown).toContain(picked.reason);
    await auto.close();
  });

  it('reads back linear data equal to the Node core render bit for bit', async () => {
    const page = await ctx.converged(WEBGL);
    const img = await readLinear(page);
    expect(img.width).toBe(SIZE);
    expect(img.rgb.length).toBe(ctx.reference.length);
    expect(bitDifferences(img.rgb, ctx.reference)).toBe(0);
    // And the canvas shows that image through the core's display transform,
    // every row of it (rows reach the texture incrementally, as they finish).
    const shown = await readDisplay(page);
    const expected = new Uint8Array(SIZE * SIZE * 4);
    for (let p = 0; p < SIZE * SIZE; p++) {
      for (let c = 0; c < 3; c++) expected[p * 4 + c] = toDisplayByte(ctx.reference[p * 3 + c], 1);
      expected[p * 4 + 3] = 255;
    }
    expect(maxByteDifference(shown.rgba, expected)).toBeLessThanOrEqual(1);
    // Save PFM carries the same linear bits; Save PNG a PNG of the picture.
    const { pfm, png } = await page.evaluate(async () => {
      const c = (window as any).__pathwise.controller;
      const blob: Blob = await c.toBlob();
      return {
        pfm: Array.from(c.toPFM() as Uint8Array),
        png: Array.from(new Uint8Array(await blob.arrayBuffer()).subarray(0, 24)),
      };
    });
    const decoded = decodePfm(Uint8Array.from(pfm));
    expect([decoded.width, decoded.height]).toEqual([SIZE, SIZE]);
    expect(bitDifferences(decoded.rgb, ctx.reference)).toBe(0);
    expect(png.slice(0, 8)).toEqual([137, 80, 78, 71, 13, 10, 26, 10]);
    // IHDR width and height, big-endian.
    expect(png.slice(16, 24)).toEqual([0, 0, 0, SIZE, 0, 0, 0, SIZE]);
    await page.close();
  });

  it('pauses, resumes and resets', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=100000`);
    await waitForSpp(page, 2);
    await page.click('#pause');
    expect(await page.locator('#pause').textContent()).toBe('Resume');
    // Stripes already in hand may still finish their pass; after that nothing moves.
    await waitForPauseSettled(page);
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
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=100000`);
    await waitForSpp(page, 3);
    // Paused, the counts only move when something resets them.
    await page.click('#pause');
    // Stripes already in hand may still finish their pass; after that nothing moves.
    await waitForPauseSettled(page);
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
    // Reset and paused: no sample of the new image yet, so the display keeps
    // the last picture (never black) until new samples cover it.
    expect(maxByteDifference((await readDisplay(page)).rgba, bright.rgba)).toBeLessThanOrEqual(1);
    await page.click('#pause');
    await waitForSpp(page, 1);
    await page.close();
  });

  it('switches scenes with the preset buttons', async () => {
    const page = await ctx.converged('');
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
    const page = await ctx.converged('');
    const before = await page.evaluate(() => (window as any).__pathwise.controller.getCamera());
    const image = await readLinear(page);
    // Paused, nothing renders: the reset by the drag stays visible as 0 spp.
    await page.click('#pause');
    const box = (await page.locator('#view').boundingBox())!;
    const cx = box.x + box.width / 2;
    const cy = box.y + box.height / 2;
    // Record the render width right after each orbit step the drag makes:
    // while the pointer moves, steps render into the low-resolution preview.
    await page.evaluate(() => {
      const c = (window as any).__pathwise.controller;
      const widths: number[] = [];
      (window as any).__widths = widths;
      const orbit = c.orbit.bind(c);
      c.orbit = (dx: number, dy: number) => {
        orbit(dx, dy);
        widths.push(c.stats().width);
      };
    });
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    await page.mouse.move(cx + 20, cy, { steps: 4 });
    await page.mouse.move(cx + 60, cy + 10, { steps: 4 });
    await page.mouse.up();
    const widths: number[] = await page.evaluate(() => (window as any).__widths);
    expect(widths.length).toBeGreaterThan(0);
    expect(Math.max(...widths)).toBeLessThan(SIZE);
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

  it('focuses where clicked and resets when the aperture opens', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=100000&${WEBGL}`);
    await waitForSpp(page, 2);
    await page.click('#pause');
    await waitForPauseSettled(page);
    const shown = await readDisplay(page);
    const box = (await page.locator('#view').boundingBox())!;
    // Click (no drag) a quarter of the way in: the pinhole keeps its samples.
    const before = await spp(page);
    await page.mouse.click(box.x + box.width * 0.25, box.y + box.height * 0.5);
    expect(await spp(page)).toBe(before);
    const focus = await page.evaluate(() => (window as any).__pathwise.controller.getCamera());
    const expected = nodePick('cornell', SIZE, SIZE, 0.25 * SIZE, 0.5 * SIZE);
    expect(Math.abs(focus.focusDistance - expected) / expected).toBeLessThan(0.02);
    await page.locator('#aperture').fill('0.5');
    const open = await page.evaluate(() => (window as any).__pathwise.controller.getCamera());
    expect(open.aperture).toBeGreaterThan(0);
    expect(open.focusDistance).toBe(focus.focusDistance);
    expect(await spp(page)).toBe(0);
    // The old picture stays up until the new samples arrive.
    expect(maxByteDifference((await readDisplay(page)).rgba, shown.rgba)).toBeLessThanOrEqual(1);
    await page.close();
  });

  it('sizes the render from the canvas, the capped devicePixelRatio, the size step and the render scale', async () => {
    // A DPR-3 phone-like page: the ratio counts up to 2.
    const page = await ctx.browser.newPage({
      viewport: { width: 500, height: 400 },
      deviceScaleFactor: 3,
    });
    await page.goto(`${ctx.url}?seed=1&spp=2&workers=2&scale=1`);
    const size = () =>
      page.evaluate(() => {
        const c = (window as any).__pathwise.controller;
        const s = c.stats();
        return { w: s.width, h: s.height, cw: c.canvas.clientWidth, ch: c.canvas.clientHeight };
      });
    await page.waitForFunction(() => (window as any).__pathwise?.controller.stats().spp >= 1);
    /** The demo's size step (64 rows for the Cornell box's 128² reference) and an even width. */
    const expectSize = (s: Awaited<ReturnType<typeof size>>, ratio: number) => {
      expect(s.h % 64).toBe(0);
      expect(Math.abs(s.h - s.ch * ratio)).toBeLessThanOrEqual(32);
      expect(s.w % 2).toBe(0);
      expect(Math.abs(s.w - (s.h * s.cw) / s.ch)).toBeLessThanOrEqual(1);
    };
    const full = await size();
    expectSize(full, 2);
    await page.locator('#scale').fill('0.5');
    const half = await size();
    expectSize(half, 1);
    // A wider window: the film follows once the size has settled.
    await page.setViewportSize({ width: 700, height: 400 });
    await page.waitForFunction(
      () => {
        const c = (window as any).__pathwise.controller;
        const s = c.stats();
        return Math.abs(s.width - (s.height * c.canvas.clientWidth) / c.canvas.clientHeight) <= 1;
      },
      null,
      { timeout: 60_000 },
    );
    expect((await size()).w).toBeGreaterThan(half.w);
    await page.close();
  });

  it('shows the loader error for a bad scene file and keeps rendering the current scene', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=100000`);
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
    // Bytes of a dropped file get the loader's strict UTF-8 rule (no silent U+FFFD).
    await page.setInputFiles('#file', {
      name: 'names.json',
      mimeType: 'application/json',
      buffer: readFileSync(join(ROOT, 'tests/fuzz/corpus/invalid-utf8-names.json')),
    });
    await expect
      .poll(async () => (await error.textContent()) ?? '')
      .toMatch(/^names\.json: scene file is not valid UTF-8 at byte 351 \(line 29\)/);
    await page.close();
  });
});
