/**
 * Time from `src` set to the first sample for a large glTF in headless Chromium (issue
 * 13: goal under 3 s for 1M triangles), and how long the main thread is blocked
 * meanwhile. Builds the demo for production, serves it with COOP/COEP (`vite preview`),
 * serves a generated GLB grid (gltf-grid.ts; --textured adds a 2048² base colour and a
 * normal map) from the same origin, and per run: sets `src` of a <pathwise-view>, then
 * records when each loading stage began (loadprogress), when `load` fired and when the
 * first sample arrived (the first `progress` event), the longest main-thread task
 * (PerformanceObserver 'longtask', ≥ 50 ms) and the page's JS heap after loading.
 * Medians over --runs. Not a test: nothing is asserted.
 * Run: node scripts/run-ts.mjs bench/gltf-first-sample.ts [--textured] [--triangles N] [--runs 3]
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { chromium } from 'playwright-core';
import { build, preview } from 'vite';
import { PreloadedIO } from '../src/core/gltf/io.ts';
import { gridDocument } from './gltf-grid.ts';

const args = process.argv.slice(2);
const arg = (name: string, fallback: number) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? Number(args[i + 1]) : fallback;
};
const textured = args.includes('--textured');
const triangles = arg('triangles', 1_000_000);
const runs = arg('runs', 3);

const median = (a: number[]) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];

const glb = await new PreloadedIO().writeBinary(gridDocument(triangles, textured));
// run-ts.mjs bundles this file elsewhere; argv[1] is where it really is.
const root = resolve(dirname(process.argv[1]), '..');
const tmp = mkdtempSync(join(tmpdir(), 'pathwise-bench-gltf-'));
const outDir = join(tmp, 'web');
await build({ root, logLevel: 'error', build: { outDir, emptyOutDir: true } });
const server = await preview({
  root,
  logLevel: 'error',
  build: { outDir },
  preview: { host: '127.0.0.1', port: 0 },
});
const url = server.resolvedUrls!.local[0];
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium',
  args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--no-first-run'],
});

interface Run {
  stages: Record<string, number>;
  loadMs: number;
  firstSampleMs: number;
  longestTaskMs: number;
  heapMiB: number;
}

async function once(): Promise<Run> {
  const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
  await page.route('**/bench/grid.glb', (route) =>
    route.fulfill({ body: Buffer.from(glb), contentType: 'model/gltf-binary' }),
  );
  // The demo page, for its bundle: the element is registered from the same build.
  await page.goto(`${url}?spp=4`);
  await page.waitForFunction(() => 'controller' in ((window as any).__pathwise ?? {}));
  const run = await page.evaluate(async () => {
    const w = window as any;
    // The demo's own view stops, so that only the model's load and render are timed.
    w.__pathwise.controller.destroy();
    const longTasks: number[] = [];
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) longTasks.push(e.duration);
    }).observe({ type: 'longtask', buffered: false });
    const tracer = w.__pathwise.createPathTracer(
      Object.assign(document.createElement('canvas'), { width: 400, height: 300 }),
      { spp: 4, cameraControls: false },
    );
    document.body.append(tracer.canvas);
    const stages: Record<string, number> = {};
    const t0 = performance.now();
    tracer.addEventListener('loadprogress', (e: CustomEvent) => {
      stages[e.detail.stage] ??= Math.round(performance.now() - t0);
    });
    let loadMs = NaN;
    tracer.addEventListener('load', () => (loadMs = performance.now() - t0));
    const first = new Promise<number>((resolve) =>
      tracer.addEventListener('progress', (e: CustomEvent) => {
        if (e.detail.spp > 0) resolve(performance.now() - t0);
      }),
    );
    await tracer.load('bench/grid.glb');
    const firstSampleMs = await first;
    const heap = (performance as any).memory?.usedJSHeapSize ?? NaN;
    tracer.destroy();
    return {
      stages,
      loadMs,
      firstSampleMs,
      longestTaskMs: Math.max(0, ...longTasks),
      heapMiB: heap / 2 ** 20,
    };
  });
  await page.close();
  return run;
}

const results: Run[] = [];
try {
  for (let r = 0; r < runs; r++) results.push(await once());
} finally {
  await browser.close();
  await server.close();
  rmSync(tmp, { recursive: true, force: true });
}
console.log(
  JSON.stringify(
    {
      file: { bytes: glb.length, triangles, textured },
      runs,
      medianMs: {
        load: Math.round(median(results.map((r) => r.loadMs))),
        firstSample: Math.round(median(results.map((r) => r.firstSampleMs))),
        longestMainThreadTask: Math.round(median(results.map((r) => r.longestTaskMs))),
      },
      stagesStartMs: results.map((r) => r.stages),
      heapMiB: Math.round(median(results.map((r) => r.heapMiB))),
    },
    null,
    2,
  ),
);
