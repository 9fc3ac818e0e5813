/**
 * Lifecycle and memory faults of <pathwise-view>, in Chromium, on a page
 * that loads the widget from the sources (fixtures/widget.html, which also
 * counts live Worker objects, WebGL contexts and pending animation frames):
 * 100 rapid connect/disconnect cycles leak nothing; `src` set while a load
 * is in flight ends with the last one; a hidden (and frozen) tab resumes
 * where it stopped; a worker that cannot start is reported once, not
 * restarted for ever; a huge CSS size × devicePixelRatio renders under the
 * accumulator cap and says so; a scene asking for 16384 × 16384 and a
 * SharedArrayBuffer that cannot be allocated are reported.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import type { BrowserContext, Page } from 'playwright-core';
import { afterEach, describe, expect, it } from 'vitest';
import { Film } from '../../src/core/index.ts';
import { MAX_FILM_BYTES } from '../../src/view/film-cap.ts';
import { useDemo } from './context.ts';
import { bitDifferences, root } from './harness.ts';
import { nodeRender } from './node-reference.ts';

const ctx = useDemo();
const WAIT = { timeout: 60_000, polling: 50 };

let context: BrowserContext | null = null;
afterEach(async () => {
  await context?.close();
  context = null;
});

interface Opened {
  page: Page;
  errors: string[];
  warnings: string[];
}

/** The fixture page in a fresh context; `init` runs before any of the page's scripts. */
async function openWidgetPage(
  options: { deviceScaleFactor?: number; init?: () => void } = {},
): Promise<Opened> {
  context = await ctx.browser.newContext({
    viewport: { width: 800, height: 600 },
    deviceScaleFactor: options.deviceScaleFactor ?? 1,
  });
  const page = await context.newPage();
  const errors: string[] = [];
  const warnings: string[] = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(m.text());
    if (m.type() === 'warning') warnings.push(m.text());
  });
  if (options.init) await page.addInitScript(options.init);
  await page.goto(`${ctx.url}tests/browser/fixtures/widget.html`);
  await page.waitForFunction(() => (window as any).__ready === true);
  return { page, errors, warnings };
}

/** Adds a <pathwise-view> with `attributes` (and an event log) to the page; returns its selector. */
async function addView(page: Page, id: string, attributes: Record<string, string>) {
  await page.evaluate(
    ({ id, attributes }) => {
      const el = document.createElement('pathwise-view') as any;
      el.id = id;
      for (const [k, v] of Object.entries(attributes)) el.setAttribute(k, v);
      el.log = [];
      for (const type of ['load', 'progress', 'converged', 'error', 'fallback']) {
        el.addEventListener(type, (e: CustomEvent) =>
          el.log.push({ type, detail: type === 'load' ? e.detail.scene.name : e.detail }),
        );
      }
      document.body.append(el);
    },
    { id, attributes },
  );
  return `#${id}`;
}

async function events(page: Page, selector: string): Promise<{ type: string; detail: any }[]> {
  return page.evaluate((s) => (document.querySelector(s) as any).log, selector);
}

async function waitForEvent(page: Page, selector: string, type: string): Promise<void> {
  await page.waitForFunction(
    ({ s, t }) => ((document.querySelector(s) as any)?.log ?? []).some((e: any) => e.type === t),
    { s: selector, t: type },
    WAIT,
  );
}

async function linear(page: Page, selector: string): Promise<Float32Array> {
  const rgb = await page.evaluate(
    (s) =>
      Array.from((document.querySelector(s) as any).controller.readLinear().rgb as Float32Array),
    selector,
  );
  return Float32Array.from(rgb);
}

/** What the page holds: live render workers (Web Locks held), Worker objects, contexts, frames. */
async function held(page: Page) {
  return page.evaluate(async () => {
    const h = (window as any).__held;
    const locks = await navigator.locks.query();
    return {
      lifeLocks: (locks.held ?? []).filter((l) => l.name?.startsWith('pathwise-render-worker-'))
        .length,
      workers: h.workersMade - h.workersTerminated,
      workersMade: h.workersMade,
      contexts: h.liveContexts(),
      frames: h.frames.size,
      canvases: document.querySelectorAll('canvas').length,
    };
  });
}

describe('<pathwise-view> lifecycle and memory faults (Chromium)', () => {
  it('100 rapid connect/disconnect cycles leak no workers, contexts or animation frames', async () => {
    const { page, errors } = await openWidgetPage();
    const made = await page.evaluate(async () => {
      const el = document.createElement('pathwise-view');
      el.setAttribute('src', '/scenes/cornell.json');
      el.setAttribute('spp', '4');
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      for (let i = 0; i < 100; i++) {
        document.body.append(el);
        // Rapid, at varied depths: same task, after a microtask, after a frame or two.
        if (i % 4 === 1) await Promise.resolve();
        if (i % 4 === 2) await frame();
        if (i % 4 === 3) {
          await frame();
          await new Promise((r) => setTimeout(r, 5));
        }
        el.remove();
        if (i % 3 === 0) await Promise.resolve();
      }
      await frame();
      return (window as any).__held.workersMade;
    });
    // Workers end (their life locks are released) within Chromium's two seconds.
    await page.waitForFunction(
      async () => {
        const locks = await navigator.locks.query();
        return !(locks.held ?? []).some((l) => l.name?.startsWith('pathwise-render-worker-'));
      },
      undefined,
      WAIT,
    );
    await page.waitForTimeout(100);
    const after = await held(page);
    expect(after).toMatchObject({ lifeLocks: 0, workers: 0, contexts: 0, frames: 0, canvases: 0 });
    expect(made).toBeGreaterThan(0);
    // A view added after all that still renders the exact image.
    const view = await addView(page, 'last', { src: '/scenes/cornell.json', spp: '4' });
    await waitForEvent(page, view, 'converged');
    expect(bitDifferences(await linear(page, view), nodeRender('cornell', 64, 64, 0, 4))).toBe(0);
    expect(errors).toEqual([]);
    console.log(`connect/disconnect: 100 cycles, ${made} workers started, none left`);
  });

  it('100 WebGL2 tracers made and destroyed leave no WebGL context (Chromium allows ~16)', async () => {
    const { page, errors, warnings } = await openWidgetPage();
    const cornell = JSON.parse(readFileSync(join(root, 'scenes', 'cornell.json'), 'utf8'));
    const result = await page.evaluate(async (scene) => {
      const { createPathTracer } = (window as any).pathwise;
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      const modes = new Set<string>();
      for (let i = 0; i < 100; i++) {
        const canvas = document.createElement('canvas');
        document.body.append(canvas);
        const t = createPathTracer(canvas, {
          scene,
          display: 'webgl2',
          width: 16,
          height: 16,
          spp: 2,
        });
        modes.add(t.mode.display);
        if (i % 2) await frame();
        t.destroy();
        canvas.remove();
      }
      // The last one, kept: it must still show a picture.
      const canvas = document.createElement('canvas');
      document.body.append(canvas);
      const t = createPathTracer(canvas, {
        scene,
        display: 'webgl2',
        width: 16,
        height: 16,
        spp: 2,
      });
      while (t.stats().spp < 2) await frame();
      const { rgba } = t.readDisplay();
      let sum = 0;
      for (let i = 0; i < rgba.length; i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
      const live = (window as any).__held.liveContexts();
      t.destroy();
      canvas.remove();
      await frame();
      return {
        modes: [...modes],
        brightness: sum / (rgba.length * 0.75),
        live,
        mode: t.mode.display,
      };
    }, cornell);
    expect(result.modes).toEqual(['webgl2']);
    expect(result.mode).toBe('webgl2');
    expect(result.live).toBe(1);
    expect(result.brightness).toBeGreaterThan(20);
    const after = await held(page);
    expect(after.contexts).toBe(0);
    expect(after.frames).toBe(0);
    expect(warnings.filter((w) => /too many active webgl contexts/i.test(w))).toEqual([]);
    expect(errors).toEqual([]);
  });

  it('src set while a load is in flight: the last one wins, whichever finishes first', async () => {
    const { page, errors } = await openWidgetPage();
    const spheres = readFileSync(join(root, 'scenes', 'spheres.json'), 'utf8');
    const cornell = readFileSync(join(root, 'scenes', 'cornell.json'), 'utf8');
    // Two slow scenes and a fast one.
    await page.route('**/slow/*.json', async (route) => {
      await new Promise((r) => setTimeout(r, 1500));
      const body = route.request().url().endsWith('spheres.json') ? spheres : cornell;
      await route.fulfill({ body, contentType: 'application/json' }).catch(() => {});
    });
    await page.route('**/fast/*.json', (route) =>
      route.fulfill({
        body: route.request().url().endsWith('spheres.json') ? spheres : cornell,
        contentType: 'application/json',
      }),
    );
    const names = {
      cornell: JSON.parse(cornell).name as string,
      spheres: JSON.parse(spheres).name as string,
    };
    // A slow load, then a fast one: the fast (last) one wins, and stays.
    const a = await addView(page, 'a', { src: '/slow/cornell.json', spp: '2' });
    await page.evaluate(() =>
      (document.querySelector('#a') as any).setAttribute('src', '/fast/spheres.json'),
    );
    // A fast load, then a slow one: the slow (last) one wins.
    const b = await addView(page, 'b', { src: '/fast/cornell.json', spp: '2' });
    await page.evaluate(() =>
      (document.querySelector('#b') as any).setAttribute('src', '/slow/spheres.json'),
    );
    // Three in a row, the middle one slow: the third wins.
    const c = await addView(page, 'c', { src: '/fast/cornell.json', spp: '2' });
    await page.evaluate(() => {
      const el = document.querySelector('#c') as any;
      el.src = '/slow/spheres.json';
      el.src = '/fast/spheres.json';
    });
    await page.waitForTimeout(2500);
    for (const [view, name] of [
      [a, names.spheres],
      [b, names.spheres],
      [c, names.spheres],
    ]) {
      await waitForEvent(page, view, 'converged');
      const scene = await page.evaluate(
        (s) => (document.querySelector(s) as any).controller.scene.name,
        view,
      );
      expect(scene, view).toBe(name);
      const loads = (await events(page, view))
        .filter((e) => e.type === 'load')
        .map((e) => e.detail);
      // The superseded load never reported a scene after the winner's.
      expect(loads[loads.length - 1], view).toBe(name);
      expect(
        (await events(page, view)).filter((e) => e.type === 'error'),
        view,
      ).toEqual([]);
    }
    expect(errors).toEqual([]);
  });

  it('a hidden, frozen tab resumes where it stopped and ends bit-identical', async () => {
    const { page, errors } = await openWidgetPage();
    const view = await addView(page, 'v', { src: '/scenes/cornell.json', spp: '24' });
    await page.waitForFunction(
      () => (document.querySelector('#v') as any).controller?.stats().spp >= 2,
      undefined,
      WAIT,
    );
    // Headless Chromium never hides a tab, so the page is told it is hidden
    // (visibilityState, the event) and frozen for real through the
    // DevTools protocol: timers, frames and workers stop.
    const atHide = await page.evaluate(async () => {
      const el = document.querySelector('#v') as any;
      Object.defineProperty(document, 'visibilityState', {
        configurable: true,
        get: () => 'hidden',
      });
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => true });
      document.dispatchEvent(new Event('visibilitychange'));
      // Stripes in hand finish; then nothing moves.
      let last = -1;
      while (el.controller.progress() !== last) {
        last = el.controller.progress();
        await new Promise((r) => setTimeout(r, 150));
      }
      return { progress: last, paused: el.controller.paused, frames: el.controller.framesRun() };
    });
    expect(atHide.paused).toBe(true);
    const cdp = await context!.newCDPSession(page);
    await cdp.send('Page.setWebLifecycleState', { state: 'frozen' });
    await new Promise((r) => setTimeout(r, 800));
    await cdp.send('Page.setWebLifecycleState', { state: 'active' });
    const hidden = await page.evaluate(async () => {
      const el = document.querySelector('#v') as any;
      await new Promise((r) => setTimeout(r, 300));
      return { progress: el.controller.progress(), frames: el.controller.framesRun() };
    });
    // Nothing traced, nothing drawn while hidden; nothing thrown away either.
    expect(hidden.progress).toBe(atHide.progress);
    expect(hidden.frames - atHide.frames).toBeLessThanOrEqual(1);
    expect(atHide.progress).toBeLessThan(24);
    await page.evaluate(() => {
      Object.defineProperty(document, 'visibilityState', {
        configurable: true,
        get: () => 'visible',
      });
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => false });
      document.dispatchEvent(new Event('visibilitychange'));
    });
    await waitForEvent(page, view, 'converged');
    const progress = (await events(page, view))
      .filter((e) => e.type === 'progress')
      .map((e) => e.detail.spp as number);
    // Resumed from where it stopped: spp never went back.
    for (let i = 1; i < progress.length; i++)
      expect(progress[i]).toBeGreaterThanOrEqual(progress[i - 1]);
    expect(bitDifferences(await linear(page, view), nodeRender('cornell', 64, 64, 0, 24))).toBe(0);
    expect(errors).toEqual([]);
  });

  it('a worker that cannot start gives one clear error and is not restarted for ever', async () => {
    const { page } = await openWidgetPage();
    const view = await addView(page, 'w', {
      src: '/scenes/cornell.json',
      'worker-url': '/no-such-worker.js',
    });
    await waitForEvent(page, view, 'error');
    const first = await held(page);
    await page.waitForTimeout(1500);
    const later = await held(page);
    expect(later.workersMade).toBe(first.workersMade);
    const message = await page.evaluate(
      () =>
        (document.querySelector('#w') as any).shadowRoot.querySelector('[part=message]')
          .textContent,
    );
    expect(message).toMatch(/worker/);
    expect(await page.evaluate(() => (window as any).__faults.replaced)).toBe(0);
  });

  it('a huge CSS size × devicePixelRatio renders under the accumulator cap and says so', async () => {
    const { page, errors } = await openWidgetPage({ deviceScaleFactor: 2 });
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
    const { page, errors } = await openWidgetPage();
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
    const { page, errors } = await openWidgetPage({
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
