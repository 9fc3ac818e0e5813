/**
 * `pathwise render` once the scene and settings are loaded: the sample
 * range, resume, the round loop with its stop criteria and checkpoints,
 * the output and the JSON line.
 */
import { existsSync } from 'node:fs';
import { LIMITS, type Scene, type SettingsDesc } from '../core/scene/format/types.ts';
import { estimateNoise } from '../core/film/noise.ts';
import { emptyImageMessage } from '../core/integrator/empty-image.ts';
import { formatRanges } from '../core/film/sample-ranges.ts';
import { ADAPTIVE_PILOT } from '../core/film/adaptive.ts';
import type { Film } from '../core/film/film.ts';
import { hasAux, type FilmHeader } from '../core/film/film-file.ts';
import { AuxOutputs } from './aux-output.ts';
import type { RenderArgs } from './args.ts';
import { processSeconds, runBatch, type BatchProgress } from './batch.ts';
import { encodeImage, encodeOutput, isFilmPath } from './encode-output.ts';
import { CliError, UsageError } from './errors.ts';
import { explainMismatch } from './film-compat.ts';
import { filmIdentity, makeHeader, readFilmFile, type FilmIdentity } from './film-file.ts';
import { stderrColumns } from './host.ts';
import { OutputFile } from './output.ts';
import { ProgressBar, type ProgressState } from './progress.ts';
import { showPath } from './read-bounded.ts';
import { RenderPool, type EarlyWorkers } from './render.ts';
import { startTestFaults, TEST_FAULTS_ENV } from './test-faults.ts';
import { testStage } from './test-stages.ts';
import type { RenderSettings } from '../core/scene/format/render-settings.ts';

interface Resumed {
  film: Film;
  end: number;
  stats: FilmHeader['stats'];
}

/** The bundled worker script, beside this bundle (dist/cli). */
export function renderWorkerUrl(): URL {
  return new URL('./render-worker.js', import.meta.url);
}

/** The denoiser's bundled worker script (denoise-pool.ts), beside this bundle. */
export function denoiseWorkerUrl(): URL {
  return new URL('./denoise-worker.js', import.meta.url);
}

export async function renderCommand(
  args: RenderArgs,
  scene: Scene,
  settings: SettingsDesc,
  /** Zero-area triangles the loader skipped (reported in --json). */
  skippedTriangles = 0,
  /** Workers started before the scene was loaded (warm-up.ts), for the pool to take over. */
  early?: EarlyWorkers,
): Promise<void> {
  const b = args.batch;
  const criteria = b.time !== undefined || b.noise !== undefined;
  // With only a stop criterion the render has no total of its own: it may
  // go up to the limit, and the total written is what it reached.
  const openEnded = criteria && args.spp === undefined && b.samples === undefined;
  const total = settings.spp;
  // The render's settings, gathered once from the scene's (with the size and bounce
  // overrides) and the flags, and passed whole from here on.
  const render: RenderSettings = {
    width: settings.width,
    height: settings.height,
    maxBounces: settings.maxBounces,
    seed: args.seed,
    estimator: args.estimator,
    sampler: args.sampler,
    ...(args.adaptive ? { adaptive: true } : {}),
  };
  const [start, end] = b.samples ?? [0, openEnded ? LIMITS.spp : total];
  if (b.samples && end > total) {
    throw new UsageError(
      `--samples ${start}:${end} goes past the render's ${total} samples per pixel (--spp gives the whole render's total)`,
    );
  }
  // The render's identity hashes the whole scene (tens of milliseconds for a
  // large one): made, before the render, only when a `.film` is read or written.
  const identity_ =
    isFilmPath(args.out) ||
    b.checkpoint !== undefined ||
    b.resume !== undefined ||
    b.pilot !== undefined
      ? filmIdentity(scene, render)
      : undefined;
  const identity = (): FilmIdentity => {
    if (identity_ === undefined) throw new Error('a film header without the render identity');
    return identity_;
  };
  const aux = args.aux.aux;
  const resumed = b.resume
    ? await loadCheckpoint(b.resume, identity(), start, end, aux)
    : undefined;
  // Read before the render starts, so that a wrong pilot is refused at once.
  const pilot = b.pilot !== undefined ? loadPilot(b.pilot, identity(), aux) : undefined;
  // Ctrl-C or SIGTERM from here on removes the temporary files (temp-registry.ts).
  // The outputs are checked (the output's temporary file created) before the render starts.
  const output = await OutputFile.prepare(args.out);
  let auxOutputs: AuxOutputs;
  try {
    auxOutputs = await AuxOutputs.prepare(args.aux);
  } catch (e) {
    await output.discard();
    throw e;
  }
  let raw: OutputFile | undefined;
  try {
    raw = args.denoise.raw === undefined ? undefined : await OutputFile.prepare(args.denoise.raw);
  } catch (e) {
    await output.discard();
    await auxOutputs.discard();
    throw e;
  }
  const pool = await startPool(
    {
      discard: async () => {
        await output.discard();
        await auxOutputs.discard();
        await raw?.discard();
      },
    },
    () =>
      new RenderPool({
        ...render,
        scene,
        threads: args.threads,
        stripeRows: args.stripeRows,
        workerUrl: renderWorkerUrl(),
        early,
        aux,
      }),
    b.checkpoint,
  );
  // Test hook (test-faults.ts): worker threads killed during the render.
  const faultSpec = process.env[TEST_FAULTS_ENV];
  const stopFaults = faultSpec ? startTestFaults(pool, faultSpec) : undefined;
  try {
    if (resumed) pool.film.copyRowsFrom(resumed.film);
    const from = resumed?.end ?? start;
    const prior = resumed?.stats ?? { paths: 0, segments: 0, rejected: 0 };
    const header = (n: number, spp: number): FilmHeader =>
      makeHeader(
        identity(),
        spp,
        n > start ? [[start, n]] : [],
        {
          paths: prior.paths + pool.stats.paths,
          segments: prior.segments + pool.stats.segments,
          rejected: prior.rejected + pool.stats.rejected,
        },
        aux,
      );
    const columns = stderrColumns();
    const bar = columns > 0 ? new ProgressBar(process.stderr, columns) : undefined;
    const renderStart = processSeconds();
    const progressState = (p: BatchProgress): ProgressState => ({
      spp: p.at - start,
      sppFrom: from - start,
      sppTarget: end - start,
      elapsed: p.elapsed,
      timeLeft: p.timeLeft,
      noise: p.noise,
      noiseTarget: b.noise,
      noiseSpp: Number.isFinite(p.noiseAt) ? p.noiseAt - start : undefined,
    });
    const pixels = settings.width * settings.height;
    // Adaptive sampling (core/film/adaptive.ts): a film that starts at sample 0 holds the
    // pilot when it reaches it; any other part renders the pilot on its own first.
    const pilotInFilm = render.adaptive === true && start === 0 && from <= ADAPTIVE_PILOT;
    if (render.adaptive === true && !pilotInFilm && end > ADAPTIVE_PILOT && from < end) {
      if (pilot) pool.setSampleMap(pilot);
      else await renderPilot(pool);
    }
    testStage('render');
    const result = await runBatch(
      pool,
      {
        start,
        from,
        end,
        time: b.time,
        noise: b.noise,
        checkpointEvery: b.checkpointEvery,
        pilotAt: pilotInFilm && end > ADAPTIVE_PILOT ? ADAPTIVE_PILOT : undefined,
        // Encoding, writing (with fsync) and exiting, measured on a loaded
        // 2-core machine: 0.15–0.35 s for a 512×512 .film; about 1 µs a
        // pixel covers a .film (68 bytes a pixel), PFM and PNG.
        reserve: 0.1 + pixels * 1e-6,
      },
      {
        checkpoint: b.checkpoint
          ? async (n) => {
              const file = await OutputFile.prepare(b.checkpoint!);
              testStage('checkpoint');
              await file.commit(encodeOutput(b.checkpoint!, pool.film, () => header(n, end), 1));
            }
          : undefined,
        pilot: () => pool.setSampleMap(pool.film),
        progress: bar ? (p: BatchProgress) => bar.update(progressState(p)) : undefined,
      },
    );
    // From starting the workers (compilation overlaps their start-up) to the last round's end.
    const seconds = (performance.now() - pool.startedAt) / 1000;
    const noise = estimateNoise(pool.film);
    bar?.finish(
      progressState({
        at: result.end,
        elapsed: processSeconds() - renderStart,
        noise,
        noiseAt: result.end,
      }),
    );
    const spp = openEnded ? result.end : total;
    // The film rejects every sample that is not finite or out of range, so this finds
    // nothing; it is the guarantee that no Inf or NaN is ever written silently.
    // Every sample dropped: there is no picture to write (issue 27), whatever the
    // exit status of a black image would suggest.
    if (pool.stats.paths > 0 && pool.stats.rejected === pool.stats.paths) {
      throw new CliError(
        `${showPath(args.scenePath)}: ` +
          emptyImageMessage(scene.camera, settings.width, settings.height, pool.stats.rejected),
      );
    }
    const bad = countNonFinite(pool.film.mean());
    if (bad > 0) throw new Error(`${bad} pixel values are not finite; nothing was written`);
    testStage('write');
    const filmHeader = () => header(result.end, spp);
    if (args.denoise.denoise) {
      // Loaded only here: the network, its weights and its worker threads (docs/denoise.md).
      const { denoiseFilm } = await import('./denoise-output.ts');
      const threads = pool.threads;
      await pool.close();
      const denoised = await denoiseFilm(pool.film, threads, denoiseWorkerUrl());
      await raw?.commit(encodeOutput(args.denoise.raw!, pool.film, filmHeader, args.exposure));
      await output.commit(
        encodeImage(args.out, pool.film.width, pool.film.rows, denoised.image, args.exposure),
      );
    } else {
      await output.commit(encodeOutput(args.out, pool.film, filmHeader, args.exposure));
    }
    await auxOutputs.commit(pool.film);
    if (pool.stats.rejected > 0) {
      // Not an error (the image is finite and written), but never silent.
      process.stderr.write(
        `pathwise: warning: ${pool.stats.rejected} of ${pool.stats.paths} samples were not finite ` +
          `(or beyond ±2^40) and were left out\n`,
      );
    }
    if (b.noise !== undefined && result.stop !== 'noise') {
      process.stderr.write(
        `pathwise: stopped by ${result.stop === 'time' ? '--time' : 'the sample count'} at ${result.end - start} spp with noise ${noise.toPrecision(3)}, above the --noise target ${b.noise}\n`,
      );
    }
    if (args.json) {
      const stats = pool.stats;
      const report = pool.report();
      process.stdout.write(
        JSON.stringify({
          seconds,
          spp: result.end - start,
          samples: [start, result.end],
          stopped_by: result.stop,
          noise: Number.isFinite(noise) ? noise : null,
          width: settings.width,
          height: settings.height,
          threads: pool.threads,
          paths: stats.paths,
          segments: stats.segments,
          mpaths_per_s: stats.paths / seconds / 1e6,
          msegments_per_s: stats.segments / seconds / 1e6,
          rejected_samples: stats.rejected,
          skipped_triangles: skippedTriangles,
          compile_seconds: report.compileSeconds,
          first_ready_seconds: report.firstReadySeconds,
          last_ready_seconds: report.lastReadySeconds,
          scene_bytes: report.sceneBytes,
          worker_heap_mb_median: median(report.workerHeapBytes) / 2 ** 20,
          resumed_from: resumed ? resumed.end : null,
          checkpoints: result.checkpoints,
          // Worker threads that died and were replaced; their stripes were
          // rendered again, or finished from their journals.
          workers_replaced: pool.faults.replaced,
          stripes_rendered_again: pool.faults.freed,
          stripes_finished_from_journal: pool.faults.finished,
        }) + '\n',
      );
    }
  } finally {
    stopFaults?.();
    await pool.close();
    await output.discard();
    await auxOutputs.discard();
    await raw?.discard();
  }
}

/**
 * Checks the checkpoint's place and starts the pool (compiling the scene); should either
 * fail, the output's temporary file is removed before the error goes on.
 */
async function startPool(
  output: Pick<OutputFile, 'discard'>,
  start: () => RenderPool,
  checkpoint: string | undefined,
): Promise<RenderPool> {
  try {
    if (checkpoint) await (await OutputFile.prepare(checkpoint)).discard();
    return start();
  } catch (e) {
    await output.discard();
    throw e;
  }
}

/**
 * The sample map of an adaptive part that does not start at sample 0, or of a resumed
 * render past the pilot: the pilot passes [0, ADAPTIVE_PILOT) are rendered into the
 * cleared film, the map built from them, and the film and its counters put back as
 * they were. Every part so builds the same map (the pilot's samples are the same bits
 * wherever they are traced), and none of the pilot's samples stays in this part.
 */
async function renderPilot(pool: RenderPool): Promise<void> {
  const bytes = new Uint8Array(pool.film.buffer);
  const saved = bytes.slice();
  const stats = { ...pool.stats };
  pool.film.clear();
  await pool.round(0, ADAPTIVE_PILOT);
  pool.setSampleMap(pool.film);
  bytes.set(saved);
  Object.assign(pool.stats, stats);
}

/**
 * `--pilot FILE.film`: the pilot of the same render (settings and key equal, albedo and
 * normal alike, samples exactly [0, ADAPTIVE_PILOT)), whose map is the one every part builds.
 */
function loadPilot(path: string, identity: FilmIdentity, aux: boolean): Film {
  const { header, film } = readFilmFile(path);
  const why = otherRender(path, header, identity, aux);
  if (why) throw new CliError(`cannot use the pilot: ${why}`);
  const r = header.ranges;
  if (r.length !== 1 || r[0][0] !== 0 || r[0][1] !== ADAPTIVE_PILOT) {
    throw new CliError(
      `cannot use the pilot: ${showPath(path)} holds samples ${formatRanges(r)}, not the pilot [0, ${ADAPTIVE_PILOT}) (render it with --samples 0:${ADAPTIVE_PILOT})`,
    );
  }
  return film;
}

function median(values: number[]): number {
  const v = [...values].sort((a, b) => a - b);
  return v.length === 0 ? NaN : v[v.length >> 1];
}

/** Pixels of the image that are not finite (none, unless the film's guard has a bug). */
function countNonFinite(values: Float32Array): number {
  let n = 0;
  for (let i = 0; i < values.length; i++) if (!Number.isFinite(values[i])) n++;
  return n;
}

/**
 * Why the film at `path` is not of this render (its identity, or albedo and normal where
 * this render records them or not), or null: what a checkpoint and a pilot must both be.
 */
function otherRender(
  path: string,
  header: FilmHeader,
  identity: FilmIdentity,
  aux: boolean,
): string | null {
  const why = explainMismatch(showPath(path), header, 'this render', identity);
  if (why) return why;
  if (hasAux(header) === aux) return null;
  return `${showPath(path)} ${aux ? 'holds no albedo and normal (it was rendered without --aux), and this render records them' : 'holds albedo and normal (rendered with --aux), and this render does not record them: add --aux'}`;
}

/**
 * The checkpoint to continue from: a film of the same render holding
 * samples [start, n) with n ≤ end. A missing file means no checkpoint was
 * written yet, so the same command line serves for the first run and for
 * every retry.
 */
async function loadCheckpoint(
  path: string,
  identity: FilmIdentity,
  start: number,
  end: number,
  aux: boolean,
): Promise<Resumed | undefined> {
  if (!existsSync(path)) {
    process.stderr.write(
      `pathwise: no checkpoint at ${showPath(path)} yet; starting from sample ${start}\n`,
    );
    return undefined;
  }
  const { header, film } = readFilmFile(path);
  const why = otherRender(path, header, identity, aux);
  if (why) throw new CliError(`cannot resume: ${why}`);
  const r = header.ranges;
  if (r.length === 0) return { film, end: start, stats: header.stats };
  if (r.length !== 1 || r[0][0] !== start) {
    throw new CliError(
      `cannot resume: ${showPath(path)} holds samples ${formatRanges(r)}, not one range starting at ${start}`,
    );
  }
  if (r[0][1] > end) {
    throw new CliError(
      `cannot resume: ${showPath(path)} holds samples ${formatRanges(r)}, past this render's end at ${end}`,
    );
  }
  return { film, end: r[0][1], stats: header.stats };
}
