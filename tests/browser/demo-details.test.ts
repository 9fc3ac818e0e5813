/**
 * Small things a new user of the demo runs into, in Chromium: a scene name
 * in the URL that does not exist, a scene with more bounces than the
 * slider's usual range, and a window too short or too narrow for the usual
 * layout (the whole image must stay on screen).
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { useDemo } from './context.ts';
import { openDemo, root, waitForSpp } from './harness.ts';

const ctx = useDemo();

describe('demo details (Chromium)', () => {
  it('says so when ?scene= names no preset, and shows the Cornell box', async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'scene=nope&width=32&height=32&spp=1');
    const error = page.locator('#error');
    await error.waitFor({ state: 'visible' });
    expect(await error.textContent()).toMatch(/no scene "nope".*cornell, spheres, mirror/);
    expect(await page.getByRole('alert').textContent()).toMatch(/nope/);
    expect(await page.evaluate(() => (window as any).__pathwise.controller.scene?.name)).toBe(
      'Cornell box',
    );
    await page.close();
  });

  it("follows a scene's bounce limit beyond 12 on the slider", async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'width=32&height=32&spp=1');
    await waitForSpp(page, 1);
    // furnace-glass.json asks for 64 bounces.
    const text = readFileSync(join(root, 'scenes', 'furnace-glass.json'), 'utf8');
    expect(JSON.parse(text).settings.maxBounces).toBe(64);
    await page.setInputFiles('#file', {
      name: 'furnace-glass.json',
      mimeType: 'application/json',
      buffer: Buffer.from(text),
    });
    await page.waitForFunction(() => (window as any).__pathwise.controller.maxBounces === 64);
    const slider = page.getByRole('slider', { name: 'Max bounces' });
    expect(await slider.inputValue()).toBe('64');
    expect(Number(await slider.getAttribute('max'))).toBeGreaterThanOrEqual(64);
    expect(await slider.getAttribute('aria-valuetext')).toBe('64 bounces');
    // Back on a preset, the slider shows that scene's limit again.
    await page.click('[data-preset="cornell"]');
    await page.waitForFunction(() => (window as any).__pathwise.controller.maxBounces === 6);
    expect(await slider.inputValue()).toBe('6');
    await page.close();
  });

  for (const viewport of [
    { width: 1280, height: 600 },
    { width: 1024, height: 700 },
    { width: 800, height: 480 },
    { width: 390, height: 844 },
  ]) {
    it(`keeps the whole image on screen at ${viewport.width}×${viewport.height}`, async () => {
      const page = await ctx.browser.newPage({ viewport });
      await page.goto(`${ctx.url}?seed=1&spp=1`);
      await page.waitForFunction(() => (window as any).__pathwise?.controller.stats().spp >= 1);
      const box = (await page.locator('#view').boundingBox())!;
      expect(box.y).toBeGreaterThanOrEqual(0);
      expect(box.x).toBeGreaterThanOrEqual(0);
      expect(box.y + box.height).toBeLessThanOrEqual(viewport.height);
      expect(box.x + box.width).toBeLessThanOrEqual(viewport.width);
      // …and it is not squeezed to nothing either.
      expect(box.height).toBeGreaterThan(Math.min(300, viewport.height / 2));
      await page.close();
    });
  }
});
