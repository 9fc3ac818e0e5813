/**
 * The package as the README tells people to use it, from a fresh install of
 * the packed tarball: no install-time scripts, the canonical scenes in the
 * package, the README's page copied literally and served as is, the
 * README's bundler snippet built by webpack 5 and by esbuild, and the
 * element's accessible name. Each page must show the Cornell box.
 */
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import type { Browser, Page } from 'playwright-core';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { launchChromium } from '../helpers/chromium.ts';
import { isGreen, isRed, wallColors } from './fixture/cornell-colors.ts';
import { installPackedPackage, REPO, type InstalledPackage } from './fixture/install-package.ts';
import { serveDirectory, type StaticServer } from './fixture/static-server.ts';

const WAIT_MS = 90_000;

let installed: InstalledPackage;
let browser: Browser;
let server: StaticServer;

beforeAll(async () => {
  installed = installPackedPackage();
  browser = await launchChromium();
  server = await serveDirectory(installed.project);
});

afterAll(async () => {
  await browser?.close();
  await server?.close();
  if (installed) rmSync(installed.dir, { recursive: true, force: true });
});

/** The code block that follows `marker` in the README, exactly as written. */
function readmeBlock(marker: string, language: string): string {
  const readme = readFileSync(join(REPO, 'README.md'), 'utf8');
  const at = readme.indexOf(marker);
  expect(at, `README marker ${marker}`).toBeGreaterThan(0);
  const fence = '```' + language + '\n';
  const start = readme.indexOf(fence, at) + fence.length;
  return readme.slice(start, readme.indexOf('\n```', start) + 1);
}

async function open(path: string) {
  const context = await browser.newContext({ viewport: { width: 800, height: 600 } });
  const page = await context.newPage();
  const errors: string[] = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => {
    // A failed request is reported below with its URL.
    if (m.type() === 'error' && !m.text().startsWith('Failed to load resource')) {
      errors.push(m.text());
    }
  });
  page.on('response', (r) => {
    // The browser asks every site for a favicon the page never mentioned.
    if (r.status() >= 400 && !r.url().endsWith('/favicon.ico')) {
      errors.push(`HTTP ${r.status()} ${r.url()}`);
    }
  });
  await page.goto(server.url + path);
  return { page, errors, close: () => context.close() };
}

/** Waits until the first <pathwise-view> has `spp` samples per pixel and checks the picture. */
async function expectCornellBox(page: Page, spp: number) {
  await page.waitForFunction(
    (n) => {
      const el = document.querySelector('pathwise-view') as unknown as {
        controller: { stats(): { spp: number } } | null;
      } | null;
      return (el?.controller?.stats().spp ?? 0) >= n;
    },
    spp,
    { timeout: WAIT_MS, polling: 100 },
  );
  // The image and its sample count are read in one task of the page: between
  // two reads the element may restart (its render scale is chosen from the
  // measured speed), and a restarted film is black until its first pass.
  const deadline = Date.now() + WAIT_MS;
  let read: { spp: number; bytes: number[] };
  for (;;) {
    read = await page.evaluate(() => {
      const el = document.querySelector('pathwise-view') as unknown as {
        controller: { stats(): { spp: number } };
        toPFM(): Uint8Array;
      };
      return { spp: el.controller.stats().spp, bytes: Array.from(el.toPFM()) };
    });
    if (read.spp >= spp || Date.now() > deadline) break;
    await page.waitForTimeout(100);
  }
  expect(read.spp, 'samples per pixel of the image read').toBeGreaterThanOrEqual(spp);
  const image = decodePfm(Uint8Array.from(read.bytes));
  const walls = wallColors(image.width, image.height, image.rgb);
  expect(isRed(walls.left), `left wall ${walls.left}`).toBe(true);
  expect(isGreen(walls.right), `right wall ${walls.right}`).toBe(true);
  // No error message inside the element.
  expect(await page.locator('pathwise-view [part=message]').isVisible()).toBe(false);
}

describe('the installed package', () => {
  test('has no install-time scripts, and installing it prints no warning about scripts', () => {
    const pkg = JSON.parse(readFileSync(join(installed.packageDir, 'package.json'), 'utf8')) as {
      scripts?: Record<string, string>;
    };
    const lifecycle = [
      'preinstall',
      'install',
      'postinstall',
      'prepare',
      'preprepare',
      'postprepare',
    ];
    expect(Object.keys(pkg.scripts ?? {}).filter((s) => lifecycle.includes(s))).toEqual([]);
    expect(installed.installLog).not.toMatch(/script/i);
  });

  test('ships the canonical scenes as pathwise/scenes/*.json', () => {
    for (const name of ['cornell', 'spheres', 'mirror']) {
      const shipped = readFileSync(join(installed.packageDir, 'scenes', `${name}.json`), 'utf8');
      expect(shipped).toBe(readFileSync(join(REPO, 'scenes', `${name}.json`), 'utf8'));
    }
    // Reachable through the exports map, as a bundler resolves it.
    const file = join(installed.project, 'import-scene.mjs');
    writeFileSync(
      file,
      `import cornell from 'pathwise/scenes/cornell.json' with { type: 'json' };\nconsole.log(cornell.name);\n`,
    );
    expect(execFileSync(process.execPath, [file], { encoding: 'utf8' }).trim()).toBe('Cornell box');
  });
});

describe("the README's examples, copied literally", () => {
  test('the element page renders the Cornell box, named by its alt text, keyboard-operable', async () => {
    const html = readmeBlock('tested exactly as written', 'html');
    expect(html).toContain('<pathwise-view');
    writeFileSync(join(installed.project, 'index.html'), html);
    const { page, errors, close } = await open('index.html');
    try {
      await expectCornellBox(page, 2);
      // camera-controls: a named group around a focusable, named image.
      const alt = await page.locator('pathwise-view').getAttribute('alt');
      expect(alt).toMatch(/Cornell box/);
      await expect.poll(() => page.getByRole('group', { name: alt! }).count()).toBe(1);
      const picture = page.getByRole('img', { name: alt! });
      await expect.poll(() => picture.count()).toBe(1);
      // Tab reaches the canvas; an arrow key orbits the camera.
      const before = await page.evaluate(
        () =>
          (
            document.querySelector('pathwise-view') as unknown as {
              controller: { getCamera(): { position: number[] } };
            }
          ).controller.getCamera().position,
      );
      await page.keyboard.press('Tab');
      expect(
        await picture.evaluate((el) => el === (el.getRootNode() as ShadowRoot).activeElement),
      ).toBe(true);
      await page.keyboard.press('ArrowLeft');
      const after = await page.evaluate(
        () =>
          (
            document.querySelector('pathwise-view') as unknown as {
              controller: { getCamera(): { position: number[] } };
            }
          ).controller.getCamera().position,
      );
      expect(after).not.toEqual(before);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  /** The bundler snippet as an app's entry, and a page around its bundle. */
  function writeApp(dir: string, body: string, script: string): string {
    const app = join(installed.project, dir);
    mkdirSync(join(app, 'src'), { recursive: true });
    mkdirSync(join(app, 'dist'), { recursive: true });
    writeFileSync(
      join(app, 'src', 'index.js'),
      readmeBlock('entry of the webpack and esbuild apps', 'js'),
    );
    writeFileSync(
      join(app, 'dist', 'index.html'),
      `<!doctype html>
<html>
  <head><meta charset="utf-8" /><style>pathwise-view { width: 64px; height: 64px; }</style></head>
  <body>
    ${body}
    ${script}
  </body>
</html>
`,
    );
    return app;
  }

  test('webpack 5 bundles the snippet and its worker; the page renders the Cornell box', async () => {
    const app = writeApp(
      'webpack-app',
      '<pathwise-view spp="4"></pathwise-view>',
      '<script src="app.js"></script>',
    );
    const webpack = (await import('webpack')).default;
    const stats = await new Promise<import('webpack').Stats>((resolve, reject) =>
      webpack(
        {
          mode: 'production',
          context: app,
          entry: './src/index.js',
          output: { path: join(app, 'dist'), filename: 'app.js', publicPath: 'auto' },
          performance: { hints: false },
        },
        (err, s) => (err || !s ? reject(err) : resolve(s)),
      ),
    );
    expect(stats.hasErrors(), stats.toString('errors-only')).toBe(false);
    const { page, errors, close } = await open('webpack-app/dist/index.html');
    try {
      await expectCornellBox(page, 4);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });

  test('esbuild bundles the snippet; with the worker copied as the README says, it renders', async () => {
    const app = writeApp(
      'esbuild-app',
      '<pathwise-view worker-url="render-worker.js" spp="4"></pathwise-view>',
      '<script type="module" src="app.js"></script>',
    );
    const esbuild = await import('esbuild');
    await esbuild.build({
      absWorkingDir: app,
      entryPoints: ['src/index.js'],
      bundle: true,
      format: 'esm',
      outfile: 'dist/app.js',
      logLevel: 'silent',
    });
    // cp node_modules/pathwise/dist/lib/render-worker.js dist/
    copyFileSync(
      join(installed.packageDir, 'dist', 'lib', 'render-worker.js'),
      join(app, 'dist', 'render-worker.js'),
    );
    const { page, errors, close } = await open('esbuild-app/dist/index.html');
    try {
      await expectCornellBox(page, 4);
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });
});

describe('<pathwise-view> accessibility', () => {
  test('the host and canvas are named images: the scene by default, alt or aria-label when given', async () => {
    writeFileSync(
      join(installed.project, 'a11y.html'),
      `<!doctype html>
<script type="importmap">{ "imports": { "pathwise": "/node_modules/pathwise/dist/lib/pathwise.js" } }</script>
<style>pathwise-view { width: 48px; height: 48px; }</style>
<pathwise-view id="plain" src="/node_modules/pathwise/scenes/cornell.json" spp="1"></pathwise-view>
<pathwise-view id="alt" alt="A test picture" src="/node_modules/pathwise/scenes/cornell.json" spp="1"></pathwise-view>
<pathwise-view id="author" aria-label="Named by the page" spp="1"></pathwise-view>
<script type="module">import 'pathwise';</script>
`,
    );
    const { page, errors, close } = await open('a11y.html');
    try {
      // Before the scene loads the name is generic; then it names the scene.
      await expect
        .poll(() => page.getByRole('img', { name: 'Cornell box, rendered by pathwise' }).count(), {
          timeout: WAIT_MS,
        })
        .toBe(2); // the host and its canvas
      expect(await page.locator('#plain').getAttribute('role')).toBe('img');
      expect(await page.getByRole('img', { name: 'A test picture' }).count()).toBe(2);
      expect(await page.locator('#author').getAttribute('aria-label')).toBe('Named by the page');
      // Without camera-controls the canvas is not a tab stop.
      expect(await page.locator('#plain canvas').getAttribute('tabindex')).toBeNull();
      // Turning camera controls on makes the canvas focusable and the host a group.
      await page.evaluate(() =>
        document.querySelector('#plain')!.setAttribute('camera-controls', ''),
      );
      expect(await page.locator('#plain').getAttribute('role')).toBe('group');
      expect(await page.locator('#plain canvas').getAttribute('tabindex')).toBe('0');
      expect(errors).toEqual([]);
    } finally {
      await close();
    }
  });
});
