/**
 * Memory faults of <pathwise-view>, in Chromium: a huge CSS size ×
 * devicePixelRatio renders under the accumulator cap (src/view/film-cap.ts)
 * and says so with a `fallback` event; a scene asking for 16384 × 16384 and
 * a SharedArrayBuffer that cannot be allocated are reported, and nothing
 * crashes the tab.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { Film } from '../../src/core/index.ts';
import { MAX_FILM_BYTES } from '../../src/view/film-cap.ts';
import { useDemo } from './context.ts';
import { root } from './harness.ts';
import { WAIT, addView, events, useWidgetPages, waitForEvent } from './widget-page.ts';

const ctx = useDemo();

/** Fixture pages in fresh contexts, each closed after its test. */
const open = useWidgetPages(ctx);

describe('<pathwise-view> memory faults (Chromium)', () => {
  it('a huge CSS size × devicePixelRatio renders under the accumulator cap and says so', async () => {
    const { page, errors } = await open({ deviceScaleFactor: 2 });
    await page.evaluate(() => {
      const style = document.createElement('style');
      style.textContent = '#huge { width: 6000px; height: 4000px; }';
      document.head.append(style);
    });
    const view = await addView(page, 'huge', {
      src: '/scenes/cornell.json',
      spp: '1',
      'render-scale': '1',
    });
    await page.waitForFunction(
      () =>
        ((document.querySelector('#huge') as any).log as any[]).some(
          (e) => e.type === 'fallback' && e.detail.renderScale !== undefined,
        ),
      undefined,
      WAIT,
    );
    const fallback = (await events(page, view)).find((e) => e.detail?.renderScale !== undefined)!;
    const stats = await page.evaluate(() =>
      (document.querySelector('#huge') as any).controller.stats(),
    );
    // 12000 × 8000 device pixels asked for; the film fits the cap, same shape.
    expect(Film.byteLength(stats.width, stats.height)).toBeLessThanOrEqual(MAX_FILM_BYTES);
    expect(stats.width).toBeGreaterThan(1000);
    expect(Math.abs(stats.width / stats.height - 1.5)).toBeLessThan(0.01);
    expect(fallback.detail.renderScale).toBeCloseTo(stats.width / 12000, 2);
    expect(fallback.detail.reason).toMatch(/accumulator cap/);
    expect((await events(page, view)).filter((e) => e.type === 'error')).toEqual([]);
    expect(errors).toEqual([]);
    // Free the memory at once for whatever runs next on this machine.
    await page.evaluate(() => document.querySelector('#huge')!.remove());
  });

  it('a scene asking for 16384 × 16384 is an error event naming the limit', async () => {
    const { page, errors } = await open();
    const scene = JSON.parse(readFileSync(join(root, 'scenes', 'cornell.json'), 'utf8'));
    scene.settings = { ...scene.settings, width: 16384, height: 16384 };
    await page.evaluate((scene) => {
      const el = document.createElement('pathwise-view') as any;
      el.id = 'big';
      el.log = [];
      el.addEventListener('error', (e: CustomEvent) =>
        el.log.push({ type: 'error', detail: e.detail }),
      );
      el.scene = scene;
      document.body.append(el);
    }, scene);
    await waitForEvent(page, '#big', 'error');
    const [error] = await events(page, '#big');
    expect(error.detail.message).toMatch(/width.*height.*must be at most 16777216 pixels/);
    expect(errors).toEqual([]);
  });

  it('a SharedArrayBuffer that cannot be allocated is caught: a smaller film, or an error', async () => {
    const { page, errors } = await open({
      init: () => {
        // As a browser out of memory: new SharedArrayBuffer throws above 400 KB.
        const Real = SharedArrayBuffer;
        (globalThis as any).SharedArrayBuffer = class extends Real {
          constructor(n: number) {
            if (n > 400_000) throw new RangeError('Array buffer allocation failed');
            super(n);
          }
        };
      },
    });
    // Sized from the canvas (300 × 150 × 80 B is over the limit): a smaller film.
    await page.evaluate(() => {
      const style = document.createElement('style');
      style.textContent = '#canvas-sized { width: 300px; height: 150px; }';
      document.head.append(style);
    });
    const view = await addView(page, 'canvas-sized', {
      src: '/scenes/cornell.json',
      spp: '2',
      'render-scale': '1',
    });
    await waitForEvent(page, view, 'converged');
    const fallback = (await events(page, view)).find((e) => e.detail?.renderScale !== undefined);
    expect(fallback?.detail.reason).toMatch(/memory for a larger film could not be had/);
    expect(fallback?.detail.renderScale).toBeLessThan(1);
    // A fixed size the memory cannot hold: an error event, no crash.
    const cornell = JSON.parse(readFileSync(join(root, 'scenes', 'cornell.json'), 'utf8'));
    const message = await page.evaluate(async (scene) => {
      const canvas = document.createElement('canvas');
      document.body.append(canvas);
      const t = (window as any).pathwise.createPathTracer(canvas, {
        scene,
        width: 400,
        height: 400,
      });
      const detail = await new Promise<any>((r) =>
        t.addEventListener('error', (e: CustomEvent) => r(e.detail)),
      );
      t.destroy();
      return detail.message as string;
    }, cornell);
    // Its quick first pass runs in a quarter-size preview film: the first to fail.
    expect(message).toMatch(
      /could not allocate shared memory \(SharedArrayBuffer\) for a (400×400|100×100) film .*allocation failed/,
    );
    expect(errors).toEqual([]);
  });
});
