/**
 * The npm package as a user gets it: packed, installed into a fresh project
 * with no access to the repository's sources, then used from Node (core,
 * server-side import), from TypeScript (published types) and from a page in
 * Chromium, served once without and once with cross-origin isolation.
 */
import { execFileSync } from 'node:child_process';
import { existsSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join } from 'node:path';
import type { Browser, BrowserContext, Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import type { FallbackInfo, ProgressInfo } from '../../src/view/types.ts';
import type { PathwiseViewElement } from '../../src/widget/index.ts';
import { launchChromium } from '../helpers/chromium.ts';
import { isGreen, isRed, wallColors } from './fixture/cornell-colors.ts';
import { installPackedPackage, REPO, type InstalledPackage } from './fixture/install-package.ts';
import { writeCdnPage, writeSite, writeViteApp } from './fixture/site.ts';
import { serveDirectory, type StaticServer } from './fixture/static-server.ts';

interface LoggedEvent {
  type: string;
  detail: unknown;
}
/** An element with the event log that the test pages attach (see fixture/site.ts). */
type LoggedView = PathwiseViewElement & { log: LoggedEvent[] };

const EVENT_WAIT_MS = 60_000;

let installed: InstalledPackage;
let browser: Browser;

beforeAll(async () => {
  installed = installPackedPackage();
  writeSite(installed.project, installed.packageDir);
  browser = await launchChromium();
});

afterAll(async () => {
  await browser?.close();
  if (installed) rmSync(installed.dir, { recursive: true, force: true });
});

/** Runs an ES module script with Node inside the consumer project; returns its stdout. */
function runInProject(name: string, source: string): string {
  const file = join(installed.project, name);
  writeFileSync(file, source);
  return execFileSync(process.execPath, [file], { cwd: installed.project, encoding: 'utf8' });
}

describe('the installed package', () => {
  test('ships only the library, its types, the command line, bin, the scenes, the KTX2 transcoder and the denoiser weights', () => {
    const top = readdirSync(installed.packageDir).sort();
    for (const entry of top) {
      expect(['LICENSE', 'README.md', 'bin', 'dist', 'package.json', 'scenes', 'vendor']).toContain(
        entry,
      );
    }
    // The Basis Universal transcoder the command line loads for KTX2 textures (src/cli/gltf-node.ts),
    // and the denoiser's weights (src/cli/denoise-output.ts).
    expect(readdirSync(join(installed.packageDir, 'vendor')).sort()).toEqual([
      'basis',
      'oidn-weights',
    ]);
    const weights = readdirSync(join(installed.packageDir, 'vendor/oidn-weights'));
    for (const f of ['rt_hdr.tza', 'rt_hdr_alb_nrm.tza', 'LICENSE.txt'])
      expect(weights).toContain(f);
    const basis = readdirSync(join(installed.packageDir, 'vendor/basis'));
    for (const f of ['basis_transcoder.js', 'basis_transcoder.wasm']) expect(basis).toContain(f);
    expect(readdirSync(join(installed.packageDir, 'dist')).sort()).toEqual(['cli', 'lib', 'types']);
    const pkg = JSON.parse(readFileSync(join(installed.packageDir, 'package.json'), 'utf8')) as {
      exports: Record<string, string | Record<string, string>>;
      sideEffects: string[];
    };
    // Every target of the exports map is really there (a pattern: some file matches).
    for (const target of Object.values(pkg.exports)) {
      for (const file of typeof target === 'string' ? [target] : Object.values(target)) {
        if (file.endsWith('/*')) {
          expect(
            readdirSync(join(installed.packageDir, file.slice(0, -2))).length,
            file,
          ).toBeGreaterThan(0);
        } else {
          expect(existsSync(join(installed.packageDir, file)), file).toBe(true);
        }
      }
    }
    // Only the registering entry is marked as having side effects among the shipped files.
    const shipped = pkg.sideEffects.filter((p) => p.startsWith('./dist/'));
    expect(shipped).toEqual(['./dist/lib/pathwise.js']);
  });

  test('pathwise/core renders the Cornell box in Node', () => {
    const scene = JSON.stringify(
      readFileSync(join(installed.project, 'scenes/cornell.json'), 'utf8'),
    );
    const out = runInProject(
      'core-render.mjs',
      `import { Film, PathTracer, RenderStats, compileScene, parseScene } from 'pathwise/core';
const scene = parseScene(${scene});
const width = 32, height = 32;
const tracer = new PathTracer(compileScene(scene), { width, height, maxBounces: 4, camera: scene.camera });
const film = new Film(width, height);
tracer.renderRows(film, 0, height, 0, 16, new RenderStats());
process.stdout.write(JSON.stringify({ width, height, rgb: Array.from(film.mean()) }));
`,
    );
    const image = JSON.parse(out) as { width: number; height: number; rgb: number[] };
    const walls = wallColors(image.width, image.height, image.rgb);
    expect(isRed(walls.left), `left wall ${walls.left}`).toBe(true);
    expect(isGreen(walls.right), `right wall ${walls.right}`).toBe(true);
  });

  test('pathwise/three converts a three.js scene in Node, and the core renders it', () => {
    // three is an optional peer dependency: the consumer brings it (here, the repository's).
    const three = JSON.stringify(join(REPO, 'node_modules/three/build/three.module.js'));
    const out = runInProject(
      'three-convert.mjs',
      `import * as THREE from ${three};
import { fromThree } from 'pathwise/three';
import { Film, PathTracer, RenderStats, compileScene, resolveSceneFiles, validateScene } from 'pathwise/core';
const scene = new THREE.Scene();
const red = new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), new THREE.MeshStandardMaterial({ color: 0xff0000, roughness: 1 }));
scene.add(red);
const light = new THREE.PointLight(0xffffff, 20);
light.position.set(0, 2, 2);
scene.add(light);
const camera = new THREE.PerspectiveCamera(40, 1, 0.1, 100);
camera.position.set(0, 0, 4);
const converted = await fromThree(scene, camera);
const loaded = await resolveSceneFiles(validateScene(converted.scene), converted.reader);
const width = 16, height = 16;
const tracer = new PathTracer(compileScene(loaded), { width, height, maxBounces: 2, camera: loaded.camera });
const film = new Film(width, height);
tracer.renderRows(film, 0, height, 0, 8, new RenderStats());
const rgb = film.mean();
const c = ((height / 2) * width + width / 2) * 3;
process.stdout.write(JSON.stringify({ warnings: converted.warnings, centre: [rgb[c], rgb[c + 1], rgb[c + 2]] }));
`,
    );
    const result = JSON.parse(out) as { warnings: string[]; centre: number[] };
    expect(result.warnings).toEqual([]);
    // The box's face towards the camera, lit by the point light: red.
    expect(result.centre[0]).toBeGreaterThan(0.05);
    expect(result.centre[1]).toBeLessThan(result.centre[0] * 0.05);
  });

  test('imports without a DOM (server-side rendering) and registers nothing there', () => {
    const out = runInProject(
      'ssr-import.mjs',
      `const main = await import('pathwise');
const element = await import('pathwise/element');
process.stdout.write(JSON.stringify({
  main: Object.keys(main).sort(),
  element: Object.keys(element).sort(),
  defined: main.definePathwiseView() ?? null,
  globals: [typeof window, typeof self, typeof customElements],
}));
`,
    );
    const result = JSON.parse(out) as Record<string, unknown>;
    expect(result.globals).toEqual(['undefined', 'undefined', 'undefined']);
    for (const key of ['main', 'element']) {
      expect(result[key]).toEqual(
        expect.arrayContaining(['PathwiseViewElement', 'createPathTracer', 'definePathwiseView']),
      );
    }
    expect(result.defined).toBeNull();
  });

  test('a TypeScript consumer compiles against the published types', () => {
    const dir = installed.project;
    writeFileSync(
      join(dir, 'consumer.ts'),
      `import {
  createPathTracer,
  definePathwiseView,
  PathwiseViewElement,
  type FallbackInfo,
  type PathTracerController,
  type ProgressInfo,
} from 'pathwise';
import { decodePfm, parseScene, type Scene } from 'pathwise/core';

// HTMLElementTagNameMap knows the tag, so no cast is needed.
const el = document.createElement('pathwise-view');
const typed: PathwiseViewElement = el;
const found: PathwiseViewElement | null = document.querySelector('pathwise-view');
el.src = '/scenes/cornell.json';
el.spp = 64;
el.bounces = null;
el.cameraControls = true;
el.scene = { format: 'pathwise-scene/1' };
el.addEventListener('progress', (e) => {
  const p: ProgressInfo = e.detail;
  console.log(p.spp, p.target, p.raysPerSecond, p.noise);
});
el.addEventListener('fallback', (e) => {
  const info: FallbackInfo = e.detail;
  const compute: 'shared' | 'transfer' = info.compute;
  console.log(compute, info.reason);
});
el.addEventListener('error', (e) => console.log(e.detail.message.toUpperCase()));
el.addEventListener('click', (e) => console.log(e.clientX));
el.reset();
el.pause();
el.resume();
const png: Promise<Blob> = el.toBlob();
const pfm = decodePfm(el.toPFM());
const ctor: CustomElementConstructor | undefined = definePathwiseView('my-view');
const controller: PathTracerController = createPathTracer(document.createElement('canvas'), {
  spp: 8,
  workerUrl: '/render-worker.js',
});
controller.addEventListener('converged', () => controller.destroy());
const scene: Scene = parseScene('{}');
console.log(typed, found, png, pfm.width, ctor, scene.name);

// The types are precise, not any: each of these must be an error.
// @ts-expect-error spp is a number
el.spp = 'lots';
// @ts-expect-error progress details have no such field
el.addEventListener('progress', (e) => e.detail.bogus);
// @ts-expect-error not a method of the element
el.frobnicate();
`,
    );
    const base = {
      target: 'ES2022',
      lib: ['ES2022', 'DOM', 'DOM.Iterable'],
      strict: true,
      noEmit: true,
      skipLibCheck: false,
      types: [],
    };
    const tsc = createRequire(import.meta.url).resolve('typescript/bin/tsc');
    for (const resolution of [
      { module: 'ESNext', moduleResolution: 'Bundler' },
      { module: 'NodeNext', moduleResolution: 'NodeNext' },
    ]) {
      const config = join(dir, `tsconfig.${resolution.moduleResolution}.json`);
      writeFileSync(
        config,
        JSON.stringify({ compilerOptions: { ...base, ...resolution }, files: ['consumer.ts'] }),
      );
      let output = '';
      try {
        execFileSync(process.execPath, [tsc, '-p', config], { cwd: dir, encoding: 'utf8' });
      } catch (e) {
        output = String((e as { stdout?: string }).stdout ?? e);
      }
      expect(output, resolution.moduleResolution).toBe('');
    }
  });
});

/** One browser context per test, so pages never share a worker pool by accident. */
async function openPage(server: StaticServer, path: string) {
  const context: BrowserContext = await browser.newContext({
    viewport: { width: 800, height: 600 },
  });
  const page = await context.newPage();
  const errors: string[] = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(server.url + path);
  await page.waitForFunction(() => customElements.get('pathwise-view') !== undefined);
  return { page, errors, close: () => context.close() };
}

function waitForEvent(page: Page, selector: string, type: string, count = 1) {
  return page.waitForFunction(
    ([sel, t, n]) => {
      const el = document.querySelector<LoggedView>(sel);
      return el?.log && el.log.filter((e) => e.type === t).length >= n;
    },
    [selector, type, count] as const,
    { timeout: EVENT_WAIT_MS },
  );
}

function eventLog(page: Page, selector: string): Promise<LoggedEvent[]> {
  return page.evaluate((sel) => document.querySelector<LoggedView>(sel)!.log, selector);
}

async function readPfm(page: Page, selector: string) {
  const bytes = await page.evaluate(
    (sel) => Array.from(document.querySelector<LoggedView>(sel)!.toPFM()),
    selector,
  );
  return decodePfm(Uint8Array.from(bytes));
}

/** Adds a recorded <pathwise-view> built from script; returns its selector. */
async function addView(page: Page, id: string, attributes: Record<string, string>, style = '') {
  await page.evaluate(
    ([i, attrs, css]) => {
      const el = document.createElement('pathwise-view');
      el.id = i;
      for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
      el.style.cssText = css;
      (window as unknown as { record(el: Element): void }).record(el);
      document.body.append(el);
    },
    [id, attributes, style] as const,
  );
  return `#${id}`;
}

/** Checks a converged declarative element: events, their payloads and the picture. */
async function expectConvergedCornellBox(page: Page) {
  await waitForEvent(page, '#view', 'converged');
  const log = await eventLog(page, '#view');
  const types = log.map((e) => e.type);
  expect(types).toContain('load');
  expect(types).toContain('progress');
  expect(log.find((e) => e.type === 'load')!.detail).toEqual({ name: 'Cornell box' });
  const converged = log.find((e) => e.type === 'converged')!.detail as ProgressInfo;
  expect(converged.target).toBe(16);
  expect(converged.spp).toBeGreaterThanOrEqual(16);
  const progress = log.filter((e) => e.type === 'progress').map((e) => e.detail as ProgressInfo);
  for (const p of progress) {
    expect(p.target).toBe(16);
    expect(typeof p.raysPerSecond).toBe('number');
    expect(typeof p.noise).toBe('number');
  }
  expect(progress.some((p) => p.spp > 0)).toBe(true);
  expect(types).not.toContain('error');

  const image = await readPfm(page, '#view');
  expect([image.width, image.height]).toEqual([64, 64]);
  const walls = wallColors(image.width, image.height, image.rgb);
  expect(isRed(walls.left), `left wall ${walls.left}`).toBe(true);
  expect(isGreen(walls.right), `right wall ${walls.right}`).toBe(true);

  const png = await page.evaluate(async () => {
    const blob = await document.querySelector('pathwise-view')!.toBlob();
    return {
      type: blob.type,
      bytes: Array.from(new Uint8Array(await blob.arrayBuffer()).slice(1, 4)),
    };
  });
  expect(png).toEqual({ type: 'image/png', bytes: [0x50, 0x4e, 0x47] });
  return log;
}

/** Removes elements and waits until the page has no workers left. */
async function expectWorkersTerminatedAfterRemoving(page: Page, selectors: string[]) {
  await page.evaluate(
    (sels) => sels.forEach((s) => document.querySelector(s)!.remove()),
    selectors,
  );
  await expect.poll(() => page.workers().length, { timeout: EVENT_WAIT_MS }).toBe(0);
}

/**
 * A glTF model as `src`, from the installed package: loaded in the package's model
 * worker (its own file, next to the render worker), framed and lit, converged.
 */
async function expectModelRendered(server: StaticServer, compute: 'shared' | 'transfer') {
  const { page, errors, close } = await openPage(server, 'blank.html');
  try {
    const workers: string[] = [];
    page.on('worker', (w) => workers.push(w.url()));
    const view = await addView(
      page,
      'model',
      { src: 'models/showcase.glb', spp: '2' },
      'width: 80px; height: 50px',
    );
    await waitForEvent(page, view, 'converged');
    const log = await eventLog(page, view);
    expect(log.find((e) => e.type === 'load')!.detail).toEqual({ name: 'showcase.glb' });
    expect((log.find((e) => e.type === 'fallback')!.detail as FallbackInfo).compute).toBe(compute);
    expect(workers.some((u) => /\/model-worker\.js$/.test(u))).toBe(true);
    const img = await readPfm(page, view);
    let sum = 0;
    for (const v of img.rgb) sum += v;
    expect(sum / img.rgb.length).toBeGreaterThan(0.05);
    expect(errors).toEqual([]);
  } finally {
    await close();
  }
}

describe('<pathwise-view> on a page without cross-origin isolation', () => {
  let server: StaticServer;
  beforeAll(async () => {
    server = await serveDirectory(installed.project);
  });
  afterAll(() => server?.close());

  test('loads, reports progress, converges at its target and shows the Cornell box', async () => {
    const { page, errors, close } = await openPage(server, 'embed.html');
    try {
      const log = await expectConvergedCornellBox(page);
      // The fallback event says why: transferable stripes, not shared memory.
      const fallback = log.find((e) => e.type === 'fallback')!.detail as FallbackInfo;
      expect(fallback.compute).toBe('transfer');
      expect(fallback.reason).toMatch(/cross-origin isolated/);
      expect(await page.evaluate(() => crossOriginIsolated)).toBe(false);
      expect(await page.evaluate(() => document.querySelector('pathwise-view')!.mode)).toEqual(
        fallback,
      );
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('renders a glTF model given as src (transferred textures)', async () => {
    await expectModelRendered(server, 'transfer');
  });

  test('a bad src or scene yields an error event and a readable message in the element', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const missing = await addView(page, 'missing', { src: 'scenes/no-such-scene.json' });
      // Strict UTF-8 and duplicate keys, with the same messages as the command line.
      const utf8 = await addView(page, 'utf8', { src: 'scenes/invalid-utf8-names.json' });
      const twice = await addView(page, 'twice', { src: 'scenes/duplicate-radius.json' });
      const invalid = await addView(page, 'invalid', {});
      // A real scene with one broken key, so the message must name that key.
      await page.evaluate(async () => {
        const scene = await (await fetch('scenes/cornell.json')).json();
        scene.shapes = 7;
        document.querySelector<PathwiseViewElement>('#invalid')!.scene = scene;
      });
      for (const [selector, pattern] of [
        [missing, /404/],
        [utf8, /^scene file is not valid UTF-8 at byte 351 \(line 29\): byte 0xff/],
        [twice, /^shapes\[1\]\.radius appears twice in one object \(line 78, column 21\)/],
        [invalid, /shapes/],
      ] as const) {
        await waitForEvent(page, selector, 'error');
        const error = (await eventLog(page, selector)).find((e) => e.type === 'error')!;
        expect((error.detail as { message: string }).message).toMatch(pattern);
        // The message is shown inside the element, on top of the canvas.
        const message = page.locator(`${selector} [part=message]`);
        expect(await message.isVisible()).toBe(true);
        expect(await message.innerText()).toMatch(pattern);
      }
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('a worker script that cannot load yields an error event and message, not a blank box', async () => {
    const { page, close } = await openPage(server, 'blank.html');
    try {
      const view = await addView(page, 'noworker', {
        src: 'scenes/cornell.json',
        'worker-url': 'no-such-worker.js',
      });
      await waitForEvent(page, view, 'error');
      const message = page.locator(`${view} [part=message]`);
      expect(await message.isVisible()).toBe(true);
      expect(await message.innerText()).toMatch(/worker/);
    } finally {
      await close();
    }
  });

  test('a worker that cannot even be created yields an error event and message', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      // As `new Worker` throws for a script the page may not start: the
      // throw happens inside the pool, which must report it, not drop it.
      await page.evaluate(() => {
        const el = document.createElement('pathwise-view');
        el.id = 'nofactory';
        el.setAttribute('src', 'scenes/cornell.json');
        el.workerFactory = () => {
          throw new Error('workers are blocked here');
        };
        (window as unknown as { record(el: Element): void }).record(el);
        document.body.append(el);
      });
      await waitForEvent(page, '#nofactory', 'error');
      const message = page.locator('#nofactory [part=message]');
      expect(await message.isVisible()).toBe(true);
      expect(await message.innerText()).toMatch(/worker.*blocked here/);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('elements share one worker pool; removing the last one terminates the workers', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const a = await addView(page, 'a', { src: 'scenes/cornell.json', spp: '8' });
      const b = await addView(page, 'b', { src: 'scenes/cornell.json', spp: '8' });
      await waitForEvent(page, a, 'converged');
      await waitForEvent(page, b, 'converged');
      const poolSizes = await page.evaluate(() =>
        ['#a', '#b'].map(
          (s) => document.querySelector<PathwiseViewElement>(s)!.controller!.stats().workers,
        ),
      );
      // One pool for both elements: as many workers as one element uses.
      // (Polled: Playwright learns of workers asynchronously.)
      await expect.poll(() => page.workers().length).toBe(poolSizes[0]);
      expect(poolSizes[1]).toBe(poolSizes[0]);

      // Removing one element leaves the pool working for the other.
      await page.evaluate(() => {
        document.querySelector('#a')!.remove();
        document.querySelector<PathwiseViewElement>('#b')!.reset();
      });
      await waitForEvent(page, b, 'converged', 2);
      expect(page.workers().length).toBe(poolSizes[0]);

      await expectWorkersTerminatedAfterRemoving(page, [b]);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('a moved element keeps tracing; a removed and re-added one starts again', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const view = await addView(page, 'moved', { src: 'scenes/cornell.json', spp: '4' });
      await waitForEvent(page, view, 'converged');
      const sameController = await page.evaluate(() => {
        const el = document.querySelector<PathwiseViewElement>('#moved')!;
        const before = el.controller;
        const box = document.createElement('div');
        document.body.append(box);
        box.append(el); // a move: disconnected and connected in one task
        return el.controller === before;
      });
      expect(sameController).toBe(true);
      // Removed in one task (its tracer is destroyed), re-added in another.
      await page.evaluate(() => {
        const el = document.querySelector('#moved')!;
        (window as unknown as { removed: Element }).removed = el;
        el.remove();
      });
      await page.evaluate(() =>
        document.body.append((window as unknown as { removed: Element }).removed),
      );
      await waitForEvent(page, view, 'load', 2);
      await waitForEvent(page, view, 'converged', 2);
      const image = await readPfm(page, view);
      const walls = wallColors(image.width, image.height, image.rgb);
      expect(isRed(walls.left) && isGreen(walls.right)).toBe(true);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('an element below the fold traces nothing until it is scrolled into view', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const view = await addView(
        page,
        'below',
        { src: 'scenes/cornell.json', spp: '8' },
        'margin-top: 3000px',
      );
      await waitForEvent(page, view, 'load');
      // A visible element with the same scene and target shares the worker
      // pool, which hands out work to its clients in turn: by the time the
      // visible one has converged, a running tracer below would have traced
      // too. (A paused view sends no progress heartbeat, so events cannot
      // be counted for this.)
      const above = await addView(
        page,
        'above',
        { src: 'scenes/cornell.json', spp: '8' },
        'display: block', // on a line of its own, not on the tall line of #below
      );
      await page.evaluate(() => document.body.prepend(document.querySelector('#above')!));
      await waitForEvent(page, above, 'converged');
      const before = await page.evaluate(() => {
        const el = document.querySelector<PathwiseViewElement>('#below')!;
        const c = el.controller as PathwiseViewElement['controller'] & { segmentsTraced(): number };
        return { spp: c.stats().spp, segments: c.segmentsTraced(), paused: c.paused };
      });
      expect(before).toEqual({ spp: 0, segments: 0, paused: true });
      const progress = (await eventLog(page, view)).filter((e) => e.type === 'progress');
      expect(progress.every((e) => (e.detail as ProgressInfo).spp === 0)).toBe(true);
      await page.evaluate(() => document.querySelector('#below')!.scrollIntoView());
      await waitForEvent(page, view, 'converged');
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('once converged it stops drawing and reporting, and a change wakes it', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const view = await addView(page, 'idle', { src: 'scenes/cornell.json', spp: '2' });
      await waitForEvent(page, view, 'converged');
      /** The controller's frame count and progress events over 20 of the page's frames. */
      const overFrames = () =>
        page.evaluate(async () => {
          const el = document.querySelector<LoggedView>('#idle')!;
          const c = el.controller as PathwiseViewElement['controller'] & { framesRun(): number };
          const count = () => ({
            frames: c.framesRun(),
            progress: el.log.filter((e) => e.type === 'progress').length,
          });
          // Let the frame that saw the last pass finish its bookkeeping.
          for (let i = 0; i < 3; i++) await new Promise(requestAnimationFrame);
          const before = count();
          for (let i = 0; i < 20; i++) await new Promise(requestAnimationFrame);
          return { before, after: count() };
        });
      const idle = await overFrames();
      expect(idle.after).toEqual(idle.before);
      // A display-only change wakes the loop for a redraw, then it idles again.
      await page.evaluate(() => {
        document.querySelector<PathwiseViewElement>('#idle')!.exposure = 2;
      });
      await page.waitForFunction(
        (n) =>
          (
            document.querySelector<PathwiseViewElement>('#idle')!.controller as unknown as {
              framesRun(): number;
            }
          ).framesRun() > n,
        idle.after.frames,
      );
      const again = await overFrames();
      expect(again.after).toEqual(again.before);
      // A reset traces again and converges a second time.
      await page.evaluate(() => document.querySelector<PathwiseViewElement>('#idle')!.reset());
      await waitForEvent(page, view, 'converged', 2);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('destroying a WebGL2 tracer loses its context', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const result = await page.evaluate(async () => {
        const m = (window as unknown as { pathwise: typeof import('../../src/widget/index.ts') })
          .pathwise;
        const canvas = document.createElement('canvas');
        document.body.append(canvas);
        const c = m.createPathTracer(canvas, {
          src: 'scenes/cornell.json',
          display: 'webgl2',
          width: 16,
          height: 16,
          spp: 1,
        });
        await new Promise((resolve) => c.addEventListener('converged', resolve, { once: true }));
        // A canvas hands out its one context again: the display's own.
        const gl = canvas.getContext('webgl2')!;
        const before = gl.isContextLost();
        c.destroy();
        return { display: c.mode.display, before, after: gl.isContextLost() };
      });
      expect(result).toEqual({ display: 'webgl2', before: false, after: true });
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('follows its size: a resized element renders at the new size', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const view = await addView(page, 'sized', { src: 'scenes/cornell.json', spp: '4' });
      await waitForEvent(page, view, 'converged');
      await page.evaluate(() => {
        document.querySelector<HTMLElement>('#sized')!.style.cssText = 'width: 96px; height: 48px';
      });
      await expect
        .poll(() =>
          page.evaluate(() => {
            const { width, height } = document
              .querySelector<PathwiseViewElement>('#sized')!
              .controller!.stats();
            return [width, height];
          }),
        )
        .toEqual([96, 48]);
      await waitForEvent(page, view, 'converged', 2);
      const image = await readPfm(page, view);
      expect([image.width, image.height]).toEqual([96, 48]);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('a hidden tab stops tracing, and a visible one resumes', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      // A target that is never reached, so only visibility decides.
      const view = await addView(page, 'tab', { src: 'scenes/cornell.json', spp: '1000000' });
      await page.waitForFunction(
        () => document.querySelector<PathwiseViewElement>('#tab')!.controller?.stats().spp,
      );
      // Headless Chromium never hides a tab, so this plays the browser's part:
      // document.hidden turns true and visibilitychange fires.
      const setHidden = (hidden: boolean) =>
        page.evaluate((h) => {
          Object.defineProperty(document, 'hidden', { configurable: true, get: () => h });
          document.dispatchEvent(new Event('visibilitychange'));
          return document.querySelector<PathwiseViewElement>('#tab')!.controller!.paused;
        }, hidden);
      expect(await setHidden(true)).toBe(true);
      expect(await setHidden(false)).toBe(false);
      const spp = await page.evaluate(
        () => document.querySelector<PathwiseViewElement>('#tab')!.controller!.stats().spp,
      );
      await page.waitForFunction(
        (n) => document.querySelector<PathwiseViewElement>('#tab')!.controller!.stats().spp > n,
        spp,
        { timeout: EVENT_WAIT_MS },
      );
      expect((await eventLog(page, view)).map((e) => e.type)).not.toContain('error');
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('registers under another name, and a second registration is harmless', async () => {
    const { page, errors, close } = await openPage(server, 'blank.html');
    try {
      const result = await page.evaluate(async () => {
        const m = (window as unknown as { pathwise: typeof import('../../src/widget/index.ts') })
          .pathwise;
        const again = m.definePathwiseView();
        const other = m.definePathwiseView('other-view');
        const el = document.createElement('other-view');
        return {
          sameAsBefore: again === customElements.get('pathwise-view'),
          isSubclass: other !== undefined && other !== again,
          instance: el instanceof m.PathwiseViewElement,
          upgraded: document.createElement('pathwise-view') instanceof m.PathwiseViewElement,
        };
      });
      expect(result).toEqual({
        sameAsBefore: true,
        isSubclass: true,
        instance: true,
        upgraded: true,
      });
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });
});

describe('<pathwise-view> on a cross-origin isolated page (COOP/COEP)', () => {
  let server: StaticServer;
  beforeAll(async () => {
    server = await serveDirectory(installed.project, { isolated: true });
  });
  afterAll(() => server?.close());

  test('renders through SharedArrayBuffer and converges to the Cornell box', async () => {
    const { page, errors, close } = await openPage(server, 'embed.html');
    try {
      expect(await page.evaluate(() => crossOriginIsolated)).toBe(true);
      const log = await expectConvergedCornellBox(page);
      const fallback = log.find((e) => e.type === 'fallback')!.detail as FallbackInfo;
      expect(fallback.compute).toBe('shared');
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('renders a glTF model given as src (shared textures)', async () => {
    await expectModelRendered(server, 'shared');
  });

  test('removing the element terminates its workers', async () => {
    const { page, errors, close } = await openPage(server, 'embed.html');
    try {
      await waitForEvent(page, '#view', 'converged');
      expect(page.workers().length).toBeGreaterThan(0);
      await expectWorkersTerminatedAfterRemoving(page, ['#view']);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });
});

describe('<pathwise-view> loaded from another origin (a CDN)', () => {
  let site: StaticServer;
  let cdn: StaticServer;
  beforeAll(async () => {
    site = await serveDirectory(installed.project);
    cdn = await serveDirectory(installed.project, { cdn: true });
  });
  afterAll(async () => {
    await site?.close();
    await cdn?.close();
  });

  // Browsers start workers only from same-origin scripts; worker-url makes
  // the element start its workers through a same-origin module shim.
  test('with worker-url on the CDN it renders the Cornell box', async () => {
    const worker = `${cdn.url}node_modules/pathwise/dist/lib/render-worker.js`;
    writeCdnPage(
      installed.project,
      installed.packageDir,
      'cdn-worker-url.html',
      cdn.url,
      `<pathwise-view id="view" src="scenes/cornell.json" spp="16" worker-url="${worker}"></pathwise-view>
    <script>record(document.getElementById('view'));</script>`,
    );
    const { page, errors, close } = await openPage(site, 'cdn-worker-url.html');
    try {
      await expectConvergedCornellBox(page);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  // The package's default worker URL is on the CDN too: the pool must
  // start it through the same shim rather than fail with no one told.
  test('without worker-url it still renders the Cornell box', async () => {
    writeCdnPage(
      installed.project,
      installed.packageDir,
      'cdn-default-worker.html',
      cdn.url,
      `<pathwise-view id="view" src="scenes/cornell.json" spp="16"></pathwise-view>
    <script>record(document.getElementById('view'));</script>`,
    );
    const { page, errors, close } = await openPage(site, 'cdn-default-worker.html');
    try {
      await expectConvergedCornellBox(page);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });
});

describe('<pathwise-view> in an app bundled by Vite', () => {
  let server: StaticServer;
  beforeAll(async () => {
    const app = writeViteApp(installed.project);
    // The repository's Vite builds the app; 'pathwise' resolves to the installed package.
    execFileSync(process.execPath, [join(REPO, 'node_modules/vite/bin/vite.js'), 'build'], {
      cwd: app,
      stdio: ['ignore', 'pipe', 'pipe'],
    });
    server = await serveDirectory(join(app, 'dist'));
  });
  afterAll(() => server?.close());

  test('the bundled worker loads and the view converges to the Cornell box', async () => {
    const { page, errors, close } = await openPage(server, 'index.html');
    try {
      await expectConvergedCornellBox(page);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });
});
