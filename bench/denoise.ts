/**
 * Denoiser speed: pathwise's TypeScript U-Net (src/core/denoise) against native OIDN 2.5
 * (pyoidn, through oidn_ref.py) on the same colour, albedo and normal images, in one run:
 * each side gets one warm-up, then REPEAT timed runs (median reported). Ours runs in-process
 * (1 thread, one tile as OIDN) and across worker_threads (src/cli/denoise-pool.ts; with
 * more than one thread the image is cut into OIDN-style overlapped tiles of at most
 * --tile-pixels, so tiles can run in parallel).
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
const tilePixels = Number(flag('--tile-pixels', '200000'));
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

async function time(run: () => unknown): Promise<number> {
  await run(); // warm-up
  const ts: number[] = [];
  for (let i = 0; i < repeat; i++) {
    const t = performance.now();
    await run();
    ts.push((performance.now() - t) / 1000);
  }
  return median(ts);
}

const native = JSON.parse(
  execFileSync(
    python,
    [
      '/work/shared/tools/oidn_ref.py',
      colorPath,
      '--albedo',
      albedoPath,
      '--normal',
      normalPath,
      '--out',
      '/tmp/pathwise-bench-denoise-oidn.pfm',
      '--repeat',
      String(repeat),
    ],
    { encoding: 'utf8' },
  ),
) as { seconds_median: number };
const rows: Record<string, number | string>[] = [
  { what: 'native OIDN 2.5.1 (pyoidn)', seconds: native.seconds_median },
];
rows.push({
  what: 'pathwise, in-process, 1 thread, 1 tile',
  seconds: await time(() => denoise(images, weights)),
});
const workerUrl = pathToFileURL('dist/cli/denoise-worker.js');
for (const t of threads) {
  const tiles = t > 1 ? { maxTilePixels: tilePixels, minTileSide: 0 } : {};
  rows.push({
    what: `pathwise, ${t} worker thread(s)`,
    seconds: await time(() => denoiseInWorkers(images, tza, { threads: t, workerUrl, tiles })),
  });
}
for (const r of rows) r.ratio = (native.seconds_median / (r.seconds as number)).toFixed(3);
console.log(
  `${c.width}×${c.height}, colour + albedo + normal, median of ${repeat} after a warm-up`,
);
console.table(rows);
