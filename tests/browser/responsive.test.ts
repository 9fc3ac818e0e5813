/**
 * The page stays responsive (Chromium, the demo, cross-origin isolated): a huge scene
 * (100,000 spheres; a 600,000-triangle OBJ mesh) and degenerate ones (2,000 spheres at
 * x = 2^k, a sphere whose bounds overflow) load with no main-thread task over 200 ms,
 * measured by a PerformanceObserver of long tasks installed before the page's scripts;
 * a load superseded by a newer one has its scene worker stopped within a second; and a
 * seeded sample of the magnitude generator (tests/fuzz/magnitudes.ts) gets in the page
 * the verdict the Node loader gives: the same message, or a finite picture.
 *
 * The scenes are served by the test (page.route) and loaded by URL from a page task,
 * as the widget's `src` does: work that Playwright runs inside page.evaluate is not
 * reported as a long task.
 */
import fc from 'fast-check';
import type { Page } from 'playwright-core';
import { describe, expect, it } from 'vitest';
import { SceneError } from '../../src/core/index.ts';
import { magnitudeCase, magnitudeScene } from '../fuzz/magnitudes.ts';
import { sceneWithFiles } from '../helpers/gltf.ts';
import { useDemo } from './context.ts';
import { openDemo, waitForSpp } from './harness.ts';

const ctx = useDemo();
/** Longest main-thread task allowed while a scene loads (ms). */
const LONG_TASK_MS = 200;

const base = {
  format: 'pathwise-scene/1',
  camera: { position: [0, 2, -12], target: [0, 0, 0], up: [0, 1, 0], fovY: 45 },
  settings: { width: 64, height: 64, maxBounces: 2, spp: 4 },
  environment: [0.5, 0.5, 0.5],
  materials: { m: { type: 'diffuse', albedo: [0.6, 0.6, 0.6] } },
};

function spheres(n: number, at: (k: number) => number[], radius: (k: number) => number) {
  return Array.from({ length: n }, (_, k) => ({
    type: 'sphere',
    center: at(k),
    radius: radius(k),
    material: 'm',
  }));
}

/** A wavy grid of 2·side² triangles as OBJ text. */
function gridObj(side: number): string {
  const lines: string[] = [];
  for (let j = 0; j <= side; j++) {
    for (let i = 0; i <= side; i++) {
      const x = (i / side) * 8 - 4;
      const z = (j / side) * 8 - 4;
      lines.push(
        `v ${x.toFixed(5)} ${(0.2 * Math.sin(3 * x) * Math.cos(3 * z)).toFixed(5)} ${z.toFixed(5)}`,
      );
    }
  }
  const v = (i: number, j: number) => j * (side + 1) + i + 1;
  for (let j = 0; j < side; j++) {
    for (let i = 0; i < side; i++) {
      lines.push(`f ${v(i, j)} ${v(i + 1, j)} ${v(i + 1, j + 1)}`);
      lines.push(`f ${v(i, j)} ${v(i + 1, j + 1)} ${v(i, j + 1)}`);
    }
  }
  return lines.join('\n') + '\n';
}

/** Serves `files` (name → body) under /t/ on the page's origin. */
async function serve(page: Page, files: Map<string, string | Uint8Array>): Promise<void> {
  await page.route('**/t/**', (route) => {
    const name = decodeURIComponent(new URL(route.request().url()).pathname.replace(/^\/t\//, ''));
    const body = files.get(name);
    if (body === undefined) return route.fulfill({ status: 404, body: 'missing' });
    return route.fulfill({
      status: 200,
      body: typeof body === 'string' ? body : Buffer.from(body),
      headers: {
        'content-type': 'application/octet-stream',
        'cross-origin-resource-policy': 'same-origin',
      },
    });
  });
}

/** Long tasks seen since the last call (ms), from the observer of the init script. */
async function takeLongTasks(page: Page): Promise<number[]> {
  return page.evaluate(() => (window as any).__longTasks.splice(0) as number[]);
}

type Verdict = { kind: 'error'; message: string } | { kind: 'load'; spp: number };

/**
 * Loads /t/NAME from a page task (as a `src` change does) and waits for its `load`
 * (then for a first sample) or its `error` event.
 */
async function loadFromPage(page: Page, name: string): Promise<Verdict> {
  return page.evaluate(
    (name) =>
      new Promise<Verdict>((resolve) => {
        const c = (window as any).__pathwise.controller;
        const done = (v: Verdict) => {
          c.removeEventListener('load', onLoad);
          c.removeEventListener('error', onError);
          resolve(v);
        };
        const onError = (e: CustomEvent) => done({ kind: 'error', message: e.detail.message });
        const onLoad = () => {
          const wait = () =>
            c.stats().spp >= 1 ? done({ kind: 'load', spp: c.stats().spp }) : setTimeout(wait, 20);
          wait();
        };
        c.addEventListener('load', onLoad);
        c.addEventListener('error', onError);
        setTimeout(() => c.load(`/t/${name}`).catch(() => {}), 0);
      }),
    name,
  );
}

describe('the page stays responsive (Chromium)', () => {
  it(`huge and degenerate scenes load with no main-thread task over ${LONG_TASK_MS} ms`, async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'width=64&height=64&seed=1&spp=2&workers=1');
    await page.evaluate(() => {
      (window as any).__longTasks = [];
      new PerformanceObserver((list) => {
        for (const e of list.getEntries()) (window as any).__longTasks.push(e.duration);
      }).observe({ type: 'longtask' });
    });
    await waitForSpp(page, 1);
    const files = new Map<string, string | Uint8Array>([
      [
        'spheres.json',
        JSON.stringify({
          ...base,
          shapes: spheres(
            100_000,
            (k) => [((k % 316) - 158) * 0.05, Math.floor(k / 316) * 0.05 - 8, 6],
            () => 0.02,
          ),
        }),
      ],
      ['grid.obj', gridObj(550)],
      [
        'mesh.json',
        JSON.stringify({ ...base, shapes: [{ type: 'mesh', file: 'grid.obj', material: 'm' }] }),
      ],
      [
        'pow2.json',
        JSON.stringify({
          ...base,
          shapes: spheres(
            2000,
            (k) => [2 ** (k - 1000), 0, 0],
            (k) => 2 ** (k - 1000) / 4,
          ),
        }),
      ],
      [
        'overflow.json',
        JSON.stringify({
          ...base,
          shapes: [
            ...spheres(
              59,
              (k) => [k, 0, 0],
              () => 0.3,
            ),
            ...spheres(
              1,
              () => [1e308, 0, 0],
              () => 1e308,
            ),
          ],
        }),
      ],
    ]);
    await serve(page, files);
    await takeLongTasks(page);
    const seen: string[] = [];
    for (const name of ['spheres.json', 'mesh.json', 'pow2.json', 'overflow.json']) {
      const verdict = await loadFromPage(page, name);
      if (name === 'overflow.json') {
        expect(verdict).toEqual({
          kind: 'error',
          message: 'shapes[59] reaches beyond the double range: center.x + radius = Infinity',
        });
      } else {
        expect(verdict.kind, JSON.stringify(verdict)).toBe('load');
      }
      const tasks = await takeLongTasks(page);
      seen.push(`${name}: ${tasks.length ? Math.max(...tasks).toFixed(0) : 0} ms`);
      expect(Math.max(0, ...tasks), name).toBeLessThan(LONG_TASK_MS);
    }
    console.log(`longest main-thread task while loading: ${seen.join(', ')}`);
    await page.close();
  }, 180_000);

  it('a load superseded by a newer one has its scene worker stopped within a second', async () => {
    const page = await openDemo(ctx.browser, ctx.url, 'width=64&height=64&seed=1&spp=2&workers=1');
    await waitForSpp(page, 1);
    await serve(
      page,
      new Map<string, string | Uint8Array>([
        ['big.obj', gridObj(700)],
        [
          'big.json',
          JSON.stringify({ ...base, shapes: [{ type: 'mesh', file: 'big.obj', material: 'm' }] }),
        ],
        [
          'small.json',
          JSON.stringify({
            ...base,
            name: 'small',
            shapes: spheres(
              3,
              (k) => [k, 0, 0],
              () => 0.4,
            ),
          }),
        ],
      ]),
    );
    // Times on the epoch clock of this machine, in the test (worker close) and the page.
    const now = () => performance.timeOrigin + performance.now();
    const closed: number[] = [];
    let started = 0;
    page.on('worker', (w) => {
      if (!w.url().includes('model-worker')) return;
      started++;
      w.on('close', () => closed.push(now()));
    });
    // The big scene reaches its BVH build (the worker's longest task), then a new load
    // supersedes it.
    const superseded = await page.evaluate(
      () =>
        new Promise<number>((resolve) => {
          const c = (window as any).__pathwise.controller;
          const onProgress = (e: CustomEvent) => {
            if (e.detail.stage !== 'compile' || e.detail.done !== 0) return;
            c.removeEventListener('loadprogress', onProgress);
            resolve(performance.timeOrigin + performance.now());
            c.load('/t/small.json').catch(() => {});
          };
          c.addEventListener('loadprogress', onProgress);
          c.load('/t/big.json').catch(() => {});
        }),
    );
    await page.waitForFunction(
      () => (window as any).__pathwise.controller.scene?.name === 'small',
      undefined,
      { timeout: 60_000 },
    );
    await expect.poll(() => closed.length, { timeout: 10_000 }).toBe(started);
    // The first worker is the big scene's.
    const stoppedAfter = closed[0] - superseded;
    console.log(`superseded scene worker stopped ${stoppedAfter.toFixed(0)} ms after the new load`);
    expect(stoppedAfter).toBeLessThan(1000);
    await page.close();
  }, 120_000);

  it("generated scenes at every magnitude get the Node loader's verdict in the page", async () => {
    const cases = fc.sample(magnitudeCase, { seed: 20261203, numRuns: 16 });
    const page = await openDemo(ctx.browser, ctx.url, 'width=64&height=64&seed=1&spp=1&workers=1');
    await waitForSpp(page, 1);
    const files = new Map<string, string | Uint8Array>();
    const expected: (string | null)[] = [];
    for (let k = 0; k < cases.length; k++) {
      const { json, files: own } = await magnitudeScene(cases[k]);
      // The case's files under its own folder, as the scene names them.
      for (const [name, bytes] of own) files.set(`${k}/${name}`, bytes);
      files.set(`${k}/scene.json`, JSON.stringify(json));
      try {
        await sceneWithFiles(JSON.parse(JSON.stringify(json)), own);
        expected.push(null);
      } catch (e) {
        if (!(e instanceof SceneError)) throw e;
        expected.push(e.message);
      }
    }
    await serve(page, files);
    let rendered = 0;
    for (let k = 0; k < cases.length; k++) {
      const verdict = await loadFromPage(page, `${k}/scene.json`);
      const what = JSON.stringify(cases[k]);
      if (expected[k] === null) {
        expect(verdict.kind, `${what}: ${JSON.stringify(verdict)}`).toBe('load');
        const finite = await page.evaluate(() => {
          const snap = (window as any).__pathwise.controller.filmSnapshot();
          return (Array.from(snap.sums as Float32Array) as number[]).every(Number.isFinite);
        });
        expect(finite, what).toBe(true);
        rendered++;
      } else {
        expect(verdict, what).toEqual({ kind: 'error', message: expected[k] });
      }
    }
    expect(rendered).toBeGreaterThan(0);
    expect(rendered).toBeLessThan(cases.length);
    await page.close();
  }, 180_000);
});
