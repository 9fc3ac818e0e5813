/**
 * A lost WebGL2 context under <pathwise-view>, in Chromium: the element on
 * its WebGL2 path (a GPU's name reported, see pretendGpu; the context is
 * SwiftShader's), the context lost and restored ten times with
 * WEBGL_lose_context during a render. The element itself must say what
 * happened with `fallback` events (display 'canvas2d' with the reason, then
 * 'webgl2'), show the image through the stand-in inside its shadow root
 * meanwhile, and lose no sample: the final linear image equals the Node
 * core's bit for bit and the final picture an undisturbed element's.
 * Removing the element afterwards leaves no context, canvas or frame.
 */
import { describe, expect, it } from 'vitest';
import { SEED, useDemo } from './context.ts';
import { bitDifferences, maxByteDifference } from './harness.ts';
import { nodeRender } from './node-reference.ts';
import {
  WAIT,
  addView,
  events,
  held,
  linear,
  useWidgetPages,
  pretendGpu,
  waitForEvent,
} from './widget-page.ts';

const ctx = useDemo();
const CYCLES = 10;
/** The fixture's element is 64 × 64 CSS pixels at devicePixelRatio 1; rendered at half that. */
const SIZE = 32;

/** Fixture pages in fresh contexts, each closed after its test. */
const open = useWidgetPages(ctx);

interface Cycle {
  lostMode: string;
  /** Canvases in the shadow root while lost (the stand-in added), then after. */
  shadowCanvases: number;
  shadowCanvasesAfter: number;
  sameBox: boolean;
  restoredMode: string;
  before: number;
  during: number;
  progressAtLoss: number;
  progressAtRestore: number;
}

describe('<pathwise-view> WebGL2 context loss (Chromium)', () => {
  it(`fires fallback on the element through ${CYCLES} lose/restore cycles and loses no sample`, async () => {
    const { page, errors } = await open({ init: pretendGpu });
    const attributes = { src: '/scenes/cornell.json', seed: String(SEED), 'render-scale': '0.5' };
    const view = await addView(page, 'v', { ...attributes, spp: '4' });
    await page.waitForFunction(
      () => (document.querySelector('#v') as any).controller?.stats().spp >= 2,
      undefined,
      WAIT,
    );
    expect(await page.evaluate(() => (document.querySelector('#v') as any).mode.display)).toBe(
      'webgl2',
    );
    const start = (await events(page, view)).filter((e) => e.type === 'fallback').length;
    const cycles: Cycle[] = await page.evaluate(async (cycles) => {
      const el = document.querySelector('#v') as any;
      const root = el.shadowRoot as ShadowRoot;
      const canvas = root.querySelector('canvas') as HTMLCanvasElement;
      const ext = canvas.getContext('webgl2')!.getExtension('WEBGL_lose_context')!;
      const fallbacks = () => (el.log as any[]).filter((e) => e.type === 'fallback').length;
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      const until = async (test: () => boolean) => {
        while (!test()) await frame();
      };
      const brightness = () => {
        const { rgba } = el.controller.readDisplay();
        let sum = 0;
        for (let i = 0; i < rgba.length; i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
        return sum / ((rgba.length / 4) * 3);
      };
      const out = [];
      for (let i = 0; i < cycles; i++) {
        const before = brightness();
        const progressAtLoss = el.controller.progress();
        // A few more passes to trace while the context is away: bounded, so
        // the render stays small on a fast machine.
        el.spp = Math.ceil(progressAtLoss) + 3;
        const seen = fallbacks();
        ext.loseContext();
        await until(() => fallbacks() > seen);
        for (let f = 0; f < 6; f++) await frame();
        await new Promise((r) => setTimeout(r, 100));
        const standIn = canvas.nextElementSibling as HTMLElement;
        const a = canvas.getBoundingClientRect();
        const b = standIn.getBoundingClientRect();
        const lost = {
          lostMode: el.mode.display,
          shadowCanvases: root.querySelectorAll('canvas').length,
          sameBox:
            standIn instanceof HTMLCanvasElement &&
            Math.abs(a.left - b.left) < 0.5 &&
            Math.abs(a.top - b.top) < 0.5 &&
            Math.abs(a.width - b.width) < 0.5 &&
            Math.abs(a.height - b.height) < 0.5,
          during: brightness(),
          progressAtRestore: el.controller.progress(),
        };
        ext.restoreContext();
        await until(() => fallbacks() > seen + 1);
        await frame();
        out.push({
          ...lost,
          before,
          progressAtLoss,
          restoredMode: el.mode.display,
          shadowCanvasesAfter: root.querySelectorAll('canvas').length,
        });
      }
      return out;
    }, CYCLES);
    for (const [i, cycle] of cycles.entries()) {
      expect(cycle.lostMode, `cycle ${i}`).toBe('canvas2d');
      expect(cycle.shadowCanvases, `cycle ${i}`).toBe(2);
      expect(cycle.sameBox, `cycle ${i}`).toBe(true);
      expect(cycle.restoredMode, `cycle ${i}`).toBe('webgl2');
      expect(cycle.shadowCanvasesAfter, `cycle ${i}`).toBe(1);
      // The stand-in shows the image (a few more samples by then).
      expect(cycle.before, `cycle ${i}`).toBeGreaterThan(20);
      expect(Math.abs(cycle.during - cycle.before) / cycle.before, `cycle ${i}`).toBeLessThan(0.15);
      expect(cycle.progressAtRestore, `cycle ${i}`).toBeGreaterThanOrEqual(cycle.progressAtLoss);
    }
    const traced = cycles.reduce((s, c) => s + c.progressAtRestore - c.progressAtLoss, 0);
    expect(traced).toBeGreaterThan(0);
    // The element said what happened, each time, in order.
    const fallbacks = (await events(page, view))
      .filter((e) => e.type === 'fallback')
      .slice(start)
      .map((e) => e.detail);
    expect(fallbacks.map((d) => d.display)).toEqual(
      Array.from({ length: 2 * CYCLES }, (_, i) => (i % 2 ? 'webgl2' : 'canvas2d')),
    );
    for (const [i, d] of fallbacks.entries()) {
      expect(d.reason, `fallback ${i}`).toMatch(
        i % 2 ? /context was restored/ : /context was lost/,
      );
    }
    // The final target: two passes above every stripe's count once the
    // stripes in hand are finished (paused through the element, progress still).
    const target = await page.evaluate(async () => {
      const el = document.querySelector('#v') as any;
      el.paused = true;
      let last = -1;
      while (el.controller.progress() !== last) {
        last = el.controller.progress();
        await new Promise((r) => setTimeout(r, 100));
      }
      const target = Math.ceil(last) + 2;
      el.spp = target;
      el.paused = false;
      return target;
    });
    await waitForEvent(page, view, 'converged');
    // Adaptive sampling is on by default (past the 16-pass pilot: the adaptive reference).
    const expected = nodeRender('cornell', SIZE, SIZE, SEED, target, undefined, undefined, true);
    expect(bitDifferences(await linear(page, view), expected)).toBe(0);
    // The rebuilt display shows what an undisturbed element's shows.
    const calm = await addView(page, 'calm', { ...attributes, spp: String(target) });
    await waitForEvent(page, calm, 'converged');
    const pictures = await page.evaluate(() =>
      ['#v', '#calm'].map((s) =>
        Array.from((document.querySelector(s) as any).controller.readDisplay().rgba as Uint8Array),
      ),
    );
    expect(maxByteDifference(Uint8Array.from(pictures[0]), Uint8Array.from(pictures[1]))).toBe(0);
    // Removed, the elements leave no context, stand-in or frame behind.
    await page.evaluate(async () => {
      for (const s of ['#v', '#calm']) document.querySelector(s)!.remove();
      await new Promise((r) => requestAnimationFrame(r));
    });
    await page.waitForTimeout(100);
    expect(await held(page)).toMatchObject({ contexts: 0, frames: 0, canvases: 0 });
    expect(errors).toEqual([]);
    console.log(
      `widget context loss: ${CYCLES} losses survived, ${2 * CYCLES} fallback events, ` +
        `${traced.toFixed(2)} passes traced while lost, linear image bit-identical at ${target} spp`,
    );
  });
});
