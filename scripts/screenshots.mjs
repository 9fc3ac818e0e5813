// Screenshots of the demo for the docs: docs/demo-desktop.png (1280×800),
// docs/demo-phone.png and docs/demo-phone-plot.png (390×844 at
// devicePixelRatio 2: the top of the page, and scrolled to the error plot),
// taken from the production build in
// headless Chromium after --seconds of rendering the Cornell box.
//   node scripts/screenshots.mjs [--seconds 20]
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { build, preview } from 'vite';

const root = fileURLToPath(new URL('..', import.meta.url));
const args = process.argv.slice(2);
const at = args.indexOf('--seconds');
const seconds = at >= 0 ? Number(args[at + 1]) : 20;

const tmp = mkdtempSync(join(tmpdir(), 'pathwise-shots-'));
const outDir = join(tmp, 'web');
await build({ root, logLevel: 'error', build: { outDir, emptyOutDir: true } });
const server = await preview({
  root,
  logLevel: 'error',
  build: { outDir },
  preview: { host: '127.0.0.1', port: 0 },
});
const url = server.resolvedUrls.local[0];
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--no-first-run'],
});

async function shoot(name, options, prepare) {
  const context = await browser.newContext(options);
  const page = await context.newPage();
  await page.goto(`${url}?seed=1`);
  await page.waitForFunction(() => window.__pathwise?.controller.stats().spp >= 1);
  await page.waitForTimeout(seconds * 1000);
  await prepare?.(page);
  await page.screenshot({ path: join(root, 'docs', name) });
  const stats = await page.evaluate(() => window.__pathwise.controller.stats());
  console.log(name, `${stats.width}x${stats.height}`, `${stats.spp} spp`);
  await context.close();
}

await shoot('demo-desktop.png', { viewport: { width: 1280, height: 800 } });
const phone = {
  viewport: { width: 390, height: 844 },
  deviceScaleFactor: 2,
  isMobile: true,
  hasTouch: true,
};
await shoot('demo-phone.png', phone);
await shoot('demo-phone-plot.png', phone, (page) =>
  page.evaluate(() => document.getElementById('error-title').scrollIntoView()),
);
await browser.close();
await server.close();
rmSync(tmp, { recursive: true, force: true });
