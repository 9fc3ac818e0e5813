// `npm run bench:core` (issue 2 §6): raw tracer throughput on cornell
// 128×128, 6 bounces, NEE+MIS — M paths/s and M segments/s with one thread
// and with all threads. Each figure is the median of several renders, each
// in a fresh process, after an unmeasured warm-up render; results go to
// bench/results/core.json.
//
//   npm run bench:core [-- --spp N --reps N --sampler independent|sobol --out FILE]
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { ROOT, machineInfo, median, renderOnce } from './lib.mjs';

const opt = {};
for (let i = 2; i < process.argv.length; i += 2)
  opt[process.argv[i].slice(2)] = process.argv[i + 1];
const spp = Number(opt.spp ?? 32);
const reps = Number(opt.reps ?? 5);
// Left out: the command line's default sampler.
const sampler = opt.sampler;
const outFile = path.resolve(ROOT, opt.out ?? 'bench/results/core.json');
const threadsAll = os.availableParallelism();
const tmpDir = path.join(os.tmpdir(), `pathwise-core-${process.pid}`);
mkdirSync(tmpDir, { recursive: true });

const config = {
  scene: path.join(ROOT, 'scenes/cornell.json'),
  width: 128,
  height: 128,
  bounces: 6,
  spp,
  seed: 1,
  estimator: 'nee-mis',
  sampler,
  out: path.join(tmpDir, 'core.pfm'),
};

const machine = machineInfo();
const results = [];
try {
  for (const threads of [...new Set([1, threadsAll])]) {
    renderOnce({ ...config, threads, spp: 1 }); // warm-up: file cache, CPU clocks
    const runs = [];
    for (let r = 0; r < reps; r++) runs.push(renderOnce({ ...config, threads }));
    const seconds = median(runs.map((r) => r.seconds));
    const { paths, segments } = runs[0];
    const entry = {
      threads,
      reps,
      seconds,
      seconds_all: runs.map((r) => r.seconds),
      cpu_seconds: runs[0].cpu_seconds === null ? null : median(runs.map((r) => r.cpu_seconds)),
      paths,
      segments,
      segments_per_path: segments / paths,
      mpaths_per_s: paths / seconds / 1e6,
      msegments_per_s: segments / seconds / 1e6,
      mpaths_per_s_per_thread: paths / seconds / 1e6 / threads,
      // Throughput per CPU-second (whole process, start-up included): a
      // figure that other load on the machine disturbs much less.
      mpaths_per_cpu_s:
        runs[0].cpu_seconds === null ? null : paths / median(runs.map((r) => r.cpu_seconds)) / 1e6,
    };
    results.push(entry);
    process.stderr.write(
      `cornell 128x128 6 bounces ${spp} spp, ${threads} thread(s): ${entry.mpaths_per_s.toFixed(3)} M paths/s, ${entry.msegments_per_s.toFixed(3)} M segments/s (median of ${reps}: ${entry.seconds_all.map((s) => s.toFixed(3)).join(' ')} s)\n`,
    );
  }
} finally {
  rmSync(tmpDir, { recursive: true, force: true });
}
const single = results[0];
const all = results[results.length - 1];
const report = {
  schema: 'pathwise-bench-core/1',
  command: `npm run bench:core${process.argv.length > 2 ? ' -- ' + process.argv.slice(2).join(' ') : ''}`,
  machine,
  loadavg_end: os.loadavg(),
  config: {
    ...config,
    out: undefined,
    scene: 'scenes/cornell.json',
    sampler: sampler ?? '(command-line default)',
  },
  results,
  summary: {
    single_thread_mpaths_per_s: single.mpaths_per_s,
    single_thread_msegments_per_s: single.msegments_per_s,
    all_threads: all.threads,
    all_threads_mpaths_per_s: all.mpaths_per_s,
    all_threads_msegments_per_s: all.msegments_per_s,
    speedup: all.mpaths_per_s / single.mpaths_per_s,
  },
};
mkdirSync(path.dirname(outFile), { recursive: true });
writeFileSync(outFile, JSON.stringify(report, null, 2) + '\n');
process.stdout.write(JSON.stringify(report.summary) + '\n');
