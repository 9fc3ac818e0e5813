// Speed of the browser demo in headless Chromium, against the command line:
//   node bench/browser-demo.mjs [--width 1280] [--height 520] [--ab 3]
// With --ab N it only runs N interleaved rounds of the demo's Benchmark at the default
// display, with the resting draw cap (REST_DRAW_MS, src/view/frame-loop.ts) and without
// it (`?restdraw=0`), and reports the medians and their ratio.
// Reports (issue 3): M rays/s of the demo's Benchmark on the Cornell box
// with all workers vs `pathwise render` msegments_per_s at the same size;
// main-thread ms per frame for upload + display; time from a camera change
// to the first frame showing new samples. Not a test: nothing is asserted.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium, serveBuiltDemo } from './browser.mjs';

const root = fileURLToPath(new URL('..', import.meta.url));
const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? Number(args[i + 1]) : fallback;
};
const width = arg('width', 1280);
const height = arg('height', 520);
/** The demo's Benchmark runs a fixed 10 s; this only bounds the wait for it. */
const seconds = 10;

function median(values) {
  const s = [...values].sort((a, b) => a - b);
  return s.length ? s[Math.floor(s.length / 2)] : NaN;
}

function percentile(values, p) {
  const s = [...values].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor(s.length * p))] : NaN;
}

// 1. The command line, all threads.
execFileSync(process.execPath, ['scripts/build-cli.mjs'], { cwd: root });
const tmp = mkdtempSync(join(tmpdir(), 'pathwise-bench-'));
/** `pathwise render` of the Cornell box at the demo's size, all threads. */
function cliRun(spp) {
  return JSON.parse(
    execFileSync(
      process.execPath,
      [
        'bin/pathwise.js',
        'render',
        'scenes/cornell.json',
        '--width',
        String(width),
        '--height',
        String(height),
        '--spp',
        String(spp),
        '--json',
        '--out',
        join(tmp, 'x.pfm'),
      ],
      { cwd: root, encoding: 'utf8' },
    ),
  );
}
// 4 spp is the figure the issue names; its few seconds include worker
// start-up and JIT warm-up, so a 16-spp run gives the steady rate too.
const cli = cliRun(4);
const cliLong = cliRun(16);

// 2. The demo, as built for production, served with COOP/COEP by `vite preview`.
const { server, url } = await serveBuiltDemo(join(tmp, 'web'));
const browser = await launchChromium();

async function open(query) {
  const page = await browser.newPage({ viewport: { width: 1600, height: 900 } });
  await page.goto(`${url}?width=${width}&height=${height}&${query}`);
  await page.waitForFunction(() => window.__pathwise?.controller?.stats().spp >= 1, null, {
    timeout: 120_000,
  });
  return page;
}

/** Main-thread ms of upload + display per drawn frame, over `ms` of rendering. */
async function frameTimes(page, ms) {
  return page.evaluate(
    (ms) =>
      new Promise((resolve) => {
        const c = window.__pathwise.controller;
        const out = [];
        const end = performance.now() + ms;
        let last = -1;
        const tick = () => {
          const s = c.stats();
          // frameMs belongs to the latest draw; record each draw once.
          if (s.frameMs !== last) out.push(s.frameMs);
          last = s.frameMs;
          if (performance.now() < end) requestAnimationFrame(tick);
          else resolve(out);
        };
        requestAnimationFrame(tick);
      }),
    ms,
  );
}

/**
 * Camera change to the first animation frame whose film holds a sample of
 * the new view. `preview` orbits as a drag does (low-resolution film).
 */
async function cameraLatency(page, preview, trials) {
  return page.evaluate(
    ({ preview, trials }) =>
      new Promise((resolve) => {
        const c = window.__pathwise.controller;
        const results = [];
        const trial = () => {
          if (preview) c.beginPreview();
          const t0 = performance.now();
          c.orbit(6, 0);
          const job = preview ? c.films.preview : c.films.full;
          const check = () => {
            const sums = job.film.sums;
            for (let i = 3; i < sums.length; i += 4) {
              if (sums[i] > 0) {
                results.push(performance.now() - t0);
                if (preview) c.endPreview();
                if (results.length < trials) setTimeout(trial, 150);
                else resolve(results);
                return;
              }
            }
            requestAnimationFrame(check);
          };
          requestAnimationFrame(check);
        };
        trial();
      }),
    { preview, trials },
  );
}

/** One display mode: frame times, camera latencies and the Benchmark button's 10 s run. */
async function benchmarkButton(page) {
  await page.click('#benchmark');
  await page.waitForFunction(() => document.getElementById('bench-result')?.dataset.mrays, null, {
    timeout: (seconds + 60) * 1000,
  });
  return Number(await page.evaluate(() => document.getElementById('bench-result').dataset.mrays));
}

async function measure(display) {
  const page = await open(`seed=1${display ? `&display=${display}` : ''}`);
  const mode = await page.evaluate(() => window.__pathwise.controller.mode);
  const frames = await frameTimes(page, 3000);
  const latencyFull = await cameraLatency(page, false, 8);
  const latencyPreview = await cameraLatency(page, true, 8);
  await page.click('#benchmark');
  await page.waitForFunction(() => document.getElementById('bench-result')?.dataset.mrays, null, {
    timeout: (seconds + 60) * 1000,
  });
  const benchmark = await page.locator('#bench-result').textContent();
  const mrays = Number(
    await page.evaluate(() => document.getElementById('bench-result').dataset.mrays),
  );
  await page.close();
  return {
    mode,
    mraysPerSecond: mrays,
    demoVsCli4: mrays / cli.msegments_per_s,
    demoVsCli16: mrays / cliLong.msegments_per_s,
    benchmark,
    frameMs: { median: median(frames), p95: percentile(frames, 0.95), frames: frames.length },
    cameraChangeToFirstFrameMs: {
      full: { median: median(latencyFull), max: Math.max(...latencyFull) },
      preview: { median: median(latencyPreview), max: Math.max(...latencyPreview) },
    },
  };
}

const info = await (async () => {
  const page = await browser.newPage();
  await page.goto(url);
  const r = await page.evaluate(() => ({
    cores: navigator.hardwareConcurrency,
    version: navigator.userAgent,
  }));
  await page.close();
  return r;
})();
const abRounds = arg('ab', 0);
if (abRounds > 0) {
  const capped = [];
  const every = [];
  for (let i = 0; i < abRounds; i++) {
    for (const [query, into] of [
      ['seed=1', capped],
      ['seed=1&restdraw=0', every],
    ]) {
      const page = await open(query);
      const mrays = await benchmarkButton(page);
      const fps = await page.evaluate(() => window.__pathwise.controller.stats().fps);
      into.push({ mrays, fps });
      await page.close();
    }
  }
  await browser.close();
  await new Promise((resolve) => server.httpServer.close(resolve));
  rmSync(tmp, { recursive: true, force: true });
  const m = (xs, k) => median(xs.map((x) => x[k]));
  console.log(
    JSON.stringify(
      {
        size: `${width}x${height}`,
        rounds: abRounds,
        capped: { runs: capped, medianMrays: m(capped, 'mrays') },
        everyFrame: { runs: every, medianMrays: m(every, 'mrays') },
        ratio: m(capped, 'mrays') / m(every, 'mrays'),
        cliMsegmentsPerSecond16spp: cliLong.msegments_per_s,
        cappedVsCli: m(capped, 'mrays') / cliLong.msegments_per_s,
        everyFrameVsCli: m(every, 'mrays') / cliLong.msegments_per_s,
        loadAverage: loadavg(),
      },
      null,
      2,
    ),
  );
  process.exit(0);
}
// The default ('auto': Canvas 2D where WebGL2 runs in software) and each path by name.
const auto = await measure(null);
const webgl2 = await measure('webgl2');
const canvas2d = await measure('canvas2d');

await browser.close();
await new Promise((resolve) => server.httpServer.close(resolve));
rmSync(tmp, { recursive: true, force: true });

const report = {
  size: `${width}x${height}`,
  browser: info.version,
  cores: info.cores,
  cli: {
    spp4: { msegmentsPerSecond: cli.msegments_per_s, seconds: cli.seconds },
    spp16: { msegmentsPerSecond: cliLong.msegments_per_s, seconds: cliLong.seconds },
    threads: cli.threads,
  },
  demo: { auto, webgl2, canvas2d },
  loadAverage: loadavg(),
};
console.log(JSON.stringify(report, null, 2));
