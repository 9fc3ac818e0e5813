/**
 * The progressive display in Chromium, as a user drags: no frame may go
 * dark (each restart keeps the last picture under the pixels the new pass
 * has not reached), the full film refines on top of the preview after
 * release, a pass fills the frame spread out rather than top to bottom, and
 * the automatic render scale follows the measured speed under a capped
 * devicePixelRatio. Nothing here asserts on timing; speeds are measured in
 * bench/first-image.ts.
 */
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { MIN_AUTO_PIXELS, PASS_BUDGET_S } from '../../src/view/auto-scale.ts';
import { WEBGL, useDemo } from './context.ts';
import { openDemo, waitForSpp } from './harness.ts';

const ctx = useDemo();

/** Waits until no speed measurement may change the automatic scale any more. */
async function waitForScaleSettled(page: Page): Promise<void> {
  await page.waitForFunction(
    () => !(window as any).__pathwise.controller.renderScaleInfo().measuring,
    undefined,
    { timeout: 60_000 },
  );
}

/** A frame darker than this fraction of the image at rest fails the drag test. */
const MIN_BRIGHTNESS = 0.6;

/** Starts sampling the mean brightness (0–255) of what the display shows, every frame. */
function startSampling(page: Page): Promise<void> {
  return page.evaluate(() => {
    const w = window as any;
    const c = w.__pathwise.controller;
    w.__frames = [] as { t: number; mean: number; width: number; spp: number }[];
    w.__sampling = true;
    const tick = () => {
      if (!w.__sampling) return;
      const { rgba } = c.readDisplay();
      let sum = 0;
      for (let i = 0; i < rgba.length; i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
      const s = c.stats();
      w.__frames.push({
        t: performance.now(),
        mean: sum / ((rgba.length / 4) * 3),
        width: s.width,
        spp: s.spp,
      });
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
}

async function stopSampling(
  page: Page,
): Promise<{ t: number; mean: number; width: number; spp: number }[]> {
  return page.evaluate(() => {
    const w = window as any;
    w.__sampling = false;
    return w.__frames;
  });
}

async function meanBrightness(page: Page): Promise<number> {
  return page.evaluate(() => {
    const { rgba } = (window as any).__pathwise.controller.readDisplay();
    let sum = 0;
    for (let i = 0; i < rgba.length; i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
    return sum / ((rgba.length / 4) * 3);
  });
}

/**
 * Drags back and forth across the middle of the canvas for about 1.5 s
 * (small moves, so the view stays inside the box and its brightness is the
 * scene's, not the dark outside), then releases and waits until the full
 * film is back with two passes and at least 20 frames were sampled after
 * the release (a frame count, not a fixed time: a loaded machine draws
 * fewer frames per second).
 */
async function dragAndRelease(page: Page): Promise<{ releasedAt: number }> {
  const box = (await page.locator('#view').boundingBox())!;
  const cx = box.x + box.width / 2;
  const cy = box.y + box.height / 2;
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  for (let i = 0; i < 48; i++) {
    const phase = Math.sin((i / 12) * Math.PI);
    await page.mouse.move(cx + 24 * phase, cy + 6 * phase);
    await page.waitForTimeout(25);
  }
  await page.mouse.up();
  const releasedAt = await page.evaluate(() => performance.now());
  await page.waitForFunction(
    (t) => {
      const frames = (window as any).__frames as { t: number; spp: number }[];
      const after = frames.filter((f) => f.t >= t);
      return after.length >= 20 && after[after.length - 1].spp >= 2;
    },
    releasedAt,
    { timeout: 60_000 },
  );
  return { releasedAt };
}

describe('progressive display while dragging (Chromium)', () => {
  for (const [label, query] of [
    ['Canvas 2D', 'display=canvas2d'],
    ['WebGL2', WEBGL],
  ] as const) {
    it(`keeps every frame above ${MIN_BRIGHTNESS * 100} % of the resting image during a drag and after release (${label})`, async () => {
      // The default page (automatic scale), at a laptop-like size.
      const page = await ctx.browser.newPage({ viewport: { width: 900, height: 600 } });
      await page.goto(`${ctx.url}?seed=1&${query}`);
      await page.waitForFunction(() => (window as any).__pathwise?.controller);
      await waitForSpp(page, 8);
      // The warm speed measurement may still raise the scale once (it needs
      // 300 ms of the full film's passes); the drag starts after it.
      await waitForScaleSettled(page);
      const rest = await meanBrightness(page);
      expect(rest).toBeGreaterThan(20);
      const fullWidth = await page.evaluate(
        () => (window as any).__pathwise.controller.stats().width,
      );
      await startSampling(page);
      const { releasedAt } = await dragAndRelease(page);
      const frames = await stopSampling(page);
      const during = frames.filter((f) => f.t < releasedAt);
      const after = frames.filter((f) => f.t >= releasedAt);
      const ratios = frames.map((f) => f.mean / rest);
      const min = (xs: number[]) => Math.min(...xs);
      console.log(
        `${label}: rest ${rest.toFixed(1)}; ${during.length} frames while dragging, min ratio ${min(
          during.map((f) => f.mean / rest),
        ).toFixed(3)}; ${after.length} after release, min ratio ${min(
          after.map((f) => f.mean / rest),
        ).toFixed(3)}`,
      );
      expect(during.length).toBeGreaterThan(10);
      expect(after.length).toBeGreaterThan(10);
      // The drag really ran in the preview, and the full film came back after it.
      expect(Math.min(...during.map((f) => f.width))).toBeLessThan(fullWidth);
      expect(after[after.length - 1].width).toBe(fullWidth);
      expect(min(ratios)).toBeGreaterThanOrEqual(MIN_BRIGHTNESS);
      await page.close();
    });
  }

  it('after release the full film starts from zero samples yet shows the preview, refining on top of it', async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'seed=1&width=128&height=128&spp=100000');
    await waitForSpp(page, 4);
    const rest = await meanBrightness(page);
    // What a drag does, without the pointer's timing (a rest of 150 ms on
    // a busy machine would end the preview early): preview on, a camera
    // step, the preview's first pass, then pause and release.
    const previewWidth = await page.evaluate(async () => {
      const c = (window as any).__pathwise.controller;
      c.beginPreview();
      c.orbit(10, 0);
      while (!(c.films.preview?.passesDone() >= 1)) await new Promise(requestAnimationFrame);
      const width = c.stats().width;
      c.pause();
      c.endPreview();
      return width;
    });
    expect(previewWidth).toBeLessThan(128);
    const state = await page.evaluate(() => (window as any).__pathwise.controller.stats());
    expect(state.width).toBe(128);
    expect(state.spp).toBe(0);
    expect((await meanBrightness(page)) / rest).toBeGreaterThan(MIN_BRIGHTNESS);
    await page.close();
  });

  it('spreads a pass over the whole frame instead of filling it from the top', async () => {
    // One worker and a tall film: the first full pass takes long enough to
    // catch partway; a pass missed (a busy main thread) is started again.
    const page = await openDemo(ctx.browser, ctx.url, 'seed=1&width=96&height=384&spp=1&workers=1');
    const quarters = await page.evaluate(async () => {
      const c = (window as any).__pathwise.controller;
      for (let attempt = 0; attempt < 20;) {
        const snap = c.filmSnapshot();
        if (snap) {
          const rows = new Uint8Array(snap.height);
          let covered = 0;
          for (let y = 0; y < snap.height; y++) {
            rows[y] = snap.sums[(y * snap.width + snap.width - 1) * 4 + 3] > 0 ? 1 : 0;
            covered += rows[y];
          }
          const fraction = covered / snap.height;
          if (fraction >= 0.1 && fraction <= 0.6) {
            const q = [0, 0, 0, 0];
            for (let y = 0; y < snap.height; y++) q[Math.floor((4 * y) / snap.height)] += rows[y];
            return { fraction, q };
          }
          if (fraction > 0.6) {
            c.reset();
            attempt++;
          }
        }
        await new Promise((r) => setTimeout(r, 2));
      }
      return null;
    });
    expect(quarters, 'the pass was not caught between 10 % and 60 %').not.toBeNull();
    // Every quarter of the frame got rows, within a factor of two of an even share.
    const share = (quarters!.fraction * 384) / 4;
    for (const n of quarters!.q) {
      expect(n).toBeGreaterThan(share / 2);
      expect(n).toBeLessThan(share * 2);
    }
    await page.close();
  });

  it('chooses the render scale from the measured speed, under a devicePixelRatio capped at 2', async () => {
    const page = await ctx.browser.newPage({
      viewport: { width: 420, height: 800 },
      deviceScaleFactor: 3,
    });
    await page.goto(`${ctx.url}?seed=1`);
    await page.waitForFunction(() => (window as any).__pathwise?.controller.stats().spp >= 1);
    // The warm measurement may raise the scale once, a few passes in.
    await waitForScaleSettled(page);
    const r = await page.evaluate(() => {
      const c = (window as any).__pathwise.controller;
      const s = c.stats();
      return {
        info: c.renderScaleInfo(),
        w: s.width,
        h: s.height,
        cw: c.canvas.clientWidth,
        ch: c.canvas.clientHeight,
        timeline: c.timeline(),
      };
    });
    expect(r.info.auto).toBe(true);
    expect(r.info.samplesPerSecond).toBeGreaterThan(0);
    // Never more than CSS × 2 (not × 3) in either direction.
    expect(r.h).toBeLessThanOrEqual(r.ch * 2 * r.info.scale + 32);
    expect(r.info.scale).toBeLessThanOrEqual(1);
    // The scale's pixels take the pass budget at the measured speed (unless clamped).
    const pixels = r.cw * r.ch * 4 * r.info.scale ** 2;
    const floor = Math.sqrt(MIN_AUTO_PIXELS / (r.cw * r.ch * 4));
    if (r.info.scale > floor * 1.0001 && r.info.scale < 1) {
      expect(pixels / r.info.samplesPerSecond).toBeCloseTo(PASS_BUDGET_S, 6);
    }
    // The first whole picture came before the first full image, both after the scene loaded.
    expect(r.timeline.firstPicture).toBeGreaterThan(r.timeline.sceneLoaded);
    expect(r.timeline.firstImage).toBeGreaterThanOrEqual(r.timeline.firstPicture);
    await page.close();
  });
});
