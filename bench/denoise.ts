/**
 * Denoiser speed: pathwise's TypeScript U-Net (src/core/denoise) against native OIDN 2.5
 * (pyoidn, bench/oidn-threads.py, with the same thread counts) on the same colour, albedo and normal images, in one run:
 * each side gets one warm-up, then REPEAT timed runs (median reported). Ours runs in-process
 * (1 thread, one tile as OIDN) and across worker_threads (src/cli/denoise-pool.ts: the
 * threads share each tile in bands of rows). With --tile-pixels N, more than one thread
 * also runs the image cut into OIDN-style overlapped tiles of at most N pixels, for
 * comparison.
 *   npm run build:cli   (for dist/cli/denoise-worker.js)
 *   (from the repository root) node scripts/run-ts.mjs bench/denoise.ts COLOR.pfm ALBEDO.pfm NORMAL.pfm [--repeat 3]
 *        [--threads 1,2] [--tile-pixels 200000] [--python PY]
 */
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { denoiseInWorkers } from '../src/cli/denoise-pool.ts';
import { denoise } from '../src/core/denoise/denoise.ts';
import { parseTza } from '../src/core/denoise/tza.ts';
import { unetWeights } from '../src/core/denoise/unet-weights.ts';
import { decodePfm } from '../src/core/io/pfm.ts';

const args = process.argv.slice(2);
const flag = (name: string, dflt: string): string => {
  const i = args.indexOf(name);
  return i >= 0 ? args.splice(i, 2)[1]! : dflt;
};
const repeat = Number(flag('--repeat', '3'));
const threads = flag('--threads', '1,2').split(',').map(Number);
const tilePixels = Number(flag('--tile-pixels', '0'));
const python = flag('--python', '/work/research/issue22/.venv/bin/python');
const [colorPath, albedoPath, normalPath] = args;
if (!colorPath || !albedoPath || !normalPath)
  throw new Error('usage: bench/denoise.ts COLOR ALBEDO NORMAL');
const read = (p: string) => decodePfm(readFileSync(p), { maxWidth: 16384, maxHeight: 16384 });
const c = read(colorPath);
const images = {
  width: c.width,
  height: c.height,
  color: c.rgb,
  albedo: read(albedoPath).rgb,
  normal: read(normalPath).rgb,
};
const tza = readFileSync('vendor/oidn-weights/rt_hdr_alb_nrm.tza');
const weights = unetWeights(parseTza(tza));
const median = (xs: number[]): number => [...xs].sort((a, b) => a - b)[xs.length >> 1]!;

/** Median wall seconds and process CPU seconds (all threads, workers included). */
async function time(run: () => unknown): Promise<{ seconds: number; cpu: number }> {
  await run(); // warm-up
  const ts: number[] = [];
  const cs: number[] = [];
  for (let i = 0; i < repeat; i++) {
    const t = performance.now();
    const c = process.cpuUsage();
    await run();
    ts.push((performance.now() - t) / 1000);
    const d = process.cpuUsage(c);
    cs.push((d.user + d.system) / 1e6);
  }
  return { seconds: median(ts), cpu: median(cs) };
}

// Native OIDN with the same thread counts as ours (bench/oidn-threads.py sets numThreads).
const rows: Record<string, number | string>[] = [];
for (const t of threads) {
  const args = [
    'bench/oidn-threads.py',
    colorPath,
    albedoPath,
    normalPath,
    String(t),
    String(repeat),
  ];
  const r = JSON.parse(execFileSync(python, args, { encoding: 'utf8' })) as {
    seconds_median: number;
    cpu_seconds_median: number;
  };
  rows.push({
    what: `native OIDN 2.5.1 (pyoidn)`,
    threads: t,
    seconds: r.seconds_median,
    cpu: r.cpu_seconds_median,
  });
}
rows.push({
  what: 'pathwise, in-process, 1 tile',
  threads: 1,
  ...(await time(() => denoise(images, weights))),
});
const workerUrl = pathToFileURL('dist/cli/denoise-worker.js');
for (const t of threads) {
  rows.push({
    what: `pathwise, worker threads, bands of 1 tile`,
    threads: t,
    ...(await time(() => denoiseInWorkers(images, tza, { threads: t, workerUrl }))),
  });
  if (tilePixels > 0 && t > 1)
    rows.push({
      what: `pathwise, worker threads, tiles of ${tilePixels} px`,
      threads: t,
      ...(await time(() =>
        denoiseInWorkers(images, tza, {
          threads: t,
          workerUrl,
          tiles: { maxTilePixels: tilePixels, minTileSide: 0 },
        }),
      )),
    });
}
// Speed relative to native OIDN with as many threads: native seconds / our seconds, by wall
// time and by process CPU time (the machine may be shared: CPU time is what load disturbs least).
const nativeAt = (t: number) =>
  rows.find((r) => r.threads === t && String(r.what).startsWith('native'))!;
for (const r of rows) {
  const n = nativeAt(r.threads as number);
  r['speed (wall)'] = ((n.seconds as number) / (r.seconds as number)).toFixed(3);
  r['speed (cpu)'] = ((n.cpu as number) / (r.cpu as number)).toFixed(3);
}
console.log(
  `${c.width}×${c.height}, colour + albedo + normal, median of ${repeat} after a warm-up`,
);
console.table(rows);
