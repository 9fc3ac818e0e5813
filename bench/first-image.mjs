// Time to the first image of the demo in headless Chromium, at the default
// (automatic) render scale, on a desktop and on a DPR-3 phone viewport:
//   node bench/first-image.mjs [--runs 5] [--seconds 10]
// Per page load: when the scene was loaded, when the first whole picture
// (the quick pass in the preview film) and the first whole image of the
// full film were drawn, both from navigation start and from the scene
// load; the size chosen; and, after --seconds, the samples per pixel and
// the noise, next to the same for the old default size (render scale 1,
// devicePixelRatio uncapped: ?scale=1&dpr=4). Not a test: nothing is asserted. Writes
// bench/results/first-image.json.
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { build, preview } from 'vite';

const root = fileURLToPath(new URL('..', import.meta.url));
const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? Number(args[i + 1]) : fallback;
};
const runs = arg('runs', 5);
const seconds = arg('seconds', 10);

function median(values) {
  const s = values.filter(Number.isFinite).sort((a, b) => a - b);
  return s.length ? s[Math.floor(s.length / 2)] : NaN;
}

const tmp = mkdtempSync(join(tmpdir(), 'pathwise-bench-'));
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

const devices = {
  desktop: { viewport: { width: 1280, height: 900 }, deviceScaleFactor: 1 },
  phone: {
    viewport: { width: 390, height: 844 },
    deviceScaleFactor: 3,
    isMobile: true,
    hasTouch: true,
  },
};

/** One page load; returns its timeline, sizes and, after `seconds`, spp and noise. */
async function load(device, query, wait) {
  const context = await browser.newContext(devices[device]);
  const page = await context.newPage();
  await page.goto(`${url}?${query}`);
  await page.waitForFunction(() => window.__pathwise?.controller.timeline().firstImage > 0, null, {
    timeout: 120_000,
    polling: 'raf',
  });
  const first = await page.evaluate(() => {
    const c = window.__pathwise.controller;
    const s = c.stats();
    return { timeline: c.timeline(), width: s.width, height: s.height };
  });
  let later = null;
  if (wait) {
    await page.waitForTimeout(seconds * 1000);
    later = await page.evaluate(() => {
      const c = window.__pathwise.controller;
      const s = c.stats();
      return {
        spp: s.spp,
        noise: s.noise,
        width: s.width,
        height: s.height,
        scale: c.renderScaleInfo(),
      };
    });
  }
  await context.close();
  return { ...first, later };
}

const results = { runs, seconds, loadAverageBefore: loadavg(), devices: {} };
for (const device of Object.keys(devices)) {
  const loads = [];
  for (let i = 0; i < runs; i++) loads.push(await load(device, 'seed=1', i === 0));
  const t = (k) => loads.map((l) => l.timeline[k]);
  const since = (k) => loads.map((l) => l.timeline[k] - l.timeline.sceneLoaded);
  const old = await load(device, 'seed=1&scale=1&dpr=4', true);
  results.devices[device] = {
    firstPictureMs: {
      median: median(t('firstPicture')),
      sinceSceneLoad: median(since('firstPicture')),
    },
    firstImageMs: { median: median(t('firstImage')), sinceSceneLoad: median(since('firstImage')) },
    sceneLoadedMs: median(t('sceneLoaded')),
    firstImageSize: loads.map((l) => `${l.width}x${l.height}`),
    afterSeconds: loads[0].later,
    oldDefaultAfterSeconds: old.later,
    oldDefaultFirstImageSinceSceneLoadMs: old.timeline.firstImage - old.timeline.sceneLoaded,
  };
  console.log(device, JSON.stringify(results.devices[device]));
}
results.loadAverageAfter = loadavg();
await browser.close();
await server.close();
rmSync(tmp, { recursive: true, force: true });
writeFileSync(
  join(root, 'bench/results/first-image.json'),
  JSON.stringify(results, null, 1) + '\n',
);
