// Adaptive against uniform sampling in the browser demo (issue 23: "the widget uses it"):
// the demo, built for production and served with COOP/COEP, in headless Chromium,
// renders each canonical preset at its reference's size with `?adaptive=1` and
// `?adaptive=0`, interleaved, for a few seeds; the demo's own error meter
// (src/app/error-meter.ts) gives the true relMSE against the committed reference on its
// comparison grid, by tracing time. Reported: the time each reached a relMSE target
// (interpolated on log-log axes between the meter's points) and the ratio uniform /
// adaptive. Not a test: nothing is asserted.
//
// The meter's grid averages film pixels into cells, so its relMSE is lower than the
// per-pixel one of the command line's benchmarks at the same samples: hence a lower target.
// Also reported: the ratio of the two relMSEs at the last time both reached (equal time).
//
//   node bench/browser-adaptive.mjs [--seconds 20] [--seeds 1,2] [--target 1e-4]
//     [--scenes cornell,spheres,mirror] [--workers 2]
import { mkdtempSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { launchChromium, serveBuiltDemo } from './browser.mjs';
import { logLogCrossing, logLogInterp } from './lib.mjs';

const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : fallback;
};
const seconds = Number(arg('seconds', '20'));
const seeds = arg('seeds', '1,2').split(',').map(Number);
const target = Number(arg('target', '1e-4'));
const scenes = arg('scenes', 'cornell,spheres,mirror').split(',');
const workers = Number(arg('workers', '2'));
/** The references' sizes (src/app/references.ts, REFERENCE_SIZES). */
const SIZES = { cornell: [128, 128], spheres: [160, 90], mirror: [128, 128], sky: [128, 128] };

const { server, url } = await serveBuiltDemo(
  join(mkdtempSync(join(tmpdir(), 'pathwise-bench-')), 'web'),
);
const browser = await launchChromium();

/** Tracing seconds at which `points` (the error meter's) first reach `goal`; NaN if never. */
const timeTo = (points, goal) =>
  logLogCrossing(
    points.map((q) => [q.seconds, q.truth]),
    goal,
  ) ?? NaN;

/** The meter's relMSE at tracing time `t`, on the log-log polyline through its points. */
const truthAt = (points, t) =>
  logLogInterp(
    points.map((q) => [q.seconds, q.truth]),
    t,
  ) ?? NaN;

async function run(scene, seed, adaptive) {
  const [w, h] = SIZES[scene];
  const page = await browser.newPage({ viewport: { width: 1600, height: 900 } });
  await page.goto(
    `${url}?scene=${scene}&width=${w}&height=${h}&seed=${seed}&spp=1000000&workers=${workers}&adaptive=${adaptive ? 1 : 0}`,
  );
  await page.waitForFunction(() => window.__pathwise?.controller?.stats().spp >= 1, null, {
    timeout: 120_000,
  });
  await page.waitForTimeout(seconds * 1000);
  const r = await page.evaluate(() => {
    const p = window.__pathwise;
    return {
      adaptive: p.controller.adaptive,
      note: p.errorMeter.note,
      points: p.errorMeter.points.map((q) => ({ seconds: q.seconds, spp: q.spp, truth: q.truth })),
    };
  });
  await page.close();
  if (r.adaptive !== adaptive) throw new Error(`${scene}: adaptive is ${r.adaptive}`);
  if (r.note) throw new Error(`${scene}: no true error (${r.note})`);
  const last = r.points[r.points.length - 1];
  return { time: timeTo(r.points, target), last, points: r.points };
}

const rows = [];
for (const scene of scenes) {
  for (const seed of seeds) {
    const got = {};
    // Interleaved, the order alternating by seed, so that load from elsewhere hits both.
    const order = seed % 2 ? [true, false] : [false, true];
    for (const adaptive of order) got[adaptive] = await run(scene, seed, adaptive);
    const t = Math.min(got.false.last.seconds, got.true.last.seconds);
    const equalTime = truthAt(got.false.points, t) / truthAt(got.true.points, t);
    delete got.false.points;
    delete got.true.points;
    const row = {
      scene,
      seed,
      uniform: got.false,
      adaptive: got.true,
      ratio: got.false.time / got.true.time,
      equalTime,
    };
    rows.push(row);
    const f = (x) => (Number.isFinite(x) ? x.toFixed(2) : '—');
    console.log(
      `${scene} seed ${seed}: to relMSE ${target} uniform ${f(got.false.time)} s, adaptive ${f(got.true.time)} s, ratio ${f(row.ratio)}; relMSE uniform / adaptive at ${t.toFixed(1)} s ${f(equalTime)}; after ${seconds} s: uniform ${got.false.last.truth.toExponential(2)} (${got.false.last.spp} passes), adaptive ${got.true.last.truth.toExponential(2)} (${got.true.last.spp} passes); load ${loadavg()[0].toFixed(2)}`,
    );
  }
}
await browser.close();
await server.close();
console.log(JSON.stringify({ seconds, target, workers, rows: rows.map((r) => ({ ...r })) }));
