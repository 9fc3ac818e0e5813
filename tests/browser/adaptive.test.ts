/**
 * Adaptive sampling in the browser (src/view/pilot-gate.ts): past the 16-pass pilot the
 * demo's film must equal the Node core's adaptive render (the command line's
 * `--adaptive on`) bit for bit, with shared memory and with transferred stripes, for
 * any number of workers, and again after a camera move past the pilot (the gate closes
 * and a new map is built). `adaptive=0` gives the uniform render, and the demo's
 * Adaptive switch turns it back on. The element's `adaptive` attribute reaches the
 * controller.
 */
import { describe, expect, it } from 'vitest';
import { SEED, SIZE, fixed, useDemo } from './context.ts';
import { bitDifferences, openDemo, readLinear, waitForSpp } from './harness.ts';
import { nodeRender } from './node-reference.ts';
import { WAIT, addView } from './widget-page.ts';

const ctx = useDemo();
/** Past the pilot (16 passes) by enough that most pixels took some passes and some not. */
const PASSES = 26;

describe('adaptive sampling in the browser (Chromium)', () => {
  const adaptive = () =>
    nodeRender('cornell', SIZE, SIZE, SEED, PASSES, undefined, undefined, true);
  const uniform = () => nodeRender('cornell', SIZE, SIZE, SEED, PASSES);

  it('the Node references differ: the map is not all ones', () => {
    expect(bitDifferences(adaptive(), uniform())).toBeGreaterThan(SIZE * SIZE * 3 * 0.2);
  });

  for (const query of ['workers=1', 'workers=3', 'shared=off&workers=1', 'shared=off&workers=3']) {
    it(`equals the core's adaptive render bit for bit (${query})`, async () => {
      const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}&${query}`);
      await waitForSpp(page, PASSES);
      const c = await page.evaluate(() => {
        const c = (window as any).__pathwise.controller;
        return { adaptive: c.adaptive, compute: c.mode.compute };
      });
      expect(c.adaptive).toBe(true);
      expect(c.compute).toBe(query.startsWith('shared=off') ? 'transfer' : 'shared');
      expect(bitDifferences((await readLinear(page)).rgb, adaptive())).toBe(0);
      // The mean samples per pixel the stats give is the film's own, below the passes.
      const counts = await page.evaluate(() => {
        const c = (window as any).__pathwise.controller;
        const f = c.filmSnapshot();
        let sum = 0;
        for (let p = 0; p < f.width * f.height; p++) sum += f.sums[4 * p + 3];
        return { mean: sum / (f.width * f.height), stats: c.stats() };
      });
      expect(counts.stats.spp).toBe(PASSES);
      expect(counts.stats.samples).toBeCloseTo(counts.mean, 9);
      expect(counts.stats.samples).toBeLessThan(PASSES);
      // The demo's stats line says it (refreshed a few times a second).
      await page.waitForFunction(
        (text) => document.getElementById('s-spp')!.textContent!.includes(text),
        `${PASSES} / ${PASSES}, mean ${counts.mean.toFixed(0)}`,
        { timeout: 10_000 },
      );
      await page.close();
    });
  }

  it('adaptive=0 renders every pixel in every pass (the uniform bits)', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}&adaptive=0`);
    await waitForSpp(page, PASSES);
    expect(await page.evaluate(() => (window as any).__pathwise.controller.adaptive)).toBe(false);
    expect(bitDifferences((await readLinear(page)).rgb, uniform())).toBe(0);
    expect(await page.evaluate(() => (window as any).__pathwise.controller.stats().samples)).toBe(
      PASSES,
    );
    // Switched on with the demo's Adaptive switch: the render starts over, adaptively.
    const box = page.getByRole('checkbox', { name: 'Adaptive' });
    expect(await box.isChecked()).toBe(false);
    await box.check();
    await page.waitForFunction(() => (window as any).__pathwise.controller.adaptive === true);
    await waitForSpp(page, PASSES);
    expect(bitDifferences((await readLinear(page)).rgb, adaptive())).toBe(0);
    await page.close();
  });

  for (const query of ['', 'shared=off']) {
    it(`builds a new map after a camera move past the pilot (${query || 'shared'})`, async () => {
      const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}&${query}`);
      await waitForSpp(page, 20);
      // Past the pilot: the map of the first camera is in use. Move, and again during
      // the new pilot, then let it finish.
      const camera = await page.evaluate(async () => {
        const c = (window as any).__pathwise.controller;
        c.orbit(12, 3);
        await new Promise((r) => setTimeout(r, 30));
        c.orbit(-5, 0);
        return c.getCamera();
      });
      await waitForSpp(page, PASSES);
      const expected = nodeRender('cornell', SIZE, SIZE, SEED, PASSES, camera, undefined, true);
      expect(bitDifferences((await readLinear(page)).rgb, expected)).toBe(0);
      await page.close();
    });
  }

  it('opens the gate without animation frames (a hidden tab runs none, its workers go on)', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}`);
    await waitForSpp(page, 2);
    // Frames stop during the pilot: the gate's timer, armed then, opens it.
    await page.evaluate(() => {
      (window as any).__raf = window.requestAnimationFrame;
      window.requestAnimationFrame = () => 0;
    });
    await waitForSpp(page, PASSES);
    expect(bitDifferences((await readLinear(page)).rgb, adaptive())).toBe(0);
    // Past the pilot (no timer left), a restart with no frames: it arms the timer again.
    await page.evaluate((seed) => (window as any).__pathwise.controller.setSeed(seed), SEED + 1);
    await page.waitForFunction(() => (window as any).__pathwise.controller.stats().spp < 16);
    await waitForSpp(page, PASSES);
    const reseeded = nodeRender(
      'cornell',
      SIZE,
      SIZE,
      SEED + 1,
      PASSES,
      undefined,
      undefined,
      true,
    );
    expect(bitDifferences((await readLinear(page)).rgb, reseeded)).toBe(0);
    await page.close();
  });

  it('<pathwise-view adaptive="false"> turns it off, and the attribute switches it', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `width=16&height=16&spp=1`);
    await page.addScriptTag({ type: 'module', content: "import '/src/widget/register.ts';" });
    await page.waitForFunction(() => customElements.get('pathwise-view') !== undefined);
    await addView(page, 'on', { src: '/scenes/cornell.json', spp: '2' });
    await addView(page, 'off', { src: '/scenes/cornell.json', spp: '2', adaptive: 'false' });
    const state = `['on', 'off'].map((id) => document.getElementById(id).controller?.adaptive)`;
    await page.waitForFunction(`${state}.every((a) => a !== undefined)`, undefined, WAIT);
    expect(await page.evaluate(state)).toEqual([true, false]);
    await page.evaluate(`(() => {
      document.getElementById('on').adaptive = false;
      document.getElementById('off').removeAttribute('adaptive');
    })()`);
    expect(await page.evaluate(state)).toEqual([false, true]);
    await page.close();
  });
});
