// `npm run bench:core` (issues 2 and 10): raw tracer throughput against the
// native C++ anchor (../shared/anchors/native), measured side by side in the
// same run on the same scenes:
//   - cornell 128×128, 6 bounces, NEE+MIS, one thread; all threads at
//     512×512 (the same work per thread);
//   - a field of 10,000 non-overlapping spheres under an area light
//     (bench/scenes.mjs), likewise;
//   - whole process (start to exit, parsing, BVH and image file included),
//     1 spp of the 10,000 spheres at 128×128, with 2 and with all threads;
//   - pathwise's start-up: compile time, time until its workers are ready to
//     trace, the shared scene's bytes and each worker's heap.
// pathwise and native runs alternate, each figure is the median of the
// repetitions, and every ratio is pathwise / native from the same run.
// pathwise's render time is the command line's `seconds` (workers started
// to all finished, start-up and JIT warm-up included); the anchor's is its
// own `seconds` (threads started to joined, no parsing).
//
// The anchor is used when it is built: --native PATH, $PATHWISE_NATIVE, or
// /tmp/pathwise-native-anchor/pt; if that is missing and
// ../shared/anchors/native/build.sh exists, it is built first. Without it
// the pathwise figures are reported alone.
//
//   npm run bench:core [-- --reps N --threads N --sampler S --out FILE --native PATH --quick]
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { ROOT, machineInfo, median, renderOnce } from './lib.mjs';
import { findNative, nativeOnce } from './native.mjs';
import { writeSpheresField } from './scenes.mjs';

const opt = {};
for (let i = 2; i < process.argv.length; i++) {
  const name = process.argv[i].slice(2);
  if (name === 'quick') opt.quick = true;
  else opt[name] = process.argv[++i];
}
const quick = !!opt.quick;
const reps = Number(opt.reps ?? (quick ? 1 : 5));
const threadsAll = Number(opt.threads ?? os.availableParallelism());
// Left out: the command line's default sampler.
const sampler = opt.sampler;
const outFile = path.resolve(ROOT, opt.out ?? 'bench/results/core.json');
const tmpDir = path.join(os.tmpdir(), `pathwise-core-${process.pid}`);
mkdirSync(tmpDir, { recursive: true });

const native = findNative(opt.native);
if (!native) process.stderr.write('no native anchor: pathwise figures only\n');
/** One render by the anchor, into the run's temporary folder. */
const nativeRun = (o) => nativeOnce(native, { ...o, out: path.join(tmpDir, 'native.pfm') });

const spheresFile = writeSpheresField(path.join(tmpDir, 'spheres-10k.json'), 10000);
const cases = [
  { name: 'cornell', scene: path.join(ROOT, 'scenes/cornell.json'), spp: quick ? 4 : 32 },
  { name: 'spheres-10k', scene: spheresFile, spp: quick ? 2 : 16 },
];

const machine = machineInfo();
const throughput = [];
const pw = (o) =>
  renderOnce({ ...o, seed: 1, estimator: 'nee-mis', sampler, out: path.join(tmpDir, 'pw.pfm') });

function summarise(runs) {
  const seconds = median(runs.map((r) => r.seconds));
  const { paths, segments } = runs[0];
  return {
    seconds,
    seconds_all: runs.map((r) => r.seconds),
    paths,
    segments,
    mpaths_per_s: paths / seconds / 1e6,
    msegments_per_s: segments / seconds / 1e6,
  };
}

try {
  for (const c of cases) {
    for (const threads of [...new Set([1, threadsAll])]) {
      // One thread: 128×128; all threads: 512×512 when there are more than
      // 4 (the same work per thread, so start-up weighs alike).
      const side = threads > 4 ? 512 : 128;
      const o = { scene: c.scene, width: side, height: side, spp: c.spp, threads, bounces: 6 };
      pw({ ...o, spp: 1 }); // warm-up: file cache, CPU clocks
      if (native) nativeRun({ ...o, spp: 1 });
      const pwRuns = [];
      const nativeRuns = [];
      for (let r = 0; r < reps; r++) {
        pwRuns.push(pw(o));
        if (native) nativeRuns.push(nativeRun(o));
      }
      const entry = {
        case: c.name,
        width: side,
        height: side,
        spp: c.spp,
        threads,
        reps,
        pathwise: {
          ...summarise(pwRuns),
          cpu_seconds:
            pwRuns[0].cpu_seconds === null ? null : median(pwRuns.map((r) => r.cpu_seconds)),
        },
        native: native ? summarise(nativeRuns) : null,
      };
      entry.ratio = native ? entry.pathwise.mpaths_per_s / entry.native.mpaths_per_s : null;
      throughput.push(entry);
      process.stderr.write(
        `${c.name} ${side}x${side} ${c.spp} spp, ${threads} thread(s): pathwise ${entry.pathwise.mpaths_per_s.toFixed(3)} M paths/s` +
          (native
            ? `, native ${entry.native.mpaths_per_s.toFixed(3)}, ratio ${entry.ratio.toFixed(3)}`
            : '') +
          '\n',
      );
    }
  }

  // Whole process, 1 spp of the 10,000 spheres: spawn to exit, everything in.
  const whole = [];
  for (const threads of [...new Set([2, threadsAll])]) {
    const o = { scene: spheresFile, width: 128, height: 128, spp: 1, threads, bounces: 6 };
    pw(o);
    if (native) nativeRun(o);
    const pwRuns = [];
    const nativeRuns = [];
    for (let r = 0; r < Math.max(reps, 3); r++) {
      pwRuns.push(pw(o));
      if (native) nativeRuns.push(nativeRun(o));
    }
    const entry = {
      threads,
      pathwise_process_seconds: median(pwRuns.map((r) => r.process_seconds)),
      pathwise_compile_seconds: median(pwRuns.map((r) => r.compile_seconds)),
      pathwise_first_ready_seconds: median(pwRuns.map((r) => r.first_ready_seconds)),
      pathwise_last_ready_seconds: median(pwRuns.map((r) => r.last_ready_seconds)),
      pathwise_render_seconds: median(pwRuns.map((r) => r.seconds)),
      pathwise_scene_bytes: pwRuns[0].scene_bytes,
      pathwise_worker_heap_mb: median(pwRuns.map((r) => r.worker_heap_mb_median)),
      native_process_seconds: native ? median(nativeRuns.map((r) => r.process_seconds)) : null,
    };
    entry.time_ratio = native
      ? entry.pathwise_process_seconds / entry.native_process_seconds
      : null;
    whole.push(entry);
    process.stderr.write(
      `10k spheres, 1 spp, whole process, ${threads} threads: pathwise ${entry.pathwise_process_seconds.toFixed(3)} s` +
        (native
          ? `, native ${entry.native_process_seconds.toFixed(3)} s, ${entry.time_ratio.toFixed(2)}×`
          : '') +
        ` (compile ${entry.pathwise_compile_seconds.toFixed(3)} s, workers ready ${entry.pathwise_first_ready_seconds.toFixed(3)}–${entry.pathwise_last_ready_seconds.toFixed(3)} s, worker heap ${entry.pathwise_worker_heap_mb.toFixed(1)} MB)\n`,
    );
  }

  const report = {
    schema: 'pathwise-bench-core/2',
    command: `npm run bench:core${process.argv.length > 2 ? ' -- ' + process.argv.slice(2).join(' ') : ''}`,
    machine,
    loadavg_end: os.loadavg(),
    native: native
      ? {
          path: native,
          note: 'the anchor of ../shared/anchors/native, built with its build.sh (-O3 -march=native, double precision)',
        }
      : null,
    config: { sampler: sampler ?? '(command-line default)', bounces: 6, estimator: 'nee-mis' },
    throughput,
    whole_process: whole,
  };
  mkdirSync(path.dirname(outFile), { recursive: true });
  writeFileSync(outFile, JSON.stringify(report, null, 2) + '\n');
  process.stdout.write(
    JSON.stringify(
      throughput.map((t) => ({
        case: t.case,
        threads: t.threads,
        pathwise: t.pathwise.mpaths_per_s,
        native: t.native?.mpaths_per_s ?? null,
        ratio: t.ratio,
      })),
    ) + '\n',
  );
} finally {
  rmSync(tmpDir, { recursive: true, force: true });
}
