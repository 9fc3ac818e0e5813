// Peer measurement of issue 24: three-gpu-pathtracer against pathwise in the
// same headless Chromium on this machine, where WebGL2 is software
// (SwiftShader), the weak-GPU case.
//   node bench/peer/run.mjs [--runs 3] [--cap 120] [--scenes cornell] [--tracers gpt,pathwise]
//                           [--tiles 1] [--out file.json]
// Scenes: a preset with a reference (tests/references), optionally with
// variants of the three.js side after a colon, joined by '+': `rect` (the
// emitter as a RectAreaLight, sampled by three-gpu-pathtracer's NEE) and
// `nomis` (FEATURE_MIS off: no NEE; for the emissive scene the same estimator
// as the default, since there are no lights to sample, but a shorter shader).
// The default, cornell alone, takes about 8 minutes on 2 cores; the report's
// table is `--scenes cornell,cornell:nomis,cornell:rect` (about 22).
// Per scene and tracer: samples per pixel per second after warm-up, time to
// the first sample (for three-gpu-pathtracer, the shader compile separately),
// time to relMSE 1e-2 and 1e-3 against the scene's Mitsuba reference, final
// relMSE and the late slope of relMSE against spp (about −1 while the error
// is noise; near 0 once a bias floor dominates). Medians of --runs page loads
// per tracer, the tracers alternating. Writes bench/results/peer-<date>.json.
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { build as esbuild } from 'esbuild';
import { build, preview } from 'vite';
import { blockMare, machineInfo, median, readPfm, relMse, ROOT } from '../lib.mjs';
import { pathwiseProbe } from './pathwise-probe.js';
import { CHROMIUM_ARGS, launchChromium } from '../../scripts/chromium.mjs';

const args = process.argv.slice(2);
const arg = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : fallback;
};
const RUNS = Number(arg('runs', 3));
/** Seconds per page load, from navigation start, before a run stops unconverged. */
const CAP_S = Number(arg('cap', 120));
const SCENES = arg('scenes', 'cornell').split(',');
const TRACERS = arg('tracers', 'gpt,pathwise').split(',');
/** three-gpu-pathtracer's tiles per side (1: each sample is one full-frame draw). */
const TILES = Number(arg('tiles', 1));
const TARGETS = [1e-2, 1e-3];
/** Seconds after the first sample before the rate is measured (JIT, compile, worker start). */
const WARMUP_S = 2;
/** pathwise reaches 1e-3 in seconds; it renders at least this long after its first image, for a steadier rate. */
const MIN_RENDER_S = 15;
const CHECKPOINTS = Array.from({ length: 17 }, (_, k) => 2 ** k);

/**
 * The scenes: pathwise's scene file, its reference and the path length.
 * Mitsuba's references use max_depth = maxBounces + 1 path segments
 * (tests/references/references.json). three-gpu-pathtracer adds a surface's
 * emission at each of its `bounces` loop iterations, and with no light
 * objects it does no next-event estimation, so `bounces` = maxBounces + 1
 * gives the same longest path.
 */
function loadScene(spec) {
  // `cornell:rect`: pathwise's scene as it is, three-gpu-pathtracer's with the
  // emitter as a RectAreaLight (three-scene.js), its own light model.
  // `:nomis` (diagnostic) turns off three-gpu-pathtracer's next-event
  // estimation (FEATURE_MIS): lights are then reached by BSDF sampling alone.
  const [name, variantList] = spec.split(':');
  const variants = variantList ? variantList.split('+') : [];
  for (const v of variants) {
    if (v !== 'rect' && v !== 'nomis') throw new Error(`unknown variant ${v} in ${spec}`);
  }
  const variant = variants.includes('rect') ? 'rect' : undefined;
  const refs = JSON.parse(readFileSync(join(ROOT, 'tests/references/references.json'), 'utf8'));
  const entry = refs.entries[name];
  const json = JSON.parse(readFileSync(join(ROOT, entry.scene), 'utf8'));
  const reference = readPfm(join(ROOT, 'tests/references', entry.file));
  // The directly seen emitter: the only pixels above 1 in these references.
  const emitterMask = new Uint8Array(reference.width * reference.height);
  for (let p = 0; p < emitterMask.length; p++) {
    const [r, g, b] = reference.rgb.subarray(3 * p, 3 * p + 3);
    emitterMask[p] = Math.max(r, g, b) > 1 ? 1 : 0;
  }
  return {
    name: spec,
    preset: name,
    emitters: variant === 'rect' ? 'rect-area-light' : 'emissive',
    mis: !variants.includes('nomis'),
    emitterMask,
    json,
    reference,
    width: reference.width,
    height: reference.height,
    maxBounces: entry.maxBounces,
    referenceInfo: `${entry.file}: ${entry.generator ?? refs.generator}, ${entry.spp} spp`,
  };
}

/** The top-down RGB of a bottom-up RGBA readback (WebGL's row order). */
function rgbFromBottomUp(rgba, width, height) {
  const rgb = new Float32Array(width * height * 3);
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const i = ((height - 1 - y) * width + x) * 4;
      const j = (y * width + x) * 3;
      rgb[j] = rgba[i];
      rgb[j + 1] = rgba[i + 1];
      rgb[j + 2] = rgba[i + 2];
    }
  }
  return rgb;
}

/**
 * Seconds at which relMSE first reaches `target`, interpolated log-log between
 * the checkpoints that bracket it (relMSE ∝ 1/t between them); null if never.
 */
function timeTo(points, target, key = 'relmse') {
  for (let i = 0; i < points.length; i++) {
    if (points[i][key] > target) continue;
    if (i === 0) return points[0].seconds;
    const a = points[i - 1];
    const b = points[i];
    const f = Math.log(target / a[key]) / Math.log(b[key] / a[key]);
    return Math.exp(Math.log(a.seconds) + f * Math.log(b.seconds / a.seconds));
  }
  return null;
}

/** Least-squares slope of log relMSE against log spp over the last `n` checkpoints. */
function lateSlope(points, n = 4) {
  const p = points.filter((q) => q.samples > 0).slice(-n);
  if (p.length < 2) return null;
  const xs = p.map((q) => Math.log(q.samples));
  const ys = p.map((q) => Math.log(q.relmse));
  const mx = xs.reduce((a, b) => a + b) / xs.length;
  const my = ys.reduce((a, b) => a + b) / ys.length;
  let sxy = 0;
  let sxx = 0;
  for (let i = 0; i < xs.length; i++) {
    sxy += (xs[i] - mx) * (ys[i] - my);
    sxx += (xs[i] - mx) ** 2;
  }
  return sxy / sxx;
}

/** spp/s from the first checkpoint WARMUP_S after the first sample to the last. */
function rate(points, firstSampleS) {
  const late = points.filter((p) => p.seconds >= firstSampleS + WARMUP_S);
  const a = late[0];
  const b = points[points.length - 1];
  if (!a || a === b) {
    // Too short a run for a warm window: the whole run after the first sample.
    const first = points[0];
    return b === first ? null : (b.samples - first.samples) / (b.seconds - first.seconds);
  }
  return (b.samples - a.samples) / (b.seconds - a.seconds);
}

/**
 * Mean of each channel, over the pixels the mask does not mark (all, without
 * one): an energy mismatch shows here before it shows as an error floor.
 */
function meanRgb(rgb, mask) {
  const m = [0, 0, 0];
  let n = 0;
  for (let p = 0; p < rgb.length / 3; p++) {
    if (mask?.[p]) continue;
    for (let c = 0; c < 3; c++) m[c] += rgb[3 * p + c];
    n++;
  }
  return m.map((x) => x / n);
}

/**
 * Where a run stops short of a target: the time it would take at the measured
 * rate if relMSE kept falling as 1/spp from the last checkpoint. An
 * extrapolation, reported apart from the measured times; meaningless if the
 * late slope is far from −1 (a floor).
 */
function extrapolate(points, sppPerS, target) {
  const last = points[points.length - 1];
  if (last.relmse <= target || !sppPerS) return null;
  // A floor: relMSE no longer falls as 1/spp, and no time reaches the target.
  if (!(lateSlope(points) <= -0.8)) return Infinity;
  const spp = (last.samples * last.relmse) / target;
  return last.seconds + (spp - last.samples) / sppPerS;
}

/**
 * The relMSE a uniform per-channel bias alone would leave: each channel of
 * the reference, off the directly seen emitter (whose pixels dominate the
 * image mean), scaled by the ratio of the image's channel mean there to the
 * reference's. An estimate of a floor: a bias that is not uniform over the
 * image is not captured, and noise in the means is counted as bias.
 */
function meanBiasFloor(rgb, reference, mask) {
  const m = meanRgb(rgb, mask);
  const r = meanRgb(reference, mask);
  const scaled = reference.map((v, i) => (mask[Math.floor(i / 3)] ? v : (v * m[i % 3]) / r[i % 3]));
  return relMse(scaled, reference);
}

function summarise(points, firstSampleS, reference, width, height, mask) {
  const last = points[points.length - 1];
  const sppPerS = rate(points, firstSampleS);
  return {
    mean_bias_floor: meanBiasFloor(points.last, reference, mask),
    final_mean_rgb_without_emitter: meanRgb(points.last, mask),
    extrapolated_time_to: Object.fromEntries(
      TARGETS.map((t) => [String(t), extrapolate(points, sppPerS, t)]),
    ),
    final_block_mare_8: blockMare(points.last, reference, width, height, 8),
    final_mean_rgb: meanRgb(points.last),
    spp_per_s: sppPerS,
    first_sample_s: firstSampleS,
    time_to: Object.fromEntries(TARGETS.map((t) => [String(t), timeTo(points, t)])),
    time_to_without_emitter_pixels: Object.fromEntries(
      TARGETS.map((t) => [String(t), timeTo(points, t, 'relmse_without_emitter')]),
    ),
    final_relmse_without_emitter: last.relmse_without_emitter,
    final_spp: last.samples,
    final_seconds: last.seconds,
    final_relmse: last.relmse,
    late_slope: lateSlope(points),
    points,
  };
}

// ---- servers and browser --------------------------------------------------

const tmp = mkdtempSync(join(tmpdir(), 'pathwise-peer-'));
const outDir = join(tmp, 'web');
console.error('building the demo and the three-gpu-pathtracer page …');
await build({ root: ROOT, logLevel: 'error', build: { outDir, emptyOutDir: true } });
mkdirSync(join(outDir, 'peer'));
await esbuild({
  entryPoints: [join(ROOT, 'bench/peer/gpt-page.js')],
  bundle: true,
  format: 'esm',
  minify: false,
  outfile: join(outDir, 'peer/gpt.js'),
  logLevel: 'error',
});
writeFileSync(
  join(outDir, 'peer/index.html'),
  '<!doctype html><meta charset="utf-8"><title>peer</title><script type="module" src="./gpt.js"></script>',
);
// `vite preview` serves both with the demo's COOP/COEP headers (pathwise's
// shared memory; harmless to the WebGL page).
const server = await preview({
  root: ROOT,
  logLevel: 'error',
  build: { outDir },
  preview: { host: '127.0.0.1', port: 0 },
});
const url = server.resolvedUrls.local[0];

// The project's Chromium and flags (scripts/chromium.mjs). With them WebGL2
// is ANGLE on SwiftShader (Vulkan), software, for both tracers alike.
const browser = await launchChromium();

/** relMSE over the pixels that do not see the emitter directly (lib.mjs's relMse on them). */
function relMseMasked(rgb, scene) {
  const keep = [];
  for (let p = 0; p < scene.emitterMask.length; p++) if (!scene.emitterMask[p]) keep.push(p);
  const pick = (img) =>
    Float32Array.from(keep.flatMap((p) => [img[3 * p], img[3 * p + 1], img[3 * p + 2]]));
  return relMse(pick(rgb), pick(scene.reference.rgb));
}

/** Pulls the checkpoint images out of the page and scores them with lib.mjs's relMSE. */
async function score(page, checkpoints, scene, bottomUp) {
  const points = [];
  for (let i = 0; i < checkpoints.length; i++) {
    const raw = Float32Array.from(await page.evaluate((k) => window.peerImage(k), i));
    const rgb = bottomUp ? rgbFromBottomUp(raw, scene.width, scene.height) : raw;
    points.push({
      samples: checkpoints[i].samples,
      seconds: checkpoints[i].ms / 1000,
      relmse: relMse(rgb, scene.reference.rgb),
      relmse_without_emitter: relMseMasked(rgb, scene),
      cap: checkpoints[i].cap,
    });
    if (i === checkpoints.length - 1) points.last = rgb;
  }
  return points;
}

function pageLog(page, log) {
  page.on('console', (m) => {
    if (m.type() === 'error' || m.type() === 'warning') log.push(`${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => log.push(`pageerror: ${e.message}`));
}

async function runGpt(scene, seed) {
  const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
  const log = [];
  pageLog(page, log);
  await page.goto(`${url}peer/index.html?seed=${seed}`);
  await page.waitForFunction(() => typeof window.runPeer === 'function');
  const r = await page.evaluate((config) => window.runPeer(config), {
    scene: scene.json,
    width: scene.width,
    height: scene.height,
    // With a RectAreaLight, next-event estimation adds one segment past the
    // last hit, so maxBounces loop iterations reach Mitsuba's max_depth.
    bounces: scene.emitters === 'emissive' || !scene.mis ? scene.maxBounces + 1 : scene.maxBounces,
    emitters: scene.emitters,
    mis: scene.mis,
    tiles: TILES,
    checkpoints: CHECKPOINTS,
    capMs: CAP_S * 1000,
    reference: Array.from(scene.reference.rgb),
    stopRelMse: TARGETS[TARGETS.length - 1],
  });
  const points = await score(page, r.checkpoints, scene, true);
  const last = points.last;
  await page.close();
  const t = r.timeline;
  return {
    ...summarise(
      points,
      t.firstSample / 1000,
      scene.reference.rgb,
      scene.width,
      scene.height,
      scene.emitterMask,
    ),
    // compileAsync resolves at once here; the program is really compiled and
    // linked at the first draw, so this is compile plus one sample.
    scene_built_to_first_sample_s: (t.firstSample - t.sceneBuilt) / 1000,
    compile_async_s: (t.compiled - t.sceneBuilt) / 1000,
    scene_build_s: (t.sceneBuilt - t.context) / 1000,
    page_script_s: t.start / 1000,
    readback_ms_total: r.readMs,
    size: r.size,
    scene_summary: r.scene,
    bounces: scene.emitters === 'emissive' || !scene.mis ? scene.maxBounces + 1 : scene.maxBounces,
    gl: r.info,
    warnings: r.warnings,
    gl_errors: r.glErrors,
    console: log,
    last,
  };
}

async function runPathwise(scene, seed) {
  const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
  const log = [];
  pageLog(page, log);
  const query = `scene=${scene.preset}&width=${scene.width}&height=${scene.height}&seed=${seed}&spp=1000000`;
  await page.goto(`${url}?${query}`);
  const r = await page.evaluate(pathwiseProbe, {
    minRenderMs: MIN_RENDER_S * 1000,
    checkpoints: CHECKPOINTS,
    capMs: CAP_S * 1000,
    reference: Array.from(scene.reference.rgb),
    stopRelMse: TARGETS[TARGETS.length - 1],
  });
  const points = await score(page, r.checkpoints, scene, false);
  const last = points.last;
  await page.close();
  const size = [r.checkpoints[0].width, r.checkpoints[0].height];
  if (size[0] !== scene.width || size[1] !== scene.height) {
    throw new Error(`pathwise rendered ${size.join('×')}, not ${scene.width}×${scene.height}`);
  }
  return {
    ...summarise(
      points,
      r.timeline.firstImage / 1000,
      scene.reference.rgb,
      scene.width,
      scene.height,
      scene.emitterMask,
    ),
    scene_loaded_s: r.timeline.sceneLoaded / 1000,
    workers: r.workers,
    size,
    console: log,
    last,
  };
}

// ---- the runs -------------------------------------------------------------

const machine = machineInfo();
const browserInfo = await (async () => {
  const page = await browser.newPage();
  await page.goto(`${url}peer/index.html`);
  const r = await page.evaluate(() => ({
    cores: navigator.hardwareConcurrency,
    userAgent: navigator.userAgent,
  }));
  await page.close();
  return { ...r, version: browser.version(), args: CHROMIUM_ARGS };
})();

/** Median over runs of the extrapolated (or reached) time; 'floor' if any run hit one. */
function extrapolatedMedian(rs, key) {
  const v = rs.map((r) => r.extrapolated_time_to[key] ?? r.time_to[key]);
  if (v.includes(Infinity)) return 'floor';
  return v.every((x) => Number.isFinite(x)) ? median(v) : null;
}

const RUNNERS = { gpt: runGpt, pathwise: runPathwise };
const NAMES = { gpt: 'three-gpu-pathtracer', pathwise: 'pathwise' };
const results = [];
for (const name of SCENES) {
  const scene = loadScene(name);
  const runs = Object.fromEntries(TRACERS.map((t) => [t, []]));
  for (let k = 0; k < RUNS; k++) {
    // Alternate which tracer goes first, so neither always gets the cooler machine.
    const order = k % 2 ? [...TRACERS].reverse() : TRACERS;
    for (const tracer of order) {
      const r = await RUNNERS[tracer](scene, k + 1);
      runs[tracer].push(r);
      const tt = (x) => (x === null ? '—' : `${x.toFixed(1)} s`);
      console.error(
        `${name} ${NAMES[tracer]} run ${k + 1}: ${r.spp_per_s?.toFixed(2)} spp/s, first sample ${r.first_sample_s.toFixed(2)} s` +
          `${r.scene_built_to_first_sample_s !== undefined ? ` (scene built to first sample ${r.scene_built_to_first_sample_s.toFixed(2)} s)` : ''}, ` +
          `1e-2 ${tt(r.time_to['0.01'])}, 1e-3 ${tt(r.time_to['0.001'])}, ` +
          `final relMSE ${r.final_relmse.toExponential(3)} at ${r.final_spp} spp / ${r.final_seconds.toFixed(1)} s, slope ${r.late_slope?.toFixed(2)}, ` +
          `mean RGB off the emitter / reference ${r.final_mean_rgb_without_emitter
            .map((x, c) => (x / meanRgb(scene.reference.rgb, scene.emitterMask)[c]).toFixed(4))
            .join(' ')}, relMSE off the emitter ${r.final_relmse_without_emitter.toExponential(3)}`,
      );
    }
  }
  // The two tracers' longest renders against each other: where both are
  // unbiased this is their noise; a floor in one shows up here too.
  const cross =
    runs.gpt?.length && runs.pathwise?.length
      ? relMse(
          runs.gpt.reduce((a, b) => (b.final_spp > a.final_spp ? b : a)).last,
          runs.pathwise.reduce((a, b) => (b.final_spp > a.final_spp ? b : a)).last,
        )
      : null;
  for (const tracer of TRACERS) {
    const rs = runs[tracer];
    const med = (f) => {
      const v = rs.map(f).filter((x) => x !== null && x !== undefined && Number.isFinite(x));
      return v.length === rs.length ? median(v) : null;
    };
    results.push({
      scene: name,
      tracer: NAMES[tracer],
      size: `${scene.width}x${scene.height}`,
      reference: scene.referenceInfo,
      runs: rs.length,
      spp_per_s: med((r) => r.spp_per_s),
      first_sample_s: med((r) => r.first_sample_s),
      compile_s:
        tracer === 'gpt'
          ? med((r) => r.scene_built_to_first_sample_s - 1 / r.spp_per_s)
          : undefined,
      final_mean_rgb: rs[rs.length - 1].final_mean_rgb,
      reference_mean_rgb: meanRgb(scene.reference.rgb),
      time_to_1e2_s: med((r) => r.time_to['0.01']),
      time_to_1e3_s: med((r) => r.time_to['0.001']),
      reached_1e3: rs.filter((r) => r.time_to['0.001'] !== null).length,
      // 'floor' where a run's relMSE had stopped falling as 1/spp (late slope above −0.8).
      extrapolated_time_to_1e2_s: extrapolatedMedian(rs, '0.01'),
      extrapolated_time_to_1e3_s: extrapolatedMedian(rs, '0.001'),
      final_relmse: med((r) => r.final_relmse),
      final_relmse_without_emitter: med((r) => r.final_relmse_without_emitter),
      time_to_1e2_without_emitter_s: med((r) => r.time_to_without_emitter_pixels['0.01']),
      emitter_pixels: scene.emitterMask.reduce((a, b) => a + b, 0),
      gpt_scene: rs[0].scene_summary,
      final_block_mare_8: med((r) => r.final_block_mare_8),
      mean_rgb_over_reference: rs.map((r) =>
        r.final_mean_rgb.map((x, c) => x / meanRgb(scene.reference.rgb)[c]),
      ),
      mean_bias_floor: med((r) => r.mean_bias_floor),
      mean_rgb_over_reference_without_emitter: rs.map((r) =>
        r.final_mean_rgb_without_emitter.map(
          (x, c) => x / meanRgb(scene.reference.rgb, scene.emitterMask)[c],
        ),
      ),
      late_slope: med((r) => r.late_slope),
      cross_relmse_gpt_vs_pathwise: cross,
      per_run: rs.map(({ last, ...r }) => r),
    });
  }
}
await browser.close();
await new Promise((resolve) => server.httpServer.close(resolve));
rmSync(tmp, { recursive: true, force: true });

// ---- report ---------------------------------------------------------------

const fmtS = (x, reached, runs, extra) =>
  x === null
    ? `${reached ? `${reached}/${runs} runs` : `not within ${CAP_S} s`}${
        extra === 'floor' ? ' (floor)' : extra ? ` (~${extra.toFixed(0)} s extrap.)` : ''
      }`
    : `${x.toFixed(1)} s`;
const header = [
  'scene',
  'tracer',
  'size',
  'spp/s',
  'first sample',
  'compile',
  'to 1e-2',
  'to 1e-3',
  'final relMSE',
  'w/o emitter px',
  'to 1e-2 w/o em.',
  'blockMARE8',
  'mean-bias floor',
  'late slope',
];
const rows = results.map((r) => [
  r.scene,
  r.tracer,
  r.size,
  r.spp_per_s?.toFixed(2) ?? '—',
  `${r.first_sample_s?.toFixed(2)} s`,
  r.compile_s === undefined ? '—' : `${r.compile_s.toFixed(2)} s`,
  fmtS(r.time_to_1e2_s, 0, r.runs, r.extrapolated_time_to_1e2_s),
  fmtS(r.time_to_1e3_s, r.reached_1e3, r.runs, r.extrapolated_time_to_1e3_s),
  `${r.final_relmse.toExponential(2)} @ ${r.per_run.map((q) => q.final_spp).sort((a, b) => a - b)[r.runs >> 1]} spp`,
  r.final_relmse_without_emitter.toExponential(2),
  fmtS(r.time_to_1e2_without_emitter_s, 0, r.runs),
  r.final_block_mare_8.toExponential(2),
  r.mean_bias_floor.toExponential(1),
  r.late_slope?.toFixed(2) ?? '—',
]);
const widths = header.map((h, i) => Math.max(h.length, ...rows.map((r) => r[i].length)));
const line = (cells) => cells.map((c, i) => c.padEnd(widths[i])).join('  ');
console.log(line(header));
for (const r of rows) console.log(line(r));
const ratios = [];
for (const name of SCENES) {
  const g = results.find((r) => r.scene === name && r.tracer === NAMES.gpt);
  const p = results.find((r) => r.scene === name && r.tracer === NAMES.pathwise);
  if (!g || !p) continue;
  const ratio = {
    scene: name,
    spp_per_s_pathwise_over_gpt: p.spp_per_s / g.spp_per_s,
    time_to_1e2_gpt_over_pathwise:
      g.time_to_1e2_s && p.time_to_1e2_s ? g.time_to_1e2_s / p.time_to_1e2_s : null,
    cross_relmse_gpt_vs_pathwise: g.cross_relmse_gpt_vs_pathwise,
  };
  ratios.push(ratio);
  console.log(
    `${name}: pathwise/gpt spp/s ${ratio.spp_per_s_pathwise_over_gpt.toFixed(2)}×; ` +
      `gpt/pathwise time to 1e-2 ${ratio.time_to_1e2_gpt_over_pathwise?.toFixed(2) ?? '—'}×; ` +
      `relMSE(gpt final, pathwise final) ${ratio.cross_relmse_gpt_vs_pathwise?.toExponential(2) ?? '—'}`,
  );
}
const loadEnd = loadavg();
console.log(
  `machine: ${machine.cpu}, ${machine.cores} cores; load average at start ${machine.loadavg_start.map((x) => x.toFixed(2)).join(' ')}, at end ${loadEnd.map((x) => x.toFixed(2)).join(' ')}`,
);

const report = {
  command: `node bench/peer/run.mjs ${args.join(' ')}`.trim(),
  machine: { ...machine, loadavg_end: loadEnd },
  browser: browserInfo,
  settings: {
    runs: RUNS,
    cap_s: CAP_S,
    tiles: TILES,
    warmup_s: WARMUP_S,
    pathwise_min_render_s: MIN_RENDER_S,
    checkpoints: 'powers of two of spp, each run stopping at relMSE ≤ 1e-3 or the cap',
    times: 'seconds since navigation start of the page (page clock), start-up included',
  },
  results,
  ratios,
};
const date = new Date().toISOString().slice(0, 10);
mkdirSync(join(ROOT, 'bench/results'), { recursive: true });
const file = arg('out', join(ROOT, `bench/results/peer-${date}.json`));
writeFileSync(file, `${JSON.stringify(report, null, 1)}\n`);
console.log(`wrote ${file}`);
