/**
 * What the browser test files share: one dev server of the demo and one
 * Chromium per file, the fixed small render they compare against the Node
 * core, and a check that no page threw.
 */
import type { Browser, Page } from 'playwright-core';
import type { ViteDevServer } from 'vite';
import { afterAll, afterEach, beforeAll, expect } from 'vitest';
import { launchBrowser, openDemo, pageErrors, startDemoServer, waitForSpp } from './harness.ts';
import { nodeRender } from './node-reference.ts';

export const SIZE = 64;
export const SEED = 1;
export const PASSES = 8;
export const fixed = `width=${SIZE}&height=${SIZE}&seed=${SEED}`;
/**
 * The main display path, asked for by name: left on 'auto', the demo picks
 * Canvas 2D where WebGL2 runs in software (as in this headless Chromium).
 */
export const WEBGL = 'display=webgl2';

export interface DemoContext {
  url: string;
  browser: Browser;
  /** The Node core's Cornell box at SIZE², SEED, PASSES samples: linear RGB. */
  reference: Float32Array;
  /** Opens the demo at the fixed size with `query` and waits for PASSES samples. */
  converged(query: string): Promise<Page>;
}

/** Registers the file's hooks; the context is filled in before the first test. */
export function useDemo(): DemoContext {
  let server: ViteDevServer | undefined;
  const ctx = {} as DemoContext;
  beforeAll(async () => {
    let url: string;
    ({ server, url } = await startDemoServer(true));
    ctx.url = url;
    ctx.browser = await launchBrowser();
    ctx.reference = nodeRender('cornell', SIZE, SIZE, SEED, PASSES);
    ctx.converged = async (query) => {
      const page = await openDemo(ctx.browser, ctx.url, `${fixed}&spp=${PASSES}&${query}`);
      await waitForSpp(page, PASSES);
      return page;
    };
  });
  afterAll(async () => {
    await ctx.browser?.close();
    await server?.close();
  });
  afterEach(() => {
    expect(pageErrors).toEqual([]);
  });
  return ctx;
}
