/**
 * The demo's live error plot on the Cornell box, in Chromium: the true
 * relMSE against the shipped Mitsuba reference falls as samples accrue,
 * sits at or below the variance estimate (Sobol sampling), equals the
 * figures Node computes from the same film exactly, is withdrawn when the view
 * leaves the reference's camera and comes back with Reset view.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { errorFigures, gridLayout, referenceLuminance } from '../../src/app/error-grid.ts';
import type { ErrorPoint } from '../../src/app/error-plot.ts';
import { decodePfm } from '../../src/core/index.ts';
import { useDemo } from './context.ts';
import { openDemo, root, waitForSpp } from './harness.ts';

const ctx = useDemo();
const SIZE = 128;
const SPP = 64;

function points(page: import('playwright-core').Page): Promise<ErrorPoint[]> {
  return page.evaluate(() => (window as any).__pathwise.errorMeter.points);
}

describe('live error plot (Chromium)', () => {
  it('shows the true error against the Mitsuba reference falling on the Cornell box', async () => {
    // The target is raised in steps (which keeps the samples, and the
    // series): the meter, which takes a point at most every 250 ms, takes one
    // at each step however fast the machine renders, so the series always has
    // points from 2 to SPP spp. It waits at the first step for the reference,
    // so that every later point has a true error.
    const page = await openDemo(
      ctx.browser,
      ctx.url,
      `width=${SIZE}&height=${SIZE}&seed=1&spp=2&workers=1`,
    );
    // The meter takes a point a moment after each step is reached.
    const pointAt = (n: number) =>
      page.waitForFunction(
        (n) => (window as any).__pathwise.errorMeter.points.at(-1)?.spp === n,
        n,
        { timeout: 60_000 },
      );
    await waitForSpp(page, 2);
    await pointAt(2);
    await page.waitForFunction(() => (window as any).__pathwise.errorMeter.reference !== null);
    for (const step of [4, 8, 16, 32, SPP]) {
      await page.evaluate((n) => (window as any).__pathwise.controller.setTargetSpp(n), step);
      await waitForSpp(page, step);
      await pointAt(step);
    }
    const series = await points(page);
    // Only the points of the steps are compared: when the target is reached, every pixel
    // holds exactly that many samples, so each is a fixed number for this seed. A point
    // taken between steps (when the meter's tick falls inside a pass) is labelled with
    // the fewest samples a stripe holds while most hold one more; how many more depends
    // on when it was taken, which a loaded machine changes.
    const steps = new Set([2, 4, 8, 16, 32, SPP]);
    const truth = series.filter((p) => Number.isFinite(p.truth) && steps.has(p.spp));
    expect(truth.length).toBeGreaterThanOrEqual(5);
    for (let i = 1; i < series.length; i++) {
      expect(series[i].seconds).toBeGreaterThan(series[i - 1].seconds);
      expect(series[i].spp).toBeGreaterThan(series[i - 1].spp);
    }
    // Falling: twice the samples or more, clearly less error (relMSE ∝ 1/spp).
    for (const a of truth) {
      for (const b of truth) {
        if (b.spp >= 2 * a.spp)
          expect(b.truth, `${a.spp} → ${b.spp} spp`).toBeLessThan(0.75 * a.truth);
      }
    }
    const last = series.at(-1)!;
    // Sobol's stratification: the truth at or below the independent-sample estimate.
    expect(last.truth / last.estimated).toBeGreaterThan(0.3);
    expect(last.truth / last.estimated).toBeLessThan(1.1);

    // The page's film is the Node core's bit for bit (demo.test.ts); the
    // figures computed on it in the page equal Node's, exactly.
    const film = await page.evaluate(() => {
      const snap = (window as any).__pathwise.controller.filmSnapshot();
      return {
        sums: Array.from(snap.sums as Float32Array),
        hi: Array.from(snap.hi as Float64Array),
        lo: Array.from(snap.lo as Float64Array),
      };
    });
    const pfm = decodePfm(readFileSync(join(root, 'tests/references/cornell.pfm')));
    const f = errorFigures(
      SIZE,
      Float32Array.from(film.sums),
      { hi: Float64Array.from(film.hi), lo: Float64Array.from(film.lo) },
      gridLayout(SIZE, SIZE, pfm.width, pfm.height)!,
      referenceLuminance(pfm.width, pfm.height, pfm.rgb),
    );
    expect(last.truth).toBe(f.relMse);
    expect(last.estimated).toBe(f.estimatedRelMse);

    // The plot is drawn and its numbers are in words too.
    const caption = (await page.locator('#error-caption').textContent()) ?? '';
    expect(caption).toMatch(new RegExp(`\\(${SPP} spp\\): estimated [\\d.e-]+, true [\\d.e-]+`));
    expect(await page.locator('#error-plot').getAttribute('aria-label')).toContain(caption);
    // The stats' Noise is the same figure as the caption's "estimated" (one definition).
    const estimated = /estimated ([\d.e-]+),/.exec(caption)![1]!;
    await expect.poll(() => page.locator('#s-noise').textContent()).toBe(estimated);
    const colours = await page.evaluate(() => {
      const canvas = document.getElementById('error-plot') as HTMLCanvasElement;
      const data = canvas.getContext('2d')!.getImageData(0, 0, canvas.width, canvas.height).data;
      const seen = new Set<number>();
      for (let i = 0; i < data.length; i += 4)
        seen.add((data[i] << 16) | (data[i + 1] << 8) | data[i + 2]);
      return seen.size;
    });
    expect(colours).toBeGreaterThan(10);
    await page.close();
  });

  it('withdraws the true error away from the reference view and restores it with Reset view', async () => {
    const page = await openDemo(ctx.browser, ctx.url, `width=${SIZE}&height=${SIZE}&seed=1&spp=8`);
    await waitForSpp(page, 2);
    await page.evaluate(() => (window as any).__pathwise.controller.orbit(30, 0));
    await waitForSpp(page, 8);
    await page.waitForFunction(
      () => (window as any).__pathwise.errorMeter.points.at(-1)?.spp === 8,
    );
    const moved = await points(page);
    expect(moved.every((p) => Number.isNaN(p.truth))).toBe(true);
    // The estimate needs two samples in a cell's pixels: a point taken at 1 spp
    // (if the meter's tick came then, which depends on the machine's speed) has
    // none, or one from the cells the second pass had already covered. Either
    // way it is never zero or negative.
    expect(moved.filter((p) => p.spp >= 2).every((p) => p.estimated > 0)).toBe(true);
    expect(moved.every((p) => Number.isNaN(p.estimated) || p.estimated > 0)).toBe(true);
    expect(moved.at(-1)!.estimated).toBeGreaterThan(0);
    expect(await page.locator('#error-caption').textContent()).toMatch(/Reset view/);
    await page.click('#reset-view');
    await page.waitForFunction(() => {
      const p = (window as any).__pathwise.errorMeter.points.at(-1);
      return p && p.spp === 8 && Number.isFinite(p.truth);
    });
    await page.close();
  });
});
