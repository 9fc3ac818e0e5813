/**
 * The `pathwise` command line, run in a worker thread by main.ts (which handles signals).
 * Exit status: 0 on success; 2 with one printable line on stderr for bad arguments, a bad
 * or unreadable scene, or an output that cannot be written; 1 for anything else (a bug).
 */
import { availableParallelism } from 'node:os';
import { FilmFileError } from '../core/film/film-file.ts';
import { SceneError, validateSettingsOverride } from '../core/scene/validate/validate.ts';
import { countSkippedTriangles } from '../core/scene/validate/mesh-desc.ts';
import { sceneWarnings } from '../core/scene/validate/warnings.ts';
import { printableLine, quote } from '../core/util/message.ts';
import { DEFAULT_SETTINGS } from '../core/scene/format/types.ts';
import { SYNOPSIS, USAGE, parseRenderArgs, type RenderArgs } from './args.ts';
import { CliError, UsageError } from './errors.ts';
import { commandArgv } from './host.ts';
import { merge } from './merge.ts';
import { renderCommand, renderWorkerUrl } from './render-command.ts';
import type { EarlyWorkers } from './render.ts';
import { loadSceneFile } from './scene-file.ts';
import { flagOf } from './setting-flags.ts';
import { startWarmWorkers } from './warm-up.ts';

async function render(argv: string[]): Promise<void> {
  if (argv.includes('--help')) {
    process.stdout.write(USAGE + '\n');
    return;
  }
  const args = parseRenderArgs(argv);
  // The workers start (and warm up) while the scene is read and compiled.
  const early = startWarmWorkers(args.threads ?? availableParallelism(), renderWorkerUrl(), {
    maxBounces: args.bounces ?? DEFAULT_SETTINGS.maxBounces,
    seed: args.seed,
    estimator: args.estimator,
    sampler: args.sampler,
  });
  try {
    await renderScene(args, early);
  } finally {
    await early.close();
  }
}

async function renderScene(args: RenderArgs, early: EarlyWorkers): Promise<void> {
  const scene = await loadSceneFile(args.scenePath, {
    width: args.width,
    height: args.height,
    allowRead: args.allowRead,
    bare: args.bare,
  });
  for (const w of sceneWarnings(scene)) {
    process.stderr.write(`pathwise: note: ${printableLine(w)}\n`);
  }
  const skipped = countSkippedTriangles(scene);
  if (skipped > 0) {
    process.stderr.write(`pathwise: note: skipped ${skipped} triangles of zero area\n`);
  }
  const settings = validateSettingsOverride(
    scene.settings,
    { width: args.width, height: args.height, maxBounces: args.bounces, spp: args.spp },
    flagOf,
  );
  await renderCommand(args, scene, settings, skipped, early);
}

async function main(argv: string[]): Promise<number> {
  const [command, ...rest] = argv;
  try {
    if (command === 'render') {
      await render(rest);
      return 0;
    }
    if (command === 'merge') {
      await merge(rest);
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
    throw new UsageError(
      `unknown command ${quote(command)} (try: pathwise render --help, pathwise merge --help)`,
    );
  } catch (e) {
    if (e instanceof CliError || e instanceof SceneError || e instanceof FilmFileError) {
      process.stderr.write(`pathwise: ${printableLine(e.message)}\n`);
      return 2;
    }
    process.stderr.write(`pathwise: ${(e as Error).stack ?? e}\n`);
    return 1;
  }
}

process.exitCode = await main(commandArgv());
