/**
 * Lifecycle faults of <pathwise-view>, in Chromium, on the fixture page
 * (widget-page.ts): 100 rapid connect/disconnect cycles leak no workers,
 * WebGL contexts or animation frames, on the Canvas 2D path and on the
 * WebGL2 one; `src` set while a load is in flight ends with the last one;
 * a hidden (and frozen) tab resumes where it stopped; a worker that cannot
 * start (a bad URL, a CSP) is reported once, not restarted for ever.
 * Memory faults are in widget-memory.test.ts, context loss in
 * widget-context-loss.test.ts.
 */
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { useDemo } from './context.ts';
import { bitDifferences, root } from './harness.ts';
import { nodeRender } from './node-reference.ts';
import { ADAPTIVE_PILOT } from '../../src/core/film/adaptive.ts';
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

/** Fixture pages in fresh contexts, each closed after its test. */
const open = useWidgetPages(ctx);

describe('<pathwise-view> lifecycle faults (Chromium)', () => {
  // Headless Chromium's WebGL2 is software, where the element picks Canvas 2D;
  // with a GPU's name reported it takes its WebGL2 path (a context per start).
  for (const display of ['canvas2d', 'webgl2'] as const) {
    it(`100 rapid connect/disconnect cycles leak no workers, contexts or animation frames (${display})`, async () => {
      const { page, errors, warnings } = await open(
        display === 'webgl2' ? { init: pretendGpu } : {},
      );
      const cycled = await page.evaluate(async () => {
        const el = document.createElement('pathwise-view') as any;
        el.setAttribute('src', '/scenes/cornell.json');
        el.setAttribute('spp', '4');
        const frame = () => new Promise((r) => requestAnimationFrame(r));
        const modes = new Set<string>();
        for (let i = 0; i < 100; i++) {
          document.body.append(el);
          // Rapid, at varied depths: same task, after a microtask, after a frame or two.
          if (i % 4 === 1) await Promise.resolve();
          if (i % 4 === 2) await frame();
          if (i % 4 === 3) {
            await frame();
            await new Promise((r) => setTimeout(r, 5));
          }
          if (el.mode) modes.add(el.mode.display);
          el.remove();
          if (i % 3 === 0) await Promise.resolve();
        }
        // One more cycle, connected until its scene has loaded: however slow the machine
        // (a loaded one may load no scene within the rapid cycles), workers were made.
        const loaded = new Promise((r) => el.addEventListener('load', r, { once: true }));
        document.body.append(el);
        await loaded;
        if (el.mode) modes.add(el.mode.display);
        el.remove();
        await frame();
        const h = (window as any).__held;
        return { workers: h.workersMade, contexts: h.contexts.size, modes: [...modes] };
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
      expect(after).toMatchObject({
        lifeLocks: 0,
        workers: 0,
        contexts: 0,
        frames: 0,
        canvases: 0,
      });
      expect(cycled.workers).toBeGreaterThan(0);
      expect(cycled.modes).toEqual([display]);
      // On WebGL2 each started element made its own context (and a probe):
      // far more than the ~16 Chromium keeps alive, had any leaked.
      if (display === 'webgl2') expect(cycled.contexts).toBeGreaterThan(32);
      // A view added after all that still renders the exact image.
      const view = await addView(page, 'last', { src: '/scenes/cornell.json', spp: '4' });
      await waitForEvent(page, view, 'converged');
      expect(await page.evaluate(() => (document.querySelector('#last') as any).mode.display)).toBe(
        display,
      );
      expect(bitDifferences(await linear(page, view), nodeRender('cornell', 64, 64, 0, 4))).toBe(0);
      expect(warnings.filter((w) => /too many active webgl contexts/i.test(w))).toEqual([]);
      expect(errors).toEqual([]);
      console.log(
        `connect/disconnect (${display}): 100 cycles, ${cycled.workers} workers and ` +
          `${cycled.contexts} WebGL contexts made, none left`,
      );
    });
  }

  it('100 WebGL2 tracers made and destroyed leave no WebGL context (Chromium allows ~16)', async () => {
    const { page, errors, warnings } = await open();
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
    const { page, errors } = await open();
    const spheres = readFileSync(join(root, 'scenes', 'spheres.json'), 'utf8');
    const cornell = readFileSync(join(root, 'scenes', 'cornell.json'), 'utf8');
    // Two slow scenes and a fast one. The slow responses are counted, so
    // that the test can wait until each has been delivered (or refused, its
    // fetch aborted) whatever the machine's speed.
    const slow = { started: 0, finished: 0 };
    await page.route('**/slow/*.json', async (route) => {
      slow.started++;
      try {
        await new Promise((r) => setTimeout(r, 1500));
        const body = route.request().url().endsWith('spheres.json') ? spheres : cornell;
        await route.fulfill({ body, contentType: 'application/json' }).catch(() => {});
      } finally {
        slow.finished++;
      }
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
    // Every slow response is out (a superseded one is the case under test),
    // and has had a moment to reach the page; then each view has loaded its
    // last scene and converged on it (view b converged on its first, fast
    // scene before the slow one arrived).
    await expect
      .poll(() => slow.started > 0 && slow.finished === slow.started, { timeout: WAIT.timeout })
      .toBe(true);
    await page.waitForTimeout(500);
    for (const [view, name] of [
      [a, names.spheres],
      [b, names.spheres],
      [c, names.spheres],
    ]) {
      await page.waitForFunction(
        ({ s, name }) => {
          const log: { type: string; detail: any }[] = (document.querySelector(s) as any).log;
          let loaded = -1;
          log.forEach((e, i) => {
            if (e.type === 'load') loaded = e.detail === name ? i : -1;
          });
          return loaded >= 0 && log.slice(loaded).some((e) => e.type === 'converged');
        },
        { s: view, name },
        WAIT,
      );
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
    const { context, page, errors } = await open();
    // A target no machine reaches before the tab is hidden; the final one is
    // set after it is shown again.
    const view = await addView(page, 'v', { src: '/scenes/cornell.json', spp: '100000' });
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
      // Stripes in hand finish; then nothing moves: none is in hand any more
      // and neither progress nor the frame count has changed over 150 ms (a
      // quiet spell alone could be a slow stripe on a loaded machine).
      const state = () => `${el.controller.progress()}/${el.controller.framesRun()}`;
      let last = state();
      for (;;) {
        await new Promise((r) => setTimeout(r, 150));
        const now = state();
        if (now === last && !el.controller.films.active()?.busy()) break;
        last = now;
      }
      return {
        progress: el.controller.progress(),
        paused: el.controller.paused,
        frames: el.controller.framesRun(),
      };
    });
    expect(atHide.paused).toBe(true);
    const cdp = await context.newCDPSession(page);
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
    await page.evaluate(() => {
      Object.defineProperty(document, 'visibilityState', {
        configurable: true,
        get: () => 'visible',
      });
      Object.defineProperty(document, 'hidden', { configurable: true, get: () => false });
      document.dispatchEvent(new Event('visibilitychange'));
    });
    // Shown again: tracing goes on from there; then paused (stripes in hand
    // finished) and given a target two passes above the progress reached.
    const target = await page.evaluate(async (from) => {
      const el = document.querySelector('#v') as any;
      const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
      while (el.controller.progress() < from + 1) await sleep(20);
      el.paused = true;
      let last = -1;
      while (el.controller.progress() !== last) {
        last = el.controller.progress();
        await sleep(100);
      }
      const target = Math.ceil(last) + 2;
      el.spp = target;
      el.paused = false;
      return target;
    }, atHide.progress);
    await waitForEvent(page, view, 'converged');
    const progress = (await events(page, view))
      .filter((e) => e.type === 'progress')
      .map((e) => e.detail.spp as number);
    // Resumed from where it stopped: spp never went back.
    for (let i = 1; i < progress.length; i++)
      expect(progress[i]).toBeGreaterThanOrEqual(progress[i - 1]);
    // Past the pilot the element samples adaptively (its default): the reference too.
    const adaptive = target > ADAPTIVE_PILOT;
    const expected = nodeRender('cornell', 64, 64, 0, target, undefined, undefined, adaptive);
    expect(bitDifferences(await linear(page, view), expected)).toBe(0);
    expect(errors).toEqual([]);
  });

  it('a scene whose every sample is dropped gives one error event, not a black picture', async () => {
    // tests/cli/empty-image.test.ts has the same scene through the command line.
    const { page, errors } = await open();
    const view = await addView(page, 'v', {
      src: '/tests/browser/fixtures/hot-box.json',
      spp: '8',
    });
    await waitForEvent(page, view, 'error');
    const state = await page.evaluate(async (s) => {
      const el = document.querySelector(s) as any;
      // A while longer: the error is sent once, and the render stops.
      const spp = el.controller.stats().spp;
      await new Promise((r) => setTimeout(r, 500));
      return {
        paused: el.controller.paused,
        sppBefore: spp,
        sppAfter: el.controller.stats().spp,
        shown: el.shadowRoot.querySelector('[part="message"]')?.hidden === false,
        message: el.shadowRoot.querySelector('[part="message"]')?.textContent ?? '',
      };
    }, view);
    const log = await events(page, view);
    const errorEvents = log.filter((e) => e.type === 'error');
    expect(errorEvents).toHaveLength(1);
    expect(errorEvents[0].detail.message).toMatch(/^no image: all \d+ samples were not finite/);
    expect(log.some((e) => e.type === 'converged')).toBe(false);
    expect(state.shown).toBe(true);
    expect(state.message).toBe(errorEvents[0].detail.message);
    expect(state.paused).toBe(true);
    expect(state.sppAfter).toBe(state.sppBefore);
    expect(errors).toEqual([]);
  });

  it('a worker that cannot start gives one clear error and is not restarted for ever', async () => {
    const { page } = await open();
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

  it('a worker a Content-Security-Policy forbids gives one clear error and no retries', async () => {
    const { page, errors } = await open({
      headers: { 'content-security-policy': "worker-src 'none'" },
    });
    const view = await addView(page, 'csp', { src: '/scenes/cornell.json' });
    await waitForEvent(page, view, 'error');
    const first = await held(page);
    await page.waitForTimeout(1500);
    const later = await held(page);
    // Not retried: no more workers tried, one error event (however many
    // workers failed), nothing replaced.
    expect(first.workersTried).toBeGreaterThan(0);
    expect(later.workersTried).toBe(first.workersTried);
    const log = await events(page, view);
    const reported = log.filter((e) => e.type === 'error').map((e) => e.detail.message);
    expect(reported).toHaveLength(1);
    expect(reported[0]).toMatch(/worker.*Content-Security-Policy/);
    // Nothing was traced.
    expect(log.filter((e) => e.type === 'progress' && e.detail.spp > 0)).toEqual([]);
    const shown = (s: string) =>
      page.evaluate(
        (s) =>
          (document.querySelector(s) as any).shadowRoot.querySelector('[part=message]').textContent,
        s,
      );
    expect(await shown(view)).toBe(reported[0]);
    // An element added later, on the same failed pool, is told too.
    const second = await addView(page, 'csp2', { src: '/scenes/cornell.json' });
    await waitForEvent(page, second, 'error');
    expect(await shown(second)).toBe(reported[0]);
    expect((await held(page)).workersTried).toBe(first.workersTried);
    expect(await page.evaluate(() => (window as any).__faults.replaced)).toBe(0);
    // The page itself threw nothing. The console has the violation, and the
    // dev server's reload socket, which Chromium blocks on a page served
    // through a route, says it cannot connect.
    const noise = /Content.Security.Policy|worker-src|WebSocket|\[vite\]/i;
    expect(errors.filter((e) => !noise.test(e))).toEqual([]);
    // And the policy really was what stopped the workers.
    expect(errors.some((e) => /Content.Security.Policy/i.test(e))).toBe(true);
    console.log(`CSP worker-src 'none', ${first.workersTried} workers tried: ${reported[0]}`);
  });
});
