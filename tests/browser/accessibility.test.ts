/**
 * The demo without a mouse, in Chromium: every slider found by its
 * accessible name, a keyboard-only walk through every control (the image
 * included: arrow keys orbit, + and − dolly, Enter focuses), pinch to zoom
 * on a touch screen, and the benchmark's result announced (aria-live).
 */
import type { FileChooser, Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { useDemo } from './context.ts';
import { openDemo, waitForSpp } from './harness.ts';

const ctx = useDemo();

const SLIDERS = ['Max bounces', 'Exposure', 'Aperture', 'Render scale', 'Workers'];

function camera(page: Page) {
  return page.evaluate(() => (window as any).__pathwise.controller.getCamera()) as Promise<{
    position: number[];
    target: number[];
    focusDistance: number;
  }>;
}

function distance(c: { position: number[]; target: number[] }): number {
  return Math.hypot(...c.position.map((p, i) => p - c.target[i]));
}

/** A short description of the focused element: its id, else its text. */
function focused(page: Page): Promise<string> {
  return page.evaluate(() => {
    const el = document.activeElement as HTMLElement | null;
    if (!el || el === document.body) return '';
    return el.id ? `#${el.id}` : (el.textContent ?? '').trim();
  });
}

/** Presses Tab (or Shift+Tab) until `target` has focus (at most 40 times); returns the stops. */
async function tabTo(page: Page, target: string, backwards = false): Promise<string[]> {
  const stops: string[] = [];
  for (let i = 0; i < 40; i++) {
    await page.keyboard.press(backwards ? 'Shift+Tab' : 'Tab');
    const now = await focused(page);
    stops.push(now);
    if (now === target) return stops;
  }
  throw new Error(`Tab never reached ${target}; stops: ${stops.join(', ')}`);
}

describe('demo accessibility (Chromium)', () => {
  it('finds every slider by its accessible name, with its value in words', async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'seed=1&width=64&height=64&spp=4');
    await waitForSpp(page, 1);
    for (const name of SLIDERS) {
      const slider = page.getByRole('slider', { name, exact: true });
      expect(await slider.count(), name).toBe(1);
      expect(await slider.getAttribute('aria-valuetext'), name).toBeTruthy();
    }
    // The aperture says what its number is: a lens radius, in scene units.
    await page.getByRole('slider', { name: 'Aperture' }).fill('0.5');
    expect(
      await page.getByRole('slider', { name: 'Aperture' }).getAttribute('aria-valuetext'),
    ).toMatch(/^radius [\d.]+ scene units$/);
    expect(await page.locator('#aperture-out').textContent()).toMatch(/scene units/);
    // The image and the error plot are named images; the open-scene control is a button.
    expect(await page.getByRole('img', { name: /Cornell box, path-traced image/ }).count()).toBe(1);
    expect(await page.getByRole('img', { name: /Error against time/ }).count()).toBe(1);
    expect(await page.getByRole('button', { name: 'Open scene…' }).count()).toBe(1);
    expect(await page.getByRole('checkbox', { name: 'Denoise' }).count()).toBe(1);
    expect(await page.getByRole('checkbox', { name: 'Adaptive' }).count()).toBe(1);
    await page.close();
  });

  it('works with the keyboard alone: every control in tab order, the image orbits, zooms and focuses', async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'seed=1&width=64&height=64&spp=100000');
    // Listened for from the start: Playwright turns on file-chooser
    // interception without waiting for it, and a key press sent right after
    // a late listener can overtake it.
    const choosers: FileChooser[] = [];
    page.on('filechooser', (chooser) => choosers.push(chooser));
    await waitForSpp(page, 1);
    const stops = await tabTo(page, '#benchmark');
    const expected = [
      'Cornell',
      'Spheres',
      'Mirror',
      'Sky',
      '#open-scene',
      '#about-open',
      '#view',
      '#pause',
      '#reset',
      '#reset-view',
      '#save-png',
      '#save-pfm',
      '#bounces',
      '#exposure',
      '#aperture',
      '#scale',
      '#workers',
      '#adaptive',
      '#denoise',
      '#benchmark',
    ];
    expect(stops).toEqual(expected);

    // The image: arrow keys orbit, + and − dolly, Enter focuses on the centre.
    await tabTo(page, '#view', true);
    const start = await camera(page);
    await page.keyboard.press('ArrowLeft');
    const orbited = await camera(page);
    expect(orbited.position).not.toEqual(start.position);
    expect(distance(orbited)).toBeCloseTo(distance(start), 6);
    await page.keyboard.press('+');
    const closer = await camera(page);
    expect(distance(closer)).toBeLessThan(distance(orbited) * 0.95);
    await page.keyboard.press('-');
    expect(distance(await camera(page))).toBeCloseTo(distance(orbited), 6);
    const before = (await camera(page)).focusDistance;
    await page.keyboard.press('Enter');
    const focus = (await camera(page)).focusDistance;
    expect(focus).not.toBe(before);
    // Reset view (a button, by keyboard) goes back to the scene's camera.
    await tabTo(page, '#reset-view');
    await page.keyboard.press('Enter');
    expect((await camera(page)).position).toEqual(start.position);

    // A slider moves with the arrow keys.
    await tabTo(page, '#exposure');
    await page.keyboard.press('ArrowRight');
    expect(await page.locator('#exposure').inputValue()).toBe('1.05');
    expect(await page.locator('#exposure-out').textContent()).toBe('× 1.05');

    // Open scene… opens the file picker from the keyboard.
    await tabTo(page, '#open-scene', true);
    await page.keyboard.press('Enter');
    await expect.poll(() => choosers.length).toBe(1);
    // Several files at once: a scene with the mesh and map files it names.
    expect(choosers[0].isMultiple()).toBe(true);

    // A preset by keyboard.
    await page.keyboard.press('Shift+Tab'); // Sky (a mesh under a map)
    await page.keyboard.press('Enter');
    await page.waitForFunction(
      () => (window as any).__pathwise.controller.scene.name !== 'Cornell box',
    );

    // About opens with Enter and closes with Escape.
    await tabTo(page, '#about-open');
    await page.keyboard.press('Enter');
    expect(await page.locator('#about').isVisible()).toBe(true);
    await page.keyboard.press('Escape');
    expect(await page.locator('#about').isVisible()).toBe(false);
    await page.close();
  });

  it('zooms with a two-finger pinch on a touch screen', async () => {
    const context = await ctx.browser.newContext({
      viewport: { width: 390, height: 700 },
      hasTouch: true,
      isMobile: true,
    });
    const page = await context.newPage();
    await page.goto(`${ctx.url}?seed=1&width=64&height=64&spp=100000`);
    await page.waitForFunction(() => (window as any).__pathwise?.controller.stats().spp >= 1);
    const box = (await page.locator('#view').boundingBox())!;
    const cx = box.x + box.width / 2;
    const cy = box.y + box.height / 2;
    const cdp = await context.newCDPSession(page);
    const touch = (type: 'touchStart' | 'touchMove' | 'touchEnd', spread: number) =>
      cdp.send('Input.dispatchTouchEvent', {
        type,
        touchPoints:
          type === 'touchEnd'
            ? []
            : [
                { x: cx - spread, y: cy, id: 1 },
                { x: cx + spread, y: cy, id: 2 },
              ],
      });
    const before = distance(await camera(page));
    await touch('touchStart', 20);
    for (let spread = 24; spread <= 80; spread += 8) await touch('touchMove', spread);
    await touch('touchEnd', 0);
    const after = distance(await camera(page));
    // Fingers four times as far apart: the eye four times as close.
    expect(after / before).toBeCloseTo(20 / 80, 1);
    await context.close();
  });

  it('announces the benchmark result and never shows its internal target', async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'seed=1&width=64&height=64&spp=16&bench=1');
    await waitForSpp(page, 1);
    const result = page.getByRole('status'); // the slider outputs are aria-hidden (valuetext says it)
    expect(await result.getAttribute('aria-live')).toBe('polite');
    expect(await result.getAttribute('id')).toBe('bench-result');
    // Every text the spp line shows is recorded as it changes: the benchmark's shows for
    // about a second, which a poll on a loaded machine can miss.
    await page.evaluate(() => {
      const line = document.getElementById('s-spp')!;
      const seen: string[] = ((window as any).__sppTexts = []);
      new MutationObserver(() => seen.push(line.textContent ?? '')).observe(line, {
        childList: true,
        characterData: true,
        subtree: true,
      });
    });
    await page.getByRole('button', { name: 'Benchmark (1 s)' }).press('Enter');
    await page.waitForFunction(() =>
      /M rays\/s/.test(document.getElementById('bench-result')!.textContent!),
    );
    const texts: string[] = await page.evaluate(() => (window as any).__sppTexts);
    const during = texts.filter((t) => t.includes('benchmark'));
    expect(during.length).toBeGreaterThan(0);
    for (const t of during) expect(t).not.toMatch(/1048576/);
    expect(await result.textContent()).toMatch(/^Benchmark: [\d.]+ M rays\/s/);
    // Back to the user's target afterwards.
    await page.waitForFunction(() => /\/ 16/.test(document.getElementById('s-spp')!.textContent!));
    await page.close();
  });
});
