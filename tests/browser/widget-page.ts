/**
 * What the <pathwise-view> fault tests share: the fixture page
 * (fixtures/widget.html, which loads the widget from the sources and counts
 * live Worker objects, WebGL contexts and pending animation frames) opened
 * in a fresh browser context, views added with an event log, and readers
 * of that log and of the film.
 */
import type { Browser, BrowserContext, Page } from 'playwright-core';
import { afterEach } from 'vitest';

export const WAIT = { timeout: 60_000, polling: 50 };

export interface Opened {
  context: BrowserContext;
  page: Page;
  errors: string[];
  warnings: string[];
}

/**
 * Headless Chromium runs WebGL2 in software (SwiftShader), where the widget
 * rightly picks Canvas 2D (src/view/mode.ts). This init script makes the
 * renderer report a GPU's name, so the widget takes its WebGL2 path, as it
 * does on a machine with a GPU; the context itself is SwiftShader's still.
 */
export function pretendGpu(): void {
  const proto = WebGL2RenderingContext.prototype;
  const getParameter = proto.getParameter;
  proto.getParameter = function (name: number) {
    // UNMASKED_RENDERER_WEBGL (WEBGL_debug_renderer_info) and RENDERER.
    if (name === 0x9246 || name === 0x1f01) return 'Test GPU (hardware)';
    return getParameter.call(this, name);
  };
}

/** The fixture page in a fresh context; `init` runs before any of the page's scripts. */
export async function openWidgetPage(
  browser: Browser,
  url: string,
  options: {
    deviceScaleFactor?: number;
    init?: () => void;
    /** Response headers added to the fixture page's own (a Content-Security-Policy). */
    headers?: Record<string, string>;
  } = {},
): Promise<Opened> {
  const context = await browser.newContext({
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
  const extra = options.headers;
  if (extra) {
    await page.route('**/tests/browser/fixtures/widget.html', async (route) => {
      const response = await route.fetch();
      await route.fulfill({ response, headers: { ...response.headers(), ...extra } });
    });
  }
  await page.goto(`${url}tests/browser/fixtures/widget.html`);
  await page.waitForFunction(() => (window as any).__ready === true);
  return { context, page, errors, warnings };
}

/**
 * A test file's opener of fixture pages (openWidgetPage on `ctx`'s browser and server,
 * read when called): the page a test opened is closed after it, pass or fail.
 */
export function useWidgetPages(ctx: {
  browser: Browser;
  url: string;
}): (options?: Parameters<typeof openWidgetPage>[2]) => Promise<Opened> {
  let opened: Opened | null = null;
  afterEach(async () => {
    await opened?.context.close();
    opened = null;
  });
  return async (options = {}) => {
    opened = await openWidgetPage(ctx.browser, ctx.url, options);
    return opened;
  };
}

/** Adds a <pathwise-view> with `attributes` (and an event log) to the page; returns its selector. */
export async function addView(page: Page, id: string, attributes: Record<string, string>) {
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

export async function events(
  page: Page,
  selector: string,
): Promise<{ type: string; detail: any }[]> {
  return page.evaluate((s) => (document.querySelector(s) as any).log, selector);
}

export async function waitForEvent(page: Page, selector: string, type: string): Promise<void> {
  await page.waitForFunction(
    ({ s, t }) => ((document.querySelector(s) as any)?.log ?? []).some((e: any) => e.type === t),
    { s: selector, t: type },
    WAIT,
  );
}

export async function linear(page: Page, selector: string): Promise<Float32Array> {
  const rgb = await page.evaluate(
    (s) =>
      Array.from((document.querySelector(s) as any).controller.readLinear().rgb as Float32Array),
    selector,
  );
  return Float32Array.from(rgb);
}

/** What the page holds: live render workers (Web Locks held), Worker objects, contexts, frames. */
export async function held(page: Page) {
  return page.evaluate(async () => {
    const h = (window as any).__held;
    const locks = await navigator.locks.query();
    return {
      lifeLocks: (locks.held ?? []).filter((l) => l.name?.startsWith('pathwise-render-worker-'))
        .length,
      workers: h.workersMade - h.workersTerminated,
      workersMade: h.workersMade,
      workersTried: h.workersTried as number,
      contexts: h.liveContexts(),
      contextsMade: h.contexts.size as number,
      frames: h.frames.size,
      canvases: document.querySelectorAll('canvas').length,
    };
  });
}
