/**
 * A lost WebGL2 context, in Chromium (SwiftShader, `display=webgl2`): the
 * context is lost and restored ten times during a render with
 * WEBGL_lose_context. While it is lost, a Canvas 2D stand-in laid over the
 * canvas keeps showing the image and tracing goes on; each loss and each
 * restoration fires `fallback`; after each restoration the WebGL2 display is
 * rebuilt. Not one sample may be lost: the final linear image must equal
 * the Node core's bit for bit, and the final picture the undisturbed one's.
 */
import { describe, expect, it } from 'vitest';
import { SEED, WEBGL } from './context.ts';
import { useDemo } from './context.ts';
import {
  bitDifferences,
  maxByteDifference,
  openDemo,
  readDisplay,
  readLinear,
  waitForSpp,
} from './harness.ts';
import { nodeRender } from './node-reference.ts';

const ctx = useDemo();

const SIZE = 32;
const CYCLES = 10;
/**
 * The first target; each cycle raises it a few passes (traced while the
 * context is away, a bounded render on any machine), and the final target
 * is set after the cycles, a little above the passes done by then.
 */
const FIRST = 4;
const query = (spp: number) =>
  `width=${SIZE}&height=${SIZE}&seed=${SEED}&spp=${spp}&workers=1&${WEBGL}`;

interface Cycle {
  /** Display mode and stand-in canvases while lost, then after the restoration. */
  lostMode: string;
  standIns: number;
  restoredMode: string;
  standInsAfter: number;
  /** The stand-in covers the canvas exactly (CSS pixels). */
  sameBox: boolean;
  /** Mean brightness (0–255) just before the loss and on the stand-in. */
  before: number;
  during: number;
  /** Fractional passes done at the loss and at the restoration. */
  progressAtLoss: number;
  progressAtRestore: number;
}

describe('WebGL2 context loss (Chromium)', () => {
  it(`survives ${CYCLES} lose/restore cycles during a render with not one sample lost`, async () => {
    const page = await openDemo(ctx.browser, ctx.url, query(FIRST));
    expect(await page.evaluate(() => (window as any).__pathwise.controller.mode.display)).toBe(
      'webgl2',
    );
    await waitForSpp(page, 2);
    const cycles: Cycle[] = await page.evaluate(async (cycles) => {
      const w = window as any;
      const c = w.__pathwise.controller;
      const canvas = document.getElementById('view') as HTMLCanvasElement;
      const gl = canvas.getContext('webgl2')!;
      const ext = gl.getExtension('WEBGL_lose_context')!;
      const events: string[] = [];
      c.addEventListener('fallback', (e: CustomEvent) => events.push(e.detail.display));
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      const until = async (test: () => boolean) => {
        while (!test()) await frame();
      };
      const brightness = () => {
        const { rgba } = c.readDisplay();
        let sum = 0;
        for (let i = 0; i < rgba.length; i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
        return sum / ((rgba.length / 4) * 3);
      };
      const out = [];
      for (let i = 0; i < cycles; i++) {
        const before = brightness();
        const progressAtLoss = c.progress();
        c.setTargetSpp(Math.ceil(progressAtLoss) + 3);
        const seen = events.length;
        ext.loseContext();
        await until(() => events.length > seen);
        // A few frames on the stand-in while the workers go on tracing.
        for (let f = 0; f < 6; f++) await frame();
        await new Promise((r) => setTimeout(r, 100));
        const standIn = canvas.nextElementSibling as HTMLCanvasElement;
        const a = canvas.getBoundingClientRect();
        const b = standIn.getBoundingClientRect();
        const lost = {
          lostMode: c.mode.display,
          standIns: document.querySelectorAll('canvas').length,
          sameBox:
            Math.abs(a.left - b.left) < 0.5 &&
            Math.abs(a.top - b.top) < 0.5 &&
            Math.abs(a.width - b.width) < 0.5 &&
            Math.abs(a.height - b.height) < 0.5,
          during: brightness(),
          progressAtRestore: c.progress(),
        };
        ext.restoreContext();
        await until(() => events.length > seen + 1);
        await frame();
        out.push({
          ...lost,
          before,
          progressAtLoss,
          restoredMode: c.mode.display,
          standInsAfter: document.querySelectorAll('canvas').length,
        });
      }
      (w as any).__events = events;
      return out;
    }, CYCLES);
    const canvases = cycles[0].standInsAfter;
    for (const [i, cycle] of cycles.entries()) {
      expect(cycle.lostMode, `cycle ${i}`).toBe('canvas2d');
      expect(cycle.standIns, `cycle ${i}`).toBe(canvases + 1);
      expect(cycle.sameBox, `cycle ${i}`).toBe(true);
      expect(cycle.restoredMode, `cycle ${i}`).toBe('webgl2');
      expect(cycle.standInsAfter, `cycle ${i}`).toBe(canvases);
      // The stand-in shows the image (more samples by then, so a little different).
      expect(cycle.before, `cycle ${i}`).toBeGreaterThan(20);
      expect(Math.abs(cycle.during - cycle.before) / cycle.before, `cycle ${i}`).toBeLessThan(0.15);
      expect(cycle.progressAtRestore, `cycle ${i}`).toBeGreaterThanOrEqual(cycle.progressAtLoss);
    }
    // Tracing went on while the context was away.
    const traced = cycles.reduce((s, c) => s + c.progressAtRestore - c.progressAtLoss, 0);
    expect(traced).toBeGreaterThan(0);
    const events = await page.evaluate(() => (window as any).__events as string[]);
    expect(events).toEqual(
      Array.from({ length: 2 * CYCLES }, (_, i) => (i % 2 ? 'webgl2' : 'canvas2d')),
    );
    // The final target: two passes above every stripe's count once the
    // stripes in hand are finished (paused, progress still).
    const passes = await page.evaluate(async () => {
      const c = (window as any).__pathwise.controller;
      c.pause();
      let last = -1;
      while (c.progress() !== last) {
        last = c.progress();
        await new Promise((r) => setTimeout(r, 100));
      }
      const target = Math.ceil(last) + 2;
      c.setTargetSpp(target);
      c.resume();
      return target;
    });
    await waitForSpp(page, passes);
    // Adaptive sampling is on by default (past the 16-pass pilot: the adaptive reference).
    const expected = nodeRender('cornell', SIZE, SIZE, SEED, passes, undefined, undefined, true);
    expect(bitDifferences((await readLinear(page)).rgb, expected)).toBe(0);
    // The rebuilt display shows what an undisturbed one shows.
    const undisturbed = await openDemo(ctx.browser, ctx.url, query(passes));
    await waitForSpp(undisturbed, passes);
    const a = await readDisplay(page);
    const b = await readDisplay(undisturbed);
    expect(maxByteDifference(a.rgba, b.rgba)).toBe(0);
    console.log(
      `context loss: ${CYCLES} losses survived, ${traced.toFixed(2)} passes traced while lost, ` +
        `linear image bit-identical at ${passes} spp`,
    );
    await undisturbed.close();
    await page.close();
  });
});
