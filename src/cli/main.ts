/**
 * The `pathwise` command line. Exit status: 0 on success, 2 with a
 * one-line message for bad arguments or a bad scene, 1 for anything else.
 */
import { readFileSync, statSync, writeFileSync } from 'node:fs';
import { deflateSync } from 'node:zlib';
import {
  LIMITS,
  SceneError,
  encodePfm,
  encodePng,
  parseScene,
  tonemapSums,
  validateSettingsOverride,
} from '../core/index.ts';
import { USAGE, UsageError, parseRenderArgs } from './args.ts';
import { renderWithWorkers } from './render.ts';

async function render(argv: string[]): Promise<void> {
  if (argv.includes('--help')) {
    process.stdout.write(USAGE + '\n');
    return;
  }
  const args = parseRenderArgs(argv);
  let text: string;
  try {
    const size = statSync(args.scenePath).size;
    if (size > LIMITS.fileBytes) {
      throw new UsageError(
        `${args.scenePath}: scene file is ${size} bytes, more than the limit of ${LIMITS.fileBytes}`,
      );
    }
    text = readFileSync(args.scenePath, 'utf8');
  } catch (e) {
    if (e instanceof UsageError) throw e;
    throw new UsageError(`cannot read ${args.scenePath}: ${(e as Error).message}`);
  }
  const scene = parseScene(text);
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
  const bytes = /\.pfm$/i.test(args.out)
    ? encodePfm(settings.width, settings.height, film.mean())
    : (() => {
        const rgba = new Uint8Array(settings.width * settings.height * 4);
        tonemapSums(film.sums, args.exposure, rgba);
        return encodePng(settings.width, settings.height, rgba, (raw) => deflateSync(raw));
      })();
  writeFileSync(args.out, bytes);
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
        compile_seconds: result.compileSeconds,
        first_ready_seconds: result.firstReadySeconds,
        last_ready_seconds: result.lastReadySeconds,
        scene_bytes: result.sceneBytes,
        worker_heap_mb_median: median(result.workerHeapBytes) / 2 ** 20,
      }) + '\n',
    );
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
    if (command === undefined || command === '--help' || command === 'help') {
      process.stdout.write(USAGE + '\n');
      return command === undefined ? 2 : 0;
    }
    throw new UsageError(
      `unknown command ${JSON.stringify(command)} (try: pathwise render --help)`,
    );
  } catch (e) {
    if (e instanceof UsageError || e instanceof SceneError) {
      process.stderr.write(`pathwise: ${e.message}\n`);
      return 2;
    }
    process.stderr.write(`pathwise: ${(e as Error).stack ?? e}\n`);
    return 1;
  }
}

process.exitCode = await main(process.argv.slice(2));
