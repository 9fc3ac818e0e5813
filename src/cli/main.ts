/**
 * The `pathwise` command line. Exit status: 0 on success, 2 with a
 * one-line message for bad arguments or a bad scene, 1 for anything else.
 */
import { readFileSync, statSync } from 'node:fs';
import {
  FilmFileError,
  LIMITS,
  SceneError,
  parseScene,
  validateSettingsOverride,
} from '../core/index.ts';
import { USAGE, UsageError, parseRenderArgs } from './args.ts';
import { merge } from './merge.ts';
import { renderCommand } from './render-command.ts';

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
  await renderCommand(args, scene, settings);
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
    if (command === undefined || command === '--help' || command === 'help') {
      process.stdout.write(USAGE + '\n');
      return command === undefined ? 2 : 0;
    }
    throw new UsageError(
      `unknown command ${JSON.stringify(command)} (try: pathwise render --help)`,
    );
  } catch (e) {
    if (e instanceof UsageError || e instanceof SceneError || e instanceof FilmFileError) {
      process.stderr.write(`pathwise: ${e.message}\n`);
      return 2;
    }
    process.stderr.write(`pathwise: ${(e as Error).stack ?? e}\n`);
    return 1;
  }
}

process.exitCode = await main(process.argv.slice(2));
