/**
 * The `pathwise` command line. Exit status: 0 on success; 2 with one printable line on
 * stderr for bad arguments, a bad or unreadable scene, or an output that cannot be
 * written; 1 for anything else (a bug).
 */
import { deflateSync } from 'node:zlib';
import {
  SceneError,
  countSkippedTriangles,
  encodePfm,
  encodePng,
  tonemapSums,
  validateSettingsOverride,
} from '../core/index.ts';
import { printableLine, quote } from '../core/scene/message.ts';
import { SYNOPSIS, USAGE, UsageError, parseRenderArgs } from './args.ts';
import { CliError } from './errors.ts';
import { OutputFile } from './output.ts';
import { loadSceneFile } from './scene-file.ts';
import { renderWithWorkers } from './render.ts';

/** Pixels of the image that are not finite (none, unless the film's guard has a bug). */
function countNonFinite(values: Float32Array): number {
  let n = 0;
  for (let i = 0; i < values.length; i++) if (!Number.isFinite(values[i])) n++;
  return n;
}

async function render(argv: string[]): Promise<void> {
  if (argv.includes('--help')) {
    process.stdout.write(USAGE + '\n');
    return;
  }
  const args = parseRenderArgs(argv);
  const scene = await loadSceneFile(args.scenePath);
  const skipped = countSkippedTriangles(scene);
  if (skipped > 0) {
    process.stderr.write(`pathwise: note: skipped ${skipped} triangles of zero area\n`);
  }
  const names: Record<string, string> = {
    width: '--width',
    height: '--height',
    maxBounces: '--bounces',
    spp: '--spp',
  };
  const settings = validateSettingsOverride(
    scene.settings,
    { width: args.width, height: args.height, maxBounces: args.bounces, spp: args.spp },
    (key) => names[key],
  );
  // The output is checked (and its temporary file created) before the render starts.
  const output = await OutputFile.prepare(args.out);
  const abandon = (signal: NodeJS.Signals) => {
    output.discardSync();
    process.exit(signal === 'SIGINT' ? 130 : 143);
  };
  process.once('SIGINT', abandon);
  process.once('SIGTERM', abandon);
  try {
    const tty = process.stderr.isTTY === true;
    const result = await renderWithWorkers({
      scene,
      width: settings.width,
      height: settings.height,
      maxBounces: settings.maxBounces,
      spp: settings.spp,
      seed: args.seed,
      threads: args.threads,
      estimator: args.estimator,
      sampler: args.sampler,
      stripeRows: args.stripeRows,
      workerUrl: new URL('./render-worker.js', import.meta.url),
      onProgress: tty
        ? (f) => process.stderr.write(`\rrendering ${(f * 100).toFixed(0).padStart(3)}%`)
        : undefined,
    });
    if (tty) process.stderr.write('\n');
    const { film, stats, seconds } = result;
    const mean = film.mean();
    // The film rejects every sample that is not finite or would overflow a sum, so this
    // finds nothing; it is the guarantee that no Inf or NaN is ever written silently.
    const bad = countNonFinite(mean);
    if (bad > 0) {
      throw new Error(`${bad} pixel values are not finite; nothing was written`);
    }
    const bytes = /\.pfm$/i.test(args.out)
      ? encodePfm(settings.width, settings.height, mean)
      : (() => {
          const rgba = new Uint8Array(settings.width * settings.height * 4);
          tonemapSums(film.sums, args.exposure, rgba);
          return encodePng(settings.width, settings.height, rgba, (raw) => deflateSync(raw));
        })();
    await output.commit(bytes);
    if (stats.rejected > 0) {
      // Not an error (the image is finite and written), but never silent.
      process.stderr.write(
        `pathwise: warning: ${stats.rejected} of ${stats.paths} samples were not finite ` +
          `(or would have overflowed the film) and were left out\n`,
      );
    }
    if (args.json) {
      process.stdout.write(
        JSON.stringify({
          seconds,
          spp: settings.spp,
          width: settings.width,
          height: settings.height,
          threads: result.threads,
          paths: stats.paths,
          segments: stats.segments,
          mpaths_per_s: stats.paths / seconds / 1e6,
          msegments_per_s: stats.segments / seconds / 1e6,
          rejected_samples: stats.rejected,
          skipped_triangles: skipped,
          compile_seconds: result.compileSeconds,
          first_ready_seconds: result.firstReadySeconds,
          last_ready_seconds: result.lastReadySeconds,
          scene_bytes: result.sceneBytes,
          worker_heap_mb_median: median(result.workerHeapBytes) / 2 ** 20,
        }) + '\n',
      );
    }
  } finally {
    await output.discard();
    process.off('SIGINT', abandon);
    process.off('SIGTERM', abandon);
  }
}

function median(values: number[]): number {
  const v = [...values].sort((a, b) => a - b);
  return v.length === 0 ? NaN : v[v.length >> 1];
}

async function main(argv: string[]): Promise<number> {
  const [command, ...rest] = argv;
  try {
    if (command === 'render') {
      await render(rest);
      return 0;
    }
    if (command === undefined) {
      // Nothing to do: say how to use it, on stderr (stdout may be a pipe into a file).
      throw new UsageError(`no command given; ${SYNOPSIS} (pathwise --help for the options)`);
    }
    if (command === '--help' || command === 'help') {
      process.stdout.write(USAGE + '\n');
      return 0;
    }
    throw new UsageError(`unknown command ${quote(command)} (try: pathwise render --help)`);
  } catch (e) {
    if (e instanceof CliError || e instanceof SceneError) {
      process.stderr.write(`pathwise: ${printableLine(e.message)}\n`);
      return 2;
    }
    process.stderr.write(`pathwise: ${(e as Error).stack ?? e}\n`);
    return 1;
  }
}

process.exitCode = await main(process.argv.slice(2));
