// Which render scale gives the demo's lowest denoised error after 5 s (issue 22)?
//   node bench/denoise-scale.mjs [--scales 0.25,0.33,0.5,0.75,1] [--runs 3] [--seconds 5]
// The demo as built for production (vite preview, COOP/COEP), Cornell, the Denoise switch
// on, the page 1280×720 at devicePixelRatio 1, every worker; for each fixed render scale
// (`?scale=`) and seed it waits `--seconds` of tracing and reads the error plot's points
// (tests/browser/error-plot.test.ts checks them): the true relMSE of the raw film and of
// the denoised picture on screen at that time, both on the plot's grid against the
// Mitsuba reference. Prints a table of medians over the runs. Not a test.
import { mkdtempSync, rmSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { build, preview } from 'vite';

const root = fileURLToPath(new URL('..', import.meta.url));
const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : fallback;
};
const scales = arg('scales', '0.25,0.33,0.5,0.75,1').split(',').map(Number);
const runs = Number(arg('runs', '3'));
const seconds = Number(arg('seconds', '5'));
const median = (v) => {
  const s = v.filter(Number.isFinite).sort((a, b) => a - b);
  return s.length ? s[Math.floor(s.length / 2)] : NaN;
};

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

async function run(scale, seed) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(`${url}?denoise=1&scale=${scale}&seed=${seed}`);
  await page.waitForFunction(() => window.__pathwise?.controller, null, { timeout: 120_000 });
  const r = await page.evaluate(
    `(async () => {
      const { controller: c, errorMeter: m } = window.__pathwise;
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      let first = NaN;
      c.addEventListener('denoised', (e) => { if (!(first > 0)) first = c.filmSnapshot()?.seconds ?? NaN; });
      while (!(c.filmSnapshot()?.seconds >= ${seconds})) await frame();
      // The meter samples every 250 ms: let it take the point at the end.
      await new Promise((r) => setTimeout(r, 600));
      const pts = m.points.filter((p) => p.seconds <= ${seconds});
      const last = (key) => { for (let i = pts.length - 1; i >= 0; i--) if (pts[i][key] > 0) return pts[i]; return null; };
      const raw = last('truth'), den = last('denoised');
      const s = c.stats();
      return { width: s.width, height: s.height, raw: raw?.truth ?? NaN, rawSpp: raw?.spp ?? 0,
        denoised: den?.denoised ?? NaN, denoisedSpp: den?.spp ?? 0, denoisedAt: den?.seconds ?? NaN,
        firstDenoised: first, note: m.note };
    })()`,
  );
  await page.close();
  return r;
}

console.log(
  `load average at start: ${loadavg()
    .map((l) => l.toFixed(2))
    .join(' ')}`,
);
console.log(
  `| scale | film | raw relMSE at ${seconds} s (spp) | denoised relMSE at ${seconds} s (from spp, shown at s) | first denoised (s) |`,
);
console.log('| --- | --- | --- | --- | --- |');
for (const scale of scales) {
  const rs = [];
  for (let i = 0; i < runs; i++) rs.push(await run(scale, i + 1));
  const m = (k) => median(rs.map((r) => r[k]));
  if (rs[0].note) console.log(`(scale ${scale}: ${rs[0].note})`);
  console.log(
    `| ${scale} | ${rs[0].width}×${rs[0].height} | ${m('raw').toExponential(2)} (${m('rawSpp')}) | ${m('denoised').toExponential(2)} (${m('denoisedSpp')}, ${m('denoisedAt').toFixed(1)}) | ${m('firstDenoised').toFixed(2)} |`,
  );
}
console.log(
  `load average at end: ${loadavg()
    .map((l) => l.toFixed(2))
    .join(' ')}`,
);
await browser.close();
await server.close();
rmSync(tmp, { recursive: true, force: true });
