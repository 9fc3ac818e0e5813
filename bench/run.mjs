// `npm run bench`: speed against error (issue 5). Renders each canonical
// scene at spp = 1, 2, 4 … with a fixed seed, one process per render, and
// measures wall time and error against the Mitsuba references; then thread
// scaling, the estimator and sampler studies, the time to reach a target
// error, and writes bench/results/bench.json, SVG plots and BENCHMARKS.md.
//
//   npm run bench                      full run (~15–30 min on 2 cores)
//   npm run bench -- --quick           smoke run, < 2 min, into bench/results/quick/
//   node bench/run.mjs --only scaling --threads-max 16 --out-dir DIR
//                                      thread scaling only (e.g. on a 16-core machine)
//
// Options: --quick, --out-dir DIR, --md FILE, --max-spp N, --reps N,
// --threads-max N, --scaling-spp N, --scaling-size WxH, --only errors|scaling,
// --from FILE (only re-write the report and plots of an existing bench.json),
// --scenes a,b, --device-results FILE[,FILE] (scaling measured elsewhere, to
// include), --device-processes FILE (output of bench/processes.mjs).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  ROOT,
  blockMare,
  color,
  logLogCrossing,
  logLogFit,
  logLogInterp,
  machineInfo,
  median,
  plotSvg,
  readPfm,
  relMse,
  renderOnce,
} from './lib.mjs';

// ------------------------------------------------------------------ options

function parseArgs(argv) {
  const o = {};
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (!a.startsWith('--')) throw new Error(`unexpected argument ${a}`);
    const name = a.slice(2);
    if (name === 'quick') o.quick = true;
    else o[name] = argv[++i];
  }
  return o;
}
/** BENCHMARKS.md's marker: the hand-written sections after it survive a re-run. */
const HAND_WRITTEN =
  '<!-- Measured by other scripts, written by hand: bench/run.mjs keeps what follows. -->';

const opt = parseArgs(process.argv.slice(2));
const quick = !!opt.quick;
const outDir = path.resolve(
  ROOT,
  opt['out-dir'] ?? (quick ? 'bench/results/quick' : 'bench/results'),
);
const mdPath = path.resolve(
  ROOT,
  opt.md ?? (quick ? path.join(outDir, 'BENCHMARKS.md') : 'BENCHMARKS.md'),
);
const maxSpp = Number(opt['max-spp'] ?? (quick ? 16 : 1024));
const fixedReps = opt.reps !== undefined ? Number(opt.reps) : null;
const threadsAll = os.availableParallelism();
const threadsMax = Number(opt['threads-max'] ?? threadsAll);
const scalingSpp = Number(opt['scaling-spp'] ?? (quick ? 4 : 64));
const [scalingW, scalingH] = (opt['scaling-size'] ?? '128x128').split('x').map(Number);
const only = opt.only ?? null;
// Figures measured on another machine (see bench/results/device/README.md)
// are included in the full report by default.
const deviceFile = (name) => {
  const f = path.join(ROOT, 'bench/results/device', name);
  return !quick && existsSync(f) ? path.relative(ROOT, f) : undefined;
};
opt['device-results'] ??=
  [deviceFile('scaling-128.json'), deviceFile('scaling-256.json'), deviceFile('scaling-512.json')]
    .filter(Boolean)
    .join(',') || undefined;
opt['device-processes'] ??= deviceFile('processes.json');
opt['device-full'] ??= deviceFile('full/bench.json');
const SEED = 1;
// The issue's target; a quick run cannot reach it, so it exercises the same
// code path with a looser one.
const TARGET = quick ? 2e-2 : 1e-3;

const references = JSON.parse(
  readFileSync(path.join(ROOT, 'tests/references/references.json'), 'utf8'),
).entries;
const SCENES = (opt.scenes ?? 'cornell,mirror,spheres').split(',').map((name) => {
  const ref = references[name];
  return {
    name,
    file: path.join(ROOT, 'scenes', `${name}.json`),
    width: ref.width,
    height: ref.height,
    maxBounces: ref.maxBounces,
    reference: readPfm(path.join(ROOT, 'tests/references', ref.file)),
  };
});
/** The configurations of the estimator and sampler studies. */
const CONFIGS = [
  { id: 'nee-mis/independent', estimator: 'nee-mis', sampler: 'independent' },
  { id: 'nee-mis/sobol', estimator: 'nee-mis', sampler: 'sobol' },
  { id: 'bsdf/independent', estimator: 'bsdf', sampler: 'independent' },
];

mkdirSync(outDir, { recursive: true });
const tmpDir = path.join(os.tmpdir(), `pathwise-bench-${process.pid}`);
mkdirSync(tmpDir, { recursive: true });
const tmpPfm = path.join(tmpDir, 'out.pfm');
const log = (s) => process.stderr.write(s + '\n');

/**
 * Repetitions of one point: several where a render is cheap (timing noise
 * dominates), one where it is long (a 30 s render is stable to ~1%).
 */
function repsFor(expectedSeconds) {
  if (fixedReps !== null) return fixedReps;
  if (quick) return 1;
  return expectedSeconds < 1 ? 5 : expectedSeconds < 4 ? 3 : 1;
}

/** Renders one point `reps` times (each in its own process) and scores the last image. */
function measure(scene, cfg, spp, threads, reps, width = scene.width, height = scene.height) {
  const runs = [];
  for (let r = 0; r < reps; r++) {
    runs.push(
      renderOnce({
        scene: scene.file,
        width,
        height,
        spp,
        threads,
        seed: SEED,
        estimator: cfg.estimator,
        sampler: cfg.sampler,
        bounces: scene.maxBounces,
        out: tmpPfm,
      }),
    );
  }
  const seconds = median(runs.map((r) => r.seconds));
  const last = runs[runs.length - 1];
  const point = {
    spp,
    threads: last.threads,
    reps,
    seconds,
    seconds_all: runs.map((r) => r.seconds),
    process_seconds: median(runs.map((r) => r.process_seconds)),
    cpu_seconds: runs[0].cpu_seconds === null ? null : median(runs.map((r) => r.cpu_seconds)),
    paths: last.paths,
    segments: last.segments,
    mpaths_per_s: last.paths / seconds / 1e6,
    msegments_per_s: last.segments / seconds / 1e6,
  };
  if (width === scene.width && height === scene.height) {
    // Every render of a point is bit-identical (fixed seed), so one image scores all.
    const img = readPfm(tmpPfm);
    point.relmse = relMse(img.rgb, scene.reference.rgb);
    point.block_mare_8 = blockMare(img.rgb, scene.reference.rgb, width, height, 8);
  }
  return point;
}

function sppList(max) {
  const list = [];
  for (let s = 1; s <= max; s *= 2) list.push(s);
  return list;
}

/** Unmeasured renders so that file caches and CPU clocks are settled before timing. */
function warmUp(scene, cfg) {
  measure(scene, cfg, 1, threadsAll, 1);
}

// ------------------------------------------------------------- error series

function runSeries() {
  const series = [];
  for (const scene of SCENES) {
    const perConfig = CONFIGS.map((cfg) => {
      warmUp(scene, cfg);
      return { cfg, points: [], expected: 0.05 };
    });
    // Configurations are interleaved spp by spp, so that a slow spell of
    // the machine (other processes) hits all of them alike and their
    // time ratios stay fair.
    for (const spp of sppList(maxSpp)) {
      for (const run of perConfig) {
        const p = measure(scene, run.cfg, spp, threadsAll, repsFor(run.expected));
        run.points.push(p);
        run.expected = p.seconds * 2;
        log(
          `${scene.name.padEnd(8)} ${run.cfg.id.padEnd(20)} spp ${String(spp).padStart(5)}  ${p.seconds.toFixed(3)} s  ${p.msegments_per_s.toFixed(2)} Mseg/s  relMSE ${p.relmse.toExponential(3)}  blockMARE ${p.block_mare_8.toExponential(3)}`,
        );
      }
    }
    for (const { cfg, points } of perConfig) {
      const fitPoints = points.filter((p) => p.spp >= (points.length >= 6 ? 4 : 1));
      const fit = logLogFit(fitPoints.map((p) => [p.spp, p.relmse]));
      const fitTime = logLogFit(fitPoints.map((p) => [p.seconds, p.relmse]));
      series.push({
        scene: scene.name,
        width: scene.width,
        height: scene.height,
        max_bounces: scene.maxBounces,
        config: cfg.id,
        estimator: cfg.estimator,
        sampler: cfg.sampler,
        threads: threadsAll,
        seed: SEED,
        slope_relmse_vs_spp: fit.slope,
        slope_fit_min_spp: fitPoints[0].spp,
        slope_relmse_vs_seconds: fitTime.slope,
        points,
      });
    }
  }
  return series;
}

/** Error ratios of config a over config b on one scene, at equal spp and at equal time. */
function compare(series, scene, a, b) {
  const A = series.find((s) => s.scene === scene && s.config === a);
  const B = series.find((s) => s.scene === scene && s.config === b);
  if (!A || !B) return null;
  const bySpp = A.points.map((p) => {
    const q = B.points.find((q) => q.spp === p.spp);
    return [p.spp, p.relmse / q.relmse];
  });
  // Geometric mean over the converged half (spp ≥ 16, or all in a quick run),
  // where a single image's error is no longer dominated by a few fireflies.
  const minSpp = Math.min(16, maxSpp);
  const gm = (xs) => Math.exp(xs.reduce((s, x) => s + Math.log(x), 0) / xs.length);
  const geo = gm(bySpp.filter(([s]) => s >= minSpp).map(([, r]) => r));
  // Equal time, from every point: with relMSE ∝ 1/time, relMSE × seconds is
  // constant along a curve (the inverse efficiency), and its ratio is the
  // error ratio at any equal time. Robust to one slow render.
  const eff = gm(
    A.points
      .filter((p) => p.spp >= minSpp)
      .map((p) => {
        const q = B.points.find((q) => q.spp === p.spp);
        return (p.relmse * p.seconds) / (q.relmse * q.seconds);
      }),
  );
  const cpuKnown = A.points.every((p) => p.cpu_seconds) && B.points.every((p) => p.cpu_seconds);
  const effCpu = cpuKnown
    ? gm(
        A.points
          .filter((p) => p.spp >= minSpp)
          .map((p) => {
            const q = B.points.find((q) => q.spp === p.spp);
            return (p.relmse * p.cpu_seconds) / (q.relmse * q.cpu_seconds);
          }),
      )
    : null;
  // And directly: both error curves interpolated (log-log) at the longest time both reached.
  const tA = A.points.map((p) => [p.seconds, p.relmse]);
  const tB = B.points.map((p) => [p.seconds, p.relmse]);
  const T = Math.min(Math.max(...tA.map((p) => p[0])), Math.max(...tB.map((p) => p[0])));
  const eA = logLogInterp(tA, T);
  const eB = logLogInterp(tB, T);
  return {
    scene,
    a,
    b,
    equal_spp_ratio_at_max_spp: bySpp[bySpp.length - 1][1],
    equal_spp_ratio_geomean: geo,
    equal_spp_ratios: bySpp,
    equal_time_ratio: eff,
    equal_cpu_time_ratio: effCpu,
    equal_time_interp_seconds: T,
    equal_time_interp_relmse_a: eA,
    equal_time_interp_relmse_b: eB,
    equal_time_interp_ratio: eA / eB,
  };
}

/**
 * The estimator and sampler studies and the defaults they choose. The
 * choice uses equal CPU time where GNU time measured it: on a machine
 * shared with other work, wall time of one render can double, CPU time
 * barely moves. Equal wall time is reported beside it.
 */
function analyze(series) {
  const estimator = SCENES.map((s) =>
    compare(series, s.name, 'nee-mis/independent', 'bsdf/independent'),
  ).filter(Boolean);
  const sampler = SCENES.map((s) =>
    compare(series, s.name, 'nee-mis/sobol', 'nee-mis/independent'),
  ).filter(Boolean);
  const gm = (xs) => Math.exp(xs.reduce((a, x) => a + Math.log(x), 0) / xs.length);
  const useCpu = [...estimator, ...sampler].every((c) => c.equal_cpu_time_ratio !== null);
  const key = useCpu ? 'equal_cpu_time_ratio' : 'equal_time_ratio';
  const samplerTime = gm(sampler.map((c) => c[key]));
  const samplerWall = gm(sampler.map((c) => c.equal_time_ratio));
  const samplerSpp = gm(sampler.map((c) => c.equal_spp_ratio_geomean));
  const estimatorTime = gm(estimator.map((c) => c[key]));
  const estimatorWall = gm(estimator.map((c) => c.equal_time_ratio));
  const bestSampler = samplerTime < 1 ? 'sobol' : 'independent';
  const bestEstimator = estimatorTime < 1 ? 'nee-mis' : 'bsdf';
  const basis = useCpu ? 'equal CPU time' : 'equal wall time';
  return {
    comparisons: { estimator, sampler },
    recommendation: {
      sampler: bestSampler,
      estimator: bestEstimator,
      basis,
      sampler_equal_time_geomean: samplerTime,
      sampler_equal_wall_time_geomean: samplerWall,
      sampler_equal_spp_geomean: samplerSpp,
      estimator_equal_time_geomean: estimatorTime,
      estimator_equal_wall_time_geomean: estimatorWall,
      text: `estimator **${bestEstimator}** (NEE+MIS / BSDF-only relMSE at ${basis}, geometric mean over scenes: ${fmt(estimatorTime)}; at equal wall time ${fmt(estimatorWall)}), sampler **${bestSampler}** (sobol / independent relMSE at ${basis}: ${fmt(samplerTime)}; at equal wall time ${fmt(samplerWall)}; at equal spp ${fmt(samplerSpp)}).`,
    },
  };
}

// ------------------------------------------------------------ thread scaling

function runScaling(cfg) {
  const scene = SCENES.find((s) => s.name === 'cornell') ?? SCENES[0];
  const spp = scalingSpp;
  measure(scene, cfg, 1, threadsMax, 1, scalingW, scalingH);
  const points = [];
  for (let t = 1; t <= threadsMax; t++) {
    const p = measure(scene, cfg, spp, t, fixedReps ?? (quick ? 1 : 3), scalingW, scalingH);
    points.push(p);
    log(
      `scaling  ${scene.name} ${scalingW}x${scalingH} ${spp} spp  threads ${t}  ${p.seconds.toFixed(3)} s  ${p.msegments_per_s.toFixed(2)} Mseg/s`,
    );
  }
  const base = points[0].msegments_per_s;
  for (const p of points) {
    p.speedup = p.msegments_per_s / base;
    p.efficiency = p.speedup / p.threads;
  }
  return {
    scene: scene.name,
    width: scalingW,
    height: scalingH,
    spp,
    config: cfg.id,
    machine: machineInfo(),
    points,
  };
}

// ------------------------------------------------------- time to the target

/**
 * Seconds to reach relMSE TARGET on cornell with one thread and with all:
 * the spp needed comes from the error series (the image does not depend
 * on the thread count, so neither does the error); the time at that spp is
 * interpolated (log-log) between renders at the bracketing powers of two.
 */
function timeToTarget(series, cfg) {
  const s = series.find((x) => x.scene === 'cornell' && x.config === cfg.id);
  if (!s) return null;
  const scene = SCENES.find((x) => x.name === 'cornell');
  const sppNeeded = logLogCrossing(
    s.points.map((p) => [p.spp, p.relmse]),
    TARGET,
  );
  const result = { config: cfg.id, target_relmse: TARGET, spp_needed: sppNeeded };
  if (sppNeeded === null) return { ...result, reached: false };
  const lo = Math.max(1, 2 ** Math.floor(Math.log2(sppNeeded)));
  const hi = Math.min(lo * 2, 2 ** Math.ceil(Math.log2(sppNeeded)) || 1);
  const first = s.points.find((p) => p.relmse <= TARGET);
  result.first_power_of_two_spp = first.spp;
  result.first_power_of_two_relmse = first.relmse;
  for (const threads of [...new Set([1, threadsAll])]) {
    const pts = [];
    for (const spp of [...new Set([lo, hi])]) {
      const existing = threads === threadsAll ? s.points.find((p) => p.spp === spp) : null;
      const p = existing ?? measure(scene, cfg, spp, threads, repsFor(3));
      pts.push(p);
    }
    const secs =
      pts.length === 1
        ? (pts[0].seconds * sppNeeded) / pts[0].spp
        : logLogInterp(
            pts.map((p) => [p.spp, p.seconds]),
            sppNeeded,
          );
    result[`threads_${threads}`] = {
      threads,
      seconds: secs,
      renders: pts.map((p) => ({ spp: p.spp, seconds: p.seconds, relmse: p.relmse })),
    };
    log(
      `target   cornell ${cfg.id} relMSE ${TARGET}: ${sppNeeded.toFixed(1)} spp, ${threads} thread(s) ${secs.toFixed(2)} s`,
    );
  }
  return { ...result, reached: true };
}

// ------------------------------------------------------------------- report

const fmt = (v, d = 3) =>
  v === null || v === undefined || !Number.isFinite(v)
    ? '–'
    : Math.abs(v) >= 1e4 || Math.abs(v) < 1e-3
      ? v.toExponential(2)
      : v.toPrecision(d);

function writePlots(result) {
  const files = [];
  const write = (name, svg) => {
    writeFileSync(path.join(outDir, name), svg);
    files.push(name);
  };
  for (const scene of SCENES) {
    const ss = result.series.filter((s) => s.scene === scene.name);
    if (!ss.length) continue;
    // Reference slope −1 (relMSE ∝ 1/N, i.e. RMSE ∝ 1/√N), drawn a factor
    // of two below the lowest curve's end so that it does not hide a curve.
    const ends = ss.map((s) => s.points[s.points.length - 1]);
    const anchor = ends.reduce((a, b) => (b.relmse < a.relmse ? b : a));
    const xs = ss[0].points.map((p) => p.spp);
    const refSpp = xs.map((x) => [x, (0.5 * anchor.relmse * anchor.spp) / x]);
    write(
      `error-spp-${scene.name}.svg`,
      plotSvg({
        title: `${scene.name} ${scene.width}×${scene.height}: relMSE vs spp`,
        xLabel: 'samples per pixel',
        yLabel: 'relMSE',
        series: [
          ...ss.map((s, i) => ({
            name: s.config,
            color: color(i),
            points: s.points.map((p) => [p.spp, p.relmse]),
          })),
          { name: 'slope −1 (1/N)', color: '#777', dash: '5 4', marker: false, points: refSpp },
        ],
      }),
    );
    const allT = ss.flatMap((s) => s.points.map((p) => p.seconds));
    const ts = [Math.min(...allT), Math.max(...allT)];
    const refT = ts.map((t) => [t, (0.5 * anchor.relmse * anchor.seconds) / t]);
    write(
      `error-time-${scene.name}.svg`,
      plotSvg({
        title: `${scene.name}: relMSE vs seconds (${result.machine.cores} threads)`,
        xLabel: 'wall seconds',
        yLabel: 'relMSE',
        series: [
          ...ss.map((s, i) => ({
            name: s.config,
            color: color(i),
            points: s.points.map((p) => [p.seconds, p.relmse]),
          })),
          { name: 'slope −1 (1/t)', color: '#777', dash: '5 4', marker: false, points: refT },
        ],
      }),
    );
  }
  const scalings = [result.scaling, ...(result.device_scaling ?? [])].filter(Boolean);
  scalings.forEach((sc, k) => {
    const base = sc.points[0].msegments_per_s;
    write(
      k === 0 ? 'scaling.svg' : `scaling-device-${k}.svg`,
      plotSvg({
        title: `thread scaling, ${sc.scene} ${sc.width}×${sc.height} (${sc.machine.cores} cores)`,
        xLabel: 'threads',
        yLabel: 'M segments/s',
        logX: false,
        logY: false,
        series: [
          {
            name: 'measured',
            color: color(0),
            points: sc.points.map((p) => [p.threads, p.msegments_per_s]),
          },
          {
            name: 'ideal (linear)',
            color: '#777',
            dash: '5 4',
            marker: false,
            points: sc.points.map((p) => [p.threads, base * p.threads]),
          },
        ],
      }),
    );
  });
  return files;
}

function writeMarkdown(result, deviceFull) {
  const rel = (f) => path.relative(path.dirname(mdPath), path.join(outDir, f)).replace(/\\/g, '/');
  const m = result.machine;
  const L = [];
  L.push('# pathwise benchmarks: speed against error');
  L.push('');
  L.push(
    `Generated by \`${result.command}\` (bench/run.mjs) on ${m.date}. Raw figures: \`${path.relative(ROOT, path.join(outDir, 'bench.json'))}\`. Do not edit by hand; re-run the benchmark.`,
  );
  L.push('');
  L.push(
    `**Machine:** ${m.cpu}, ${m.cores} logical cores, ${m.memory_gib} GiB, ${m.platform}, Node ${m.node}; commit ${m.git_commit ?? 'unknown'}${m.git_dirty ? ' (with uncommitted changes)' : ''}. Load average at start ${m.loadavg_start.map((v) => v.toFixed(2)).join(' / ')}, at end ${result.loadavg_end.map((v) => v.toFixed(2)).join(' / ')}.`,
  );
  L.push('');
  L.push(
    '> Absolute times vary between machines (and with other load on this one); ratios measured within one run — error at equal time, scaling efficiency — hold. Every render is a fresh `node bin/pathwise.js render … --json` process, seed 1; each time is the median of the repetitions listed (more for short renders), after an unmeasured warm-up render. The error of a point is deterministic: the same seed gives a bit-identical image at any thread count.',
  );
  L.push('');
  const maxLoad = Math.max(m.loadavg_start[0], result.loadavg_end[0]);
  if (maxLoad > m.cores * 0.75) {
    L.push(
      `> **This run shared the machine with other work** (1-minute load average up to ${maxLoad.toFixed(1)} on ${m.cores} cores): wall times, and above all the thread scaling measured here, are disturbed. CPU-time ratios (given beside the wall-time ones) and the errors are not; the figures from the idle 16-core machine below are the cleaner timing reference.`,
    );
    L.push('');
  }
  L.push(
    'Error metrics against the Mitsuba 3 references (`tests/references`, 65,536 spp): **relMSE** = mean over pixels and channels of (x − r)² / (r² + 0.01); **blockMARE** = mean over 8×8 blocks and channels of |x̄ − r̄| / (r̄ + 0.01). The references have their own noise (relMSE at 65,536 spp ≈ relMSE(1 spp)/65,536), negligible at the spp measured here.',
  );
  L.push('');
  L.push('## Headline figures');
  L.push('');
  L.push('| figure | value |');
  L.push('|---|---|');
  for (const t of result.time_to_target) {
    if (!t) continue;
    if (!t.reached) {
      L.push(`| cornell, ${t.config}: relMSE ${t.target_relmse} | not reached by ${maxSpp} spp |`);
      continue;
    }
    L.push(
      `| cornell 128×128, 6 bounces, ${t.config}: time to relMSE ${t.target_relmse}, 1 thread | **${fmt(t.threads_1.seconds)} s** (${fmt(t.spp_needed)} spp interpolated; ${t.first_power_of_two_spp} spp gives ${fmt(t.first_power_of_two_relmse)}) |`,
    );
    const all = t[`threads_${m.cores}`];
    if (all && m.cores > 1) {
      L.push(
        `| cornell, ${t.config}: time to relMSE ${t.target_relmse}, ${m.cores} threads | **${fmt(all.seconds)} s** |`,
      );
    }
  }
  for (const c of result.comparisons.estimator) {
    if (c)
      L.push(
        `| ${c.scene}: relMSE of NEE+MIS / BSDF-only at equal time | **${fmt(c.equal_time_ratio)}** wall, **${fmt(c.equal_cpu_time_ratio)}** CPU (wall interpolated at ${fmt(c.equal_time_interp_seconds)} s: ${fmt(c.equal_time_interp_ratio)}; equal spp: ${fmt(c.equal_spp_ratio_geomean)}) |`,
      );
  }
  for (const c of result.comparisons.sampler) {
    if (c)
      L.push(
        `| ${c.scene}: relMSE of sobol / independent (NEE+MIS) at equal spp (geo. mean, spp ≥ 16); at equal time | **${fmt(c.equal_spp_ratio_geomean)}**; **${fmt(c.equal_time_ratio)}** wall, **${fmt(c.equal_cpu_time_ratio)}** CPU (wall interpolated at ${fmt(c.equal_time_interp_seconds)} s: ${fmt(c.equal_time_interp_ratio)}) |`,
      );
  }
  if (result.scaling) {
    for (const p of result.scaling.points.filter((p) => p.threads > 1)) {
      L.push(
        `| scaling efficiency at ${p.threads} threads (this machine) | **${(p.efficiency * 100).toFixed(0)} %** (speed-up ${fmt(p.speedup)}×) |`,
      );
    }
  }
  for (const sc of result.device_scaling ?? []) {
    const last = sc.points[sc.points.length - 1];
    L.push(
      `| scaling efficiency at ${last.threads} threads (${sc.machine.cpu}, ${sc.machine.cores} cores, ${sc.width}×${sc.height}) | **${(last.efficiency * 100).toFixed(0)} %** (speed-up ${fmt(last.speedup)}×) |`,
    );
  }
  for (const s of result.series) {
    L.push(
      `| convergence slope, ${s.scene}, ${s.config} (relMSE vs spp, spp ≥ ${s.slope_fit_min_spp}) | ${fmt(s.slope_relmse_vs_spp)} |`,
    );
  }
  L.push('');
  L.push(`**Defaults chosen from these figures:** ${result.recommendation.text}`);
  L.push('');
  L.push('## Error against samples and against time');
  L.push('');
  L.push(
    `Log-log; the dashed line has slope −1 (relMSE ∝ 1/N, i.e. RMSE ∝ 1/√N). All renders use ${m.cores} threads.`,
  );
  L.push('');
  for (const scene of SCENES) {
    L.push(`### ${scene.name} (${scene.width}×${scene.height}, ${scene.maxBounces} bounces)`);
    L.push('');
    L.push(
      `![relMSE vs spp](${rel(`error-spp-${scene.name}.svg`)}) ![relMSE vs seconds](${rel(`error-time-${scene.name}.svg`)})`,
    );
    L.push('');
    const ss = result.series.filter((s) => s.scene === scene.name);
    L.push('| config | spp | seconds | reps | M paths/s | M segments/s | relMSE | blockMARE |');
    L.push('|---|---:|---:|---:|---:|---:|---:|---:|---:|');
    for (const s of ss) {
      for (const p of s.points) {
        L.push(
          `| ${s.config} | ${p.spp} | ${fmt(p.seconds)} | ${fmt(p.cpu_seconds)} | ${p.reps} | ${fmt(p.mpaths_per_s)} | ${fmt(p.msegments_per_s)} | ${fmt(p.relmse)} | ${fmt(p.block_mare_8)} |`,
        );
      }
    }
    L.push('');
  }
  const scalings = [result.scaling, ...(result.device_scaling ?? [])].filter(Boolean);
  if (scalings.length) {
    L.push('## Thread scaling');
    L.push('');
    scalings.forEach((sc, k) => {
      const mm = sc.machine;
      L.push(
        `### ${mm.cpu}, ${mm.cores} cores, Node ${mm.node} (${mm.date}${k ? ', measured separately with `node bench/run.mjs --only scaling`' : ''})`,
      );
      L.push('');
      L.push(`![scaling](${rel(k === 0 ? 'scaling.svg' : `scaling-device-${k}.svg`)})`);
      L.push('');
      L.push(
        `${sc.scene} ${sc.width}×${sc.height}, ${sc.spp} spp, ${sc.config}; median of ${sc.points[0].reps} runs.`,
      );
      L.push('');
      L.push(
        '| threads | seconds | M paths/s | M segments/s | speed-up | efficiency | CPU seconds |',
      );
      L.push('|---:|---:|---:|---:|---:|---:|---:|');
      for (const p of sc.points) {
        L.push(
          `| ${p.threads} | ${fmt(p.seconds)} | ${fmt(p.mpaths_per_s)} | ${fmt(p.msegments_per_s)} | ${fmt(p.speedup)} | ${(p.efficiency * 100).toFixed(0)} % | ${fmt(p.cpu_seconds)} |`,
        );
      }
      L.push('');
    });
  }
  const dp = result.device_processes;
  if (dp) {
    L.push(
      `### The hardware's own ceiling: independent processes (${dp.machine.cpu}, ${dp.machine.cores} cores)`,
    );
    L.push('');
    L.push(
      `n single-thread renders started at once as separate processes (\`${dp.command}\`): what the machine gives when nothing is shared. Where this stays near 100 % but the thread scaling above falls off, the limit is the renderer's worker pool, not the hardware.`,
    );
    L.push('');
    L.push('| processes | M paths/s in total | efficiency |');
    L.push('|---:|---:|---:|');
    for (const p of dp.points) {
      L.push(
        `| ${p.processes} | ${fmt(p.mpaths_per_s_total)} | ${(p.efficiency * 100).toFixed(0)} % |`,
      );
    }
    L.push('');
  }
  if (deviceFull) {
    const d = deviceFull;
    L.push(`## Cross-check: the same benchmark on ${d.machine.cores} cores`);
    L.push('');
    L.push(
      `\`${d.command}\` on ${d.machine.cpu}, ${d.machine.cores} cores, Node ${d.machine.node}, ${d.machine.date} (code ${d.machine.git_commit ?? 'unknown'}; up to ${d.settings.max_spp} spp, all ${d.settings.threads} threads; raw figures and plots in \`${path.dirname(result.device_full_file)}/\`). An idle machine, so its equal-time ratios are not disturbed by other load; its all-thread times suffer from the pool's scaling shown above.`,
    );
    L.push('');
    L.push('| figure | value |');
    L.push('|---|---|');
    for (const t of d.time_to_target.filter((t) => t && t.reached)) {
      L.push(
        `| cornell, ${t.config}: time to relMSE ${t.target_relmse}, 1 thread / ${d.settings.threads} threads | ${fmt(t.threads_1.seconds)} s / ${fmt(t[`threads_${d.settings.threads}`]?.seconds)} s (${fmt(t.spp_needed)} spp) |`,
      );
    }
    for (const c of d.comparisons.estimator) {
      L.push(
        `| ${c.scene}: NEE+MIS / BSDF-only relMSE, equal time (equal spp) | ${fmt(c.equal_time_ratio)} (${fmt(c.equal_spp_ratio_geomean)}) |`,
      );
    }
    for (const c of d.comparisons.sampler) {
      L.push(
        `| ${c.scene}: sobol / independent relMSE, equal spp / equal time | ${fmt(c.equal_spp_ratio_geomean)} / ${fmt(c.equal_time_ratio)} |`,
      );
    }
    for (const s of d.series) {
      L.push(`| slope, ${s.scene}, ${s.config} | ${fmt(s.slope_relmse_vs_spp)} |`);
    }
    L.push('');
  }
  anchorSection(L);
  L.push('## Method');
  L.push('');
  L.push(
    '- Convergence slope: least-squares fit of log relMSE against log spp over the points listed; ≈ −1 for an unbiased Monte Carlo estimator (flatter means bias or a bug, steeper means the low-discrepancy sampler still stratifies).',
  );
  L.push(
    '- Equal time: geometric mean over spp ≥ 16 of (relMSE × seconds) of one configuration over the other — with relMSE ∝ 1/time this is the error ratio at any equal time, and it uses every render rather than one. The direct reading (both curves interpolated on log-log axes at the longest time both reached) is given beside it. Equal spp: geometric mean of the error ratio over spp ≥ 16. Configurations are rendered interleaved, spp by spp, so that load from other processes hits them alike.',
  );
  L.push(
    '- Time to a target relMSE: the spp needed is interpolated (log-log) from the error series; the time at that spp is interpolated between renders at the two bracketing powers of two, with one thread and with all threads.',
  );
  L.push(
    `- Re-run: \`npm run bench\` (full) or \`npm run bench -- --quick\` (smoke, < 2 min). Thread scaling alone, e.g. on a bigger machine: \`node bench/run.mjs --only scaling --threads-max 16 --out-dir DIR\`, then pass \`--device-results DIR/scaling.json\` to a full run to include it.`,
  );
  L.push('');
  // Sections measured by other scripts (bench/forest.ts, the denoiser's time to error) are
  // written by hand below this marker; a re-run keeps them.
  const kept = existsSync(mdPath) ? readFileSync(mdPath, 'utf8') : '';
  const at = kept.indexOf(HAND_WRITTEN);
  if (at >= 0) L.push(kept.slice(at));
  writeFileSync(mdPath, L.join('\n'));
}

// ------------------------------------------------- against the native anchor

const readJson = (f) => (existsSync(f) ? JSON.parse(readFileSync(f, 'utf8')) : null);
const readJsonLines = (f) =>
  existsSync(f)
    ? readFileSync(f, 'utf8')
        .trim()
        .split('\n')
        .filter(Boolean)
        .map((l) => JSON.parse(l))
    : [];

/**
 * The section on speed against the native anchor (issue 10): bench:core
 * figures of this machine (outDir/core.json) and of the 16-core device
 * (bench/results/device/s4/core.json and speed-*), each with its machine,
 * date and commit.
 */
function anchorSection(L) {
  const dev = (f) => path.join(ROOT, 'bench/results/device', f);
  // The device: its latest bench:core (s4/, issue 10's last round), then the
  // first one (524651a), so that the page shows where the rounds took it.
  const cores = [
    readJson(path.join(outDir, 'core.json')),
    readJson(dev('s4/core.json')),
    readJson(dev('speed-core.json')),
  ].filter((c) => c && c.schema === 'pathwise-bench-core/2');
  if (cores.length === 0) return;
  L.push('## Speed against the native anchor');
  L.push('');
  L.push(
    "pathwise against the C++ anchor of `../shared/anchors/native` (same estimator, double precision, `-O3 -march=native`, a SIMD loop over ≤ 48 primitives and a SAH BVH above), run alternately in the same `npm run bench:core` (bench/core.mjs), median of the repetitions. pathwise M paths/s use the command line's render time (workers started to finished, start-up and JIT warm-up included); the anchor's its own render time (no parsing). Cornell: 128×128, 6 bounces, NEE+MIS, pathwise's default sampler; 10k spheres: bench/scenes.mjs (10,000 non-overlapping spheres under an area light), same settings. All-thread runs render 512×512 (the same work per thread).",
  );
  L.push('');
  for (const c of cores) {
    const m = c.machine;
    L.push(
      `### ${m.cpu}, ${m.cores} cores, Node ${m.node} — ${m.date.slice(0, 10)}, commit ${(m.git_commit ?? 'unknown').slice(0, 7)}${m.git_dirty ? ' (uncommitted changes)' : ''}`,
    );
    L.push('');
    const maxLoad = Math.max(m.loadavg_start[0], c.loadavg_end[0]);
    if (maxLoad > m.cores * 0.75) {
      L.push(
        `> Shared machine: 1-minute load average up to ${maxLoad.toFixed(1)} on ${m.cores} cores. The ratios (pathwise and anchor alternated in one run) hold better than the absolute figures.`,
      );
      L.push('');
    }
    L.push(
      '| scene | image | threads | pathwise M paths/s | native M paths/s | pathwise / native |',
    );
    L.push('|---|---|---:|---:|---:|---:|');
    for (const t of c.throughput) {
      L.push(
        `| ${t.case} | ${t.width}×${t.height}, ${t.spp} spp | ${t.threads} | ${fmt(t.pathwise.mpaths_per_s)} | ${t.native ? fmt(t.native.mpaths_per_s) : '—'} | ${t.ratio === null ? '—' : `**${fmt(t.ratio)}**`} |`,
      );
    }
    L.push('');
    L.push(
      '| 10k spheres, 1 spp, 128×128, whole process | pathwise | native | pathwise / native | pathwise: compile (once) | workers ready | worker heap |',
    );
    L.push('|---|---:|---:|---:|---:|---:|---:|');
    for (const w of c.whole_process) {
      L.push(
        `| ${w.threads} threads | ${fmt(w.pathwise_process_seconds)} s | ${w.native_process_seconds === null ? '—' : `${fmt(w.native_process_seconds)} s`} | ${w.time_ratio === null ? '—' : `**${fmt(w.time_ratio)}×**`} | ${fmt(w.pathwise_compile_seconds)} s | ${fmt(w.pathwise_first_ready_seconds)}–${fmt(w.pathwise_last_ready_seconds)} s | ${fmt(w.pathwise_worker_heap_mb)} MB |`,
      );
    }
    L.push('');
    L.push(`Command: \`${c.command}\`.`);
    L.push('');
  }
  const inproc = readJsonLines(dev('speed-inproc.jsonl'));
  if (inproc.length) {
    L.push('### Steady state in one thread (16-core device)');
    L.push('');
    L.push(
      'In-process, no start-up: `node dist/bench/inproc.mjs SCENE 128 128 16 6 5` (bench/inproc.ts: a warm-up render, then the median of 5), "before" the same harness on commit 27f0092 (before issue 10), "native" the anchor\'s render time at 1 thread (median of 3).',
    );
    L.push('');
    L.push(
      '| scene | before M paths/s | pathwise M paths/s | native M paths/s | pathwise / native |',
    );
    L.push('|---|---:|---:|---:|---:|');
    for (const scene of [...new Set(inproc.map((r) => r.scene))]) {
      const of = (w) => inproc.filter((r) => r.scene === scene && r.which === w);
      const before = of('before')[0]?.r.mpaths_per_s;
      const now = of('pathwise')[0]?.r.mpaths_per_s;
      const nat = median(of('native').map((r) => r.r.mpaths_per_s));
      L.push(
        `| ${scene.includes('cornell') ? 'cornell' : 'spheres-10k'} | ${fmt(before)} | ${fmt(now)} | ${fmt(nat)} | **${fmt(now / nat)}** |`,
      );
    }
    L.push('');
  }
  const cli = readJsonLines(dev('speed-cli-scaling.jsonl'));
  const pools = ['speed-pool-shared.json', 'speed-pool-transfer.json'].map((f) => readJson(dev(f)));
  const procs = readJson(dev('speed-processes.json'));
  if (cli.length) {
    L.push('### Worker scaling (16-core device), cornell 512×512, 16 spp');
    L.push('');
    L.push(
      'Command line: `node bin/pathwise.js render scenes/cornell.json --width 512 --height 512 --spp 16 --threads T --json` (with more than four workers it runs in a child node with `--v8-pool-size=0`; the "V8 pool 4" rows forbid that, as before this change). Browser pool: the page\'s WorkerPool and render worker in Node (`node dist/bench/pool-node.mjs --size 512 --spp 16 --mode shared|transfer`; bench/pool-node.ts), film bit-identical at every count. Processes: n independent single-thread renders at once (`node bench/processes.mjs --spp 16`), the machine\'s own ceiling.',
    );
    L.push('');
    L.push('| threads | CLI s | CLI speed-up | CLI efficiency | workers ready (s) |');
    L.push('|---:|---:|---:|---:|---:|');
    const base = cli.find((r) => r.r.threads === 1 && r.v8pool !== 'four');
    for (const r of cli) {
      const sp = base ? base.r.seconds / r.r.seconds : null;
      L.push(
        `| ${r.r.threads}${r.v8pool === 'four' ? ' (V8 pool 4)' : ''} | ${fmt(r.r.seconds)} | ${sp === null ? '—' : fmt(sp)} | ${sp === null ? '—' : `${((sp / r.r.threads) * 100).toFixed(0)} %`} | ${fmt(r.r.first_ready_seconds)}–${fmt(r.r.last_ready_seconds)} |`,
      );
    }
    L.push('');
    for (const p of pools.filter(Boolean)) {
      L.push(
        `Browser pool, ${p.config.mode} mode${p.node_options?.length ? ` (node ${p.node_options.join(' ')})` : ''}: ` +
          p.points
            .map(
              (q) =>
                `${q.threads} workers ${fmt(q.seconds)} s (${(q.efficiency * 100).toFixed(0)} %)`,
            )
            .join(', ') +
          `; films bit-identical: ${p.films_bit_identical ? 'yes' : 'NO'}.`,
      );
      L.push('');
    }
    const devCore = readJson(dev('speed-core.json'));
    if (devCore?.throughput?.length) {
      const parts = [];
      for (const name of [...new Set(devCore.throughput.map((t) => t.case))]) {
        const rows = devCore.throughput.filter((t) => t.case === name && t.native);
        const one = rows.find((t) => t.threads === 1);
        const all = rows.find((t) => t.threads > 1);
        if (!one || !all) continue;
        const f = (w) => all[w].mpaths_per_s / one[w].mpaths_per_s;
        parts.push(
          `${name} 1 → ${all.threads} threads: native ${fmt(f('native'))}× (${((f('native') / all.threads) * 100).toFixed(0)} %), pathwise ${fmt(f('pathwise'))}× (${((f('pathwise') / all.threads) * 100).toFixed(0)} %)`,
        );
      }
      if (parts.length) {
        L.push(
          `Same lease, bench:core above (512×512 against 128×128, the same work per thread): ${parts.join('; ')}.`,
        );
        L.push('');
      }
    }
    if (procs) {
      L.push(
        'Independent processes: ' +
          procs.points
            .map(
              (q) =>
                `${q.processes}: ${fmt(q.mpaths_per_s_total)} M paths/s (${(q.efficiency * 100).toFixed(0)} %)`,
            )
            .join(', ') +
          '.',
      );
      L.push('');
    }
  }
}

// --------------------------------------------------------------------- main

/** Scaling series measured elsewhere: each a scaling.json of `--only scaling` or a whole bench.json. */
function readDeviceScaling(files) {
  return files.split(',').map((f) => {
    const j = JSON.parse(readFileSync(path.resolve(ROOT, f), 'utf8'));
    return j.scaling ?? j;
  });
}

const started = performance.now();
const command = `npm run bench${process.argv.length > 2 ? ' -- ' + process.argv.slice(2).join(' ') : ''}`;
const machine = machineInfo();
log(`pathwise bench: ${machine.cpu}, ${machine.cores} cores, Node ${machine.node}`);

try {
  if (opt.from) {
    // Re-renders the report and plots of an existing bench.json, measuring nothing.
    const result = JSON.parse(readFileSync(path.resolve(ROOT, opt.from), 'utf8'));
    Object.assign(result, analyze(result.series));
    // Device figures are files of their own: take the current ones.
    if (opt['device-results']) result.device_scaling = readDeviceScaling(opt['device-results']);
    const deviceFull = result.device_full_file
      ? JSON.parse(readFileSync(path.resolve(ROOT, result.device_full_file), 'utf8'))
      : null;
    result.plots = writePlots(result);
    writeMarkdown(result, deviceFull);
    log(`wrote ${mdPath} from ${opt.from}`);
  } else if (only === 'scaling') {
    const cfg = CONFIGS.find((c) => c.id === (opt.config ?? 'nee-mis/sobol')) ?? CONFIGS[1];
    const scaling = runScaling(cfg);
    scaling.command = `node bench/run.mjs ${process.argv.slice(2).join(' ')}`;
    writeFileSync(path.join(outDir, 'scaling.json'), JSON.stringify(scaling, null, 2) + '\n');
    log(`wrote ${path.join(outDir, 'scaling.json')}`);
  } else {
    const series = runSeries();
    const { comparisons, recommendation } = analyze(series);
    log(`recommendation: ${recommendation.text}`);
    const bestSampler = recommendation.sampler;
    // Saved before the slower stages, so a failure there keeps the series.
    writeFileSync(
      path.join(outDir, 'bench.partial.json'),
      JSON.stringify({ machine, series, comparisons, recommendation }, null, 2) + '\n',
    );
    const winner = CONFIGS.find((c) => c.id === `nee-mis/${bestSampler}`);
    const other = CONFIGS.find(
      (c) => c.id === `nee-mis/${bestSampler === 'sobol' ? 'independent' : 'sobol'}`,
    );
    const time_to_target = [timeToTarget(series, winner), timeToTarget(series, other)];
    const scaling = only === 'errors' ? null : runScaling(winner);
    const device_scaling = opt['device-results'] ? readDeviceScaling(opt['device-results']) : [];
    const device_processes = opt['device-processes']
      ? JSON.parse(readFileSync(path.resolve(ROOT, opt['device-processes']), 'utf8'))
      : null;
    const device_full = opt['device-full']
      ? JSON.parse(readFileSync(path.resolve(ROOT, opt['device-full']), 'utf8'))
      : null;
    // The same run measures speed against the native anchor (bench:core).
    if (!quick || opt['with-core']) {
      log('bench:core: pathwise against the native anchor');
      const r = spawnSync(
        process.execPath,
        [
          path.join(ROOT, 'bench/core.mjs'),
          '--out',
          path.join(outDir, 'core.json'),
          ...(quick ? ['--quick'] : []),
        ],
        { stdio: ['ignore', 'ignore', 'inherit'] },
      );
      if (r.status !== 0) log(`bench:core failed (${r.status}); the report goes without it`);
    }
    const result = {
      schema: 'pathwise-bench/1',
      command,
      quick,
      machine,
      loadavg_end: os.loadavg(),
      total_seconds: (performance.now() - started) / 1000,
      settings: { seed: SEED, max_spp: maxSpp, threads: threadsAll, target_relmse: TARGET },
      series,
      comparisons,
      recommendation,
      time_to_target,
      scaling,
      device_scaling,
      device_processes,
      device_full_file: opt['device-full'] ?? null,
    };
    result.plots = writePlots(result);
    writeFileSync(path.join(outDir, 'bench.json'), JSON.stringify(result, null, 2) + '\n');
    writeMarkdown(result, device_full);
    rmSync(path.join(outDir, 'bench.partial.json'), { force: true });
    log(
      `wrote ${path.join(outDir, 'bench.json')} and ${mdPath} in ${result.total_seconds.toFixed(0)} s`,
    );
  }
} finally {
  if (existsSync(tmpDir)) rmSync(tmpDir, { recursive: true, force: true });
}
