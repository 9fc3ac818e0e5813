/**
 * In-process tracer throughput, one thread, no workers: the harness for
 * profiling (`node --cpu-prof`, `--trace-deopt`) and for quick A/B runs of
 * the hot loop. Renders `scene` at W×H once to warm up, then `reps` times,
 * and prints the median M paths/s.
 *   node scripts/run-ts.mjs bench/inproc.ts SCENE.json [W H SPP BOUNCES REPS SAMPLER ACCEL]
 * (SAMPLER: independent | sobol, default the tracer's; ACCEL: bvh | list, default by size).
 * SCENE `@million` or `@bunny`: the mesh scenes of bench/mesh-scenes.ts (the Cornell box
 * with a generated 1,000,000-triangle mesh or the Stanford bunny in place of its boxes).
 */
import { Film, PathTracer, RenderStats, compileScene } from '../src/core/index.ts';
import type { SamplerKind } from '../src/core/index.ts';
import { loadBenchScene } from './mesh-scenes.ts';

const [file, w = '128', h = '128', sppArg = '8', bouncesArg = '6', repsArg = '5', sampler, accel] =
  process.argv.slice(2);
const width = Number(w);
const height = Number(h);
const spp = Number(sppArg);
const reps = Number(repsArg);
const t0 = performance.now();
const scene = loadBenchScene(file);
const t1 = performance.now();
const compiled = compileScene(scene, {
  bvh: accel === 'bvh' ? true : accel === 'list' ? false : undefined,
});
const t2 = performance.now();
const tracer = new PathTracer(compiled, {
  width,
  height,
  maxBounces: Number(bouncesArg),
  seed: 1,
  sampler: sampler as SamplerKind | undefined,
  camera: scene.camera,
});
let sink = 0;
/** FNV-1a over the film's bytes: equal digests mean bit-identical images (before/after checks). */
let digest = 0;
const rates: number[] = [];
const cpuRates: number[] = [];
const segCpuRates: number[] = [];
for (let r = 0; r <= reps; r++) {
  const film = new Film(width, height);
  const stats = new RenderStats();
  const s = performance.now();
  const c = process.cpuUsage();
  tracer.renderRows(film, 0, height, 0, spp, stats);
  const sec = (performance.now() - s) / 1000;
  const cu = process.cpuUsage(c);
  const cpuSec = (cu.user + cu.system) / 1e6;
  sink += film.sums[(width * (height >> 1) + (width >> 1)) * 4];
  if (r === 0) digest = fnv1a(new Uint8Array(film.buffer));
  if (r > 0) {
    rates.push(stats.paths / sec / 1e6);
    cpuRates.push(stats.paths / cpuSec / 1e6);
    segCpuRates.push(stats.segments / cpuSec / 1e6);
  } else
    process.stderr.write(
      `first render ${sec.toFixed(3)} s, ${(stats.segments / stats.paths).toFixed(3)} segments/path\n`,
    );
}
rates.sort((a, b) => a - b);
cpuRates.sort((a, b) => a - b);
segCpuRates.sort((a, b) => a - b);
process.stdout.write(
  JSON.stringify({
    parse_ms: t1 - t0,
    compile_ms: t2 - t1,
    mpaths_per_s: rates[rates.length >> 1],
    mpaths_per_cpu_s: cpuRates[cpuRates.length >> 1],
    msegments_per_cpu_s: segCpuRates[segCpuRates.length >> 1],
    all: rates.map((r) => +r.toFixed(3)),
    sink,
    film_fnv1a: digest.toString(16),
  }) + '\n',
);

function fnv1a(bytes: Uint8Array): number {
  let h = 0x811c9dc5;
  for (let i = 0; i < bytes.length; i++) h = Math.imul(h ^ bytes[i], 0x01000193);
  return h >>> 0;
}
