/**
 * Shared setup of the browser tests: a Vite dev server of the demo (with
 * or without the cross-origin isolation headers) and Debian's Chromium
 * driven by playwright-core.
 */
import demoConfig from '../../vite.config.ts';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { Browser, Page } from 'playwright-core';
import { launchChromium } from '../helpers/chromium.ts';
import { build, createServer, preview, type PreviewServer, type ViteDevServer } from 'vite';

export const root = fileURLToPath(new URL('../..', import.meta.url));
/**
 * The demo's dev server. `isolated: false` serves it without COOP/COEP.
 * Each server gets its own dependency cache: other Vite servers on this
 * checkout (other test files, a developer's `npm start`) must not rewrite
 * the pre-bundled modules under a page that is loading them.
 */
export async function startDemoServer(
  isolated = true,
): Promise<{ server: ViteDevServer; url: string }> {
  const cacheDir = mkdtempSync(join(tmpdir(), 'pathwise-vite-'));
  const server = await createServer({
    root,
    cacheDir,
    configFile: isolated ? undefined : false,
    // Without the config file (its headers isolate the page), but with its dependency
    // list: a plain server that discovers dependencies as pages load re-optimises and
    // cannot reload the page (no HMR), which left pages waiting on a loaded machine.
    ...(isolated ? {} : { worker: demoConfig.worker, optimizeDeps: demoConfig.optimizeDeps }),
    server: { host: '127.0.0.1', port: 0, strictPort: false, hmr: false },
    logLevel: 'error',
  });
  await server.listen();
  const url = server.resolvedUrls!.local[0];
  const close = server.close.bind(server);
  server.close = async () => {
    await close();
    rmSync(cacheDir, { recursive: true, force: true });
  };
  return { server, url };
}

/** The production build of the demo in a temporary folder, served by `vite preview`. */
export async function startPreviewServer(): Promise<{ server: PreviewServer; url: string }> {
  const outDir = mkdtempSync(join(tmpdir(), 'pathwise-web-'));
  const cacheDir = mkdtempSync(join(tmpdir(), 'pathwise-vite-'));
  await build({ root, cacheDir, logLevel: 'error', build: { outDir, emptyOutDir: true } });
  const server = await preview({
    root,
    cacheDir,
    logLevel: 'error',
    build: { outDir },
    preview: { host: '127.0.0.1', port: 0 },
  });
  const url = server.resolvedUrls!.local[0];
  const close = server.close.bind(server);
  server.close = async () => {
    await close();
    rmSync(outDir, { recursive: true, force: true });
    rmSync(cacheDir, { recursive: true, force: true });
  };
  return { server, url };
}

export function launchBrowser(): Promise<Browser> {
  return launchChromium();
}

/** Uncaught exceptions of every page opened by openDemo; the tests expect none. */
export const pageErrors: string[] = [];

/** Opens the demo with URL parameters and waits for the test hook. */
export async function openDemo(browser: Browser, url: string, query: string): Promise<Page> {
  const page = await browser.newPage();
  page.on('pageerror', (e) => pageErrors.push(`${query}: ${e.message}`));
  const logged: string[] = [];
  consoleErrors.set(page, logged);
  page.on('console', (m) => {
    if (m.type() === 'error') logged.push(m.text());
  });
  await page.goto(`${url}?${query}`);
  await page.waitForFunction(() => 'controller' in ((window as any).__pathwise ?? {}));
  return page;
}

export async function spp(page: Page): Promise<number> {
  return page.evaluate(() => (window as any).__pathwise.controller.stats().spp as number);
}

/** Console errors per page, for the message of a wait that times out. */
const consoleErrors = new WeakMap<Page, string[]>();

/** Waits until the controller has at least `n` samples per pixel. */
export async function waitForSpp(page: Page, n: number, timeout = 60_000): Promise<void> {
  try {
    await page.waitForFunction(
      (target) => (window as any).__pathwise.controller.stats().spp >= target,
      n,
      { timeout, polling: 50 },
    );
  } catch (e) {
    // Say where it stood: a stalled render is otherwise just a timeout.
    const state = await page
      .evaluate(() => ({
        stats: (window as any).__pathwise.controller.stats(),
        error: document.getElementById('error')?.textContent,
      }))
      .catch(() => null);
    const logged = (consoleErrors.get(page) ?? []).slice(-5).join(' | ');
    throw new Error(
      `spp did not reach ${n}: ${JSON.stringify(state)}; console: ${logged}; ${(e as Error).message}`,
    );
  }
}

/**
 * After a pause, stripes already in hand still finish their pass and are shown.
 * Waits until that has happened: no stripe is in hand any more (the film job is
 * not busy) and the controller's frame loop has gone idle (its frame count and
 * spp unchanged over 500 ms), so the display no longer moves. The first alone
 * could be fooled by a renderer starved of frames on a loaded machine.
 */
export async function waitForPauseSettled(page: Page, timeout = 60_000): Promise<void> {
  const probe = () =>
    page.evaluate(() => {
      const c = (window as any).__pathwise.controller;
      const busy = c.films.active()?.busy() ?? false;
      return `${c.framesRun()}/${c.stats().spp}/${busy ? 'busy' : 'idle'}`;
    });
  const end = Date.now() + timeout;
  let last = await probe();
  for (;;) {
    await page.waitForTimeout(500);
    const now = await probe();
    if (now === last && now.endsWith('/idle')) return;
    if (Date.now() > end) throw new Error(`the paused demo did not settle: ${last} → ${now}`);
    last = now;
  }
}

/** The linear mean image as Float32 (exact: float32 values survive the trip through doubles). */
export async function readLinear(
  page: Page,
): Promise<{ width: number; height: number; rgb: Float32Array }> {
  const r = await page.evaluate(() => {
    const { width, height, rgb } = (window as any).__pathwise.controller.readLinear();
    return { width, height, rgb: Array.from(rgb as Float32Array) };
  });
  return { width: r.width, height: r.height, rgb: Float32Array.from(r.rgb) };
}

/** The canvas's displayed RGBA8 pixels, row 0 at the top. */
export async function readDisplay(
  page: Page,
): Promise<{ width: number; height: number; rgba: Uint8Array }> {
  const r = await page.evaluate(() => {
    const { width, height, rgba } = (window as any).__pathwise.controller.readDisplay();
    return { width, height, rgba: Array.from(rgba as Uint8Array) };
  });
  return { width: r.width, height: r.height, rgba: Uint8Array.from(r.rgba) };
}

/** Mean RGB of the displayed pixels in the box [x0, x1) × [y0, y1). */
export function meanRgb(
  img: { width: number; rgba: Uint8Array },
  x0: number,
  y0: number,
  x1: number,
  y1: number,
): [number, number, number] {
  const sum = [0, 0, 0];
  let n = 0;
  for (let y = y0; y < y1; y++) {
    for (let x = x0; x < x1; x++) {
      const i = (y * img.width + x) * 4;
      sum[0] += img.rgba[i];
      sum[1] += img.rgba[i + 1];
      sum[2] += img.rgba[i + 2];
      n++;
    }
  }
  return [sum[0] / n, sum[1] / n, sum[2] / n];
}

/** Largest per-channel difference between two RGBA8 images of one size. */
export function maxByteDifference(a: Uint8Array, b: Uint8Array): number {
  let max = 0;
  for (let i = 0; i < a.length; i++) max = Math.max(max, Math.abs(a[i] - b[i]));
  return max;
}

/** Count of float32 values that differ in any bit. */
export function bitDifferences(a: Float32Array, b: Float32Array): number {
  const ua = new Uint32Array(a.buffer, a.byteOffset, a.length);
  const ub = new Uint32Array(b.buffer, b.byteOffset, b.length);
  let n = 0;
  for (let i = 0; i < ua.length; i++) if (ua[i] !== ub[i]) n++;
  return n;
}
