/**
 * Time to relMSE 1e-2 and 1e-3, raw and denoised (issue 22; BENCHMARKS.md, Denoising):
 * whole `pathwise render` processes (start-up, render and, denoised, the network after
 * the render: `--denoise`), at the reference's size, against the committed Mitsuba 3
 * references (tests/references), relMSE = mean over pixels and channels of
 * (x − ref)² / (ref² + 0.01). Samples per pixel double from 1 (raw up to --max-raw,
 * denoised up to --max-denoised); a cell is the first run at or below the error.
 *   npm run build:cli
 *   node scripts/run-ts.mjs bench/denoise-time.ts [--scenes cornell,mirror,spheres,metal-sky]
 *        [--threads 2] [--max-raw 1024] [--max-denoised 64]
 * Prints a Markdown table. Not a test.
 */
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { decodePfm } from '../src/core/io/pfm.ts';
import { relMse } from './lib.mjs';

const args = process.argv.slice(2);
const flag = (name: string, dflt: string): string => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1]! : dflt;
};
const scenes = flag('scenes', 'cornell,mirror,spheres,metal-sky').split(',');
const threads = flag('threads', '2');
const maxRaw = Number(flag('max-raw', '1024'));
const maxDenoised = Number(flag('max-denoised', '64'));
const tmp = mkdtempSync(join(tmpdir(), 'pathwise-denoise-time-'));
const LIMIT = 1 << 24;

interface Run {
  spp: number;
  seconds: number;
  error: number;
}

function render(scene: string, w: number, h: number, spp: number, denoise: boolean): Run {
  const out = join(tmp, 'x.pfm');
  const t0 = process.hrtime.bigint();
  execFileSync(
    process.execPath,
    [
      'bin/pathwise.js',
      'render',
      `scenes/${scene}.json`,
      ...['--width', String(w), '--height', String(h), '--spp', String(spp)],
      ...['--threads', threads, '--out', out],
      ...(denoise ? ['--denoise'] : []),
    ],
    { stdio: ['ignore', 'ignore', 'inherit'] },
  );
  const seconds = Number(process.hrtime.bigint() - t0) / 1e9;
  const ref = decodePfm(readFileSync(`tests/references/${scene}.pfm`));
  const img = decodePfm(readFileSync(out), { maxWidth: LIMIT, maxHeight: LIMIT });
  return { spp, seconds, error: relMse(img.rgb, ref.rgb) };
}

function series(scene: string, w: number, h: number, max: number, denoise: boolean): Run[] {
  const runs: Run[] = [];
  for (let spp = 1; spp <= max; spp *= 2) {
    const r = render(scene, w, h, spp, denoise);
    runs.push(r);
    if (r.error <= 1e-3) break;
  }
  return runs;
}

function cell(runs: Run[], target: number, max: number): string {
  const hit = runs.find((r) => r.error <= target);
  if (hit) return `${hit.seconds.toFixed(1)} s (${hit.spp} spp, ${hit.error.toExponential(1)})`;
  const last = runs[runs.length - 1]!;
  return `not reached in ${max} spp (${last.error.toExponential(1)}, ${last.seconds.toFixed(1)} s)`;
}

console.log('| scene | raw to 1e-2 | denoised to 1e-2 | raw to 1e-3 | denoised to 1e-3 |');
console.log('| --- | --- | --- | --- | --- |');
for (const scene of scenes) {
  const ref = decodePfm(readFileSync(`tests/references/${scene}.pfm`));
  const { width: w, height: h } = ref;
  const raw = series(scene, w, h, maxRaw, false);
  const den = series(scene, w, h, maxDenoised, true);
  console.log(
    `| ${scene} ${w}×${h} | ${cell(raw, 1e-2, maxRaw)} | ${cell(den, 1e-2, maxDenoised)} | ${cell(raw, 1e-3, maxRaw)} | ${cell(den, 1e-3, maxDenoised)} |`,
  );
}
rmSync(tmp, { recursive: true, force: true });
