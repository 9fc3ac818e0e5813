// Time to relMSE 1e-2 and 1e-3 with and without adaptive sampling (issue 23, deliverable
// 2; src/core/film/adaptive.ts) on the canonical scenes: whole processes of `pathwise
// render` at 128×128 (the size of the Mitsuba 3 references in tests/references), passes
// doubling from 32, each render's relMSE (lib.mjs) against the reference. The time to an
// error is the log-log interpolation of error against process seconds between the two
// renders around it (extrapolated as 1/time past the last render); the ratio is uniform
// over adaptive, measured in this one run, per seed and as the median over seeds.
// Prints a Markdown table.
//
//   npm run build:cli
//   node bench/adaptive-time.mjs [--scenes cornell,mirror,spheres,metal-sky]
//        [--threads 2] [--max-spp 4096] [--seeds 1,2]
import { median, readPfm, relMse, renderOnce, ROOT, timeToError } from './lib.mjs';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';

const argv = process.argv.slice(2);
const flag = (name, dflt) => {
  const i = argv.indexOf(`--${name}`);
  return i >= 0 ? argv[i + 1] : dflt;
};
const scenes = flag('scenes', 'cornell,mirror,spheres,metal-sky').split(',');
const threads = Number(flag('threads', '2'));
const maxSpp = Number(flag('max-spp', '4096'));
const seeds = flag('seeds', '1,2').split(',').map(Number);
const TARGETS = [1e-2, 1e-3];
const tmp = mkdtempSync(path.join(tmpdir(), 'pathwise-adaptive-'));

/** Renders at passes 32, 64, … until the error is below the last target (or maxSpp). */
function sweep(scene, ref, adaptive, seed) {
  const points = [];
  for (let spp = 32; spp <= maxSpp; spp *= 2) {
    const out = path.join(tmp, 'x.pfm');
    const r = renderOnce({
      scene: path.join(ROOT, 'scenes', `${scene}.json`),
      width: ref.width,
      height: ref.height,
      spp,
      threads,
      seed,
      adaptive,
      out,
    });
    const error = relMse(readPfm(out).rgb, ref.rgb);
    points.push({ spp, seconds: r.process_seconds, error, paths: r.paths });
    process.stderr.write(
      `  ${scene} ${adaptive ? 'adaptive' : 'uniform '} seed ${seed} passes ${spp}: ` +
        `${r.process_seconds.toFixed(2)} s, ${(r.paths / (ref.width * ref.height)).toFixed(0)} ` +
        `samples/pixel, relMSE ${error.toExponential(2)}\n`,
    );
    if (error < TARGETS.at(-1) && points.length >= 2) break;
  }
  return points;
}

const rows = [];
for (const scene of scenes) {
  const ref = readPfm(path.join(ROOT, 'tests/references', `${scene}.pfm`));
  const ratios = TARGETS.map(() => []);
  const cells = { uniform: TARGETS.map(() => []), adaptive: TARGETS.map(() => []) };
  for (const seed of seeds) {
    const u = sweep(scene, ref, false, seed);
    const a = sweep(scene, ref, true, seed);
    TARGETS.forEach((t, i) => {
      const tu = timeToError(u, t);
      const ta = timeToError(a, t);
      cells.uniform[i].push(tu);
      cells.adaptive[i].push(ta);
      ratios[i].push(tu.seconds / ta.seconds);
    });
  }
  const show = (xs) =>
    xs.map((x) => `${x.extrapolated ? '≈ ' : ''}${x.seconds.toFixed(2)} s`).join(', ');
  rows.push(
    `| ${scene} | ${TARGETS.map(
      (_, i) =>
        `${show(cells.uniform[i])} | ${show(cells.adaptive[i])} | ` +
        `${ratios[i].map((r) => r.toFixed(2)).join(', ')} (median ${median(ratios[i]).toFixed(2)})`,
    ).join(' | ')} |`,
  );
}
rmSync(tmp, { recursive: true, force: true });
process.stdout.write(
  `128×128, ${threads} threads, whole processes, seeds ${seeds.join(', ')}; time = log-log ` +
    `interpolation of relMSE against process seconds (≈: extrapolated from the last ` +
    `render as error ∝ 1/time)\n\n` +
    `| scene | uniform to 1e-2 | adaptive to 1e-2 | ratio | uniform to 1e-3 | adaptive to 1e-3 | ratio |\n` +
    `|---|---|---|---|---|---|---|\n` +
    rows.join('\n') +
    '\n',
);
