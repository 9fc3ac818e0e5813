/**
 * Running the built command line (tests/global-setup.ts bundles it) as a
 * user does, and small helpers for the batch tests: a temporary folder, a
 * shrunken Cornell box, reading `.film` files.
 */
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { decodeFilmFile, type FilmFile } from '../../src/core/index.ts';
import { ROOT } from './render.ts';

export const BIN = join(ROOT, 'bin/pathwise.js');

export interface RunResult {
  status: number | null;
  stdout: string;
  stderr: string;
}

export function pathwise(args: string[], cwd = ROOT, env?: NodeJS.ProcessEnv): RunResult {
  const r = spawnSync(process.execPath, [BIN, ...args], {
    cwd,
    encoding: 'utf8',
    env: env ?? process.env,
  });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

/** Runs and expects exit status 0; returns the result. */
export function pathwiseOk(args: string[], cwd = ROOT): RunResult {
  const r = pathwise(args, cwd);
  if (r.status !== 0) {
    throw new Error(`pathwise ${args.join(' ')} exited ${r.status}: ${r.stderr}`);
  }
  return r;
}

export function tempDir(prefix: string): string {
  return mkdtempSync(join(tmpdir(), `pathwise-${prefix}-`));
}

/** The Cornell box with other settings (a small image keeps CLI tests fast). */
export function writeCornell(
  dir: string,
  settings: { width: number; height: number; spp: number; maxBounces?: number },
  name = 'scene.json',
): string {
  const scene = JSON.parse(readFileSync(join(ROOT, 'scenes/cornell.json'), 'utf8'));
  scene.settings = { ...scene.settings, ...settings };
  const file = join(dir, name);
  writeFileSync(file, JSON.stringify(scene, null, 2));
  return file;
}

export function readFilm(path: string): FilmFile {
  return decodeFilmFile(readFileSync(path));
}

/** Expects a refusal: exit status 2 and exactly one line on stderr matching `message`. */
export function expectRefusal(r: RunResult, message: RegExp): void {
  const lines = r.stderr.trim().split('\n');
  if (r.status !== 2 || lines.length !== 1 || !message.test(lines[0])) {
    throw new Error(
      `expected exit 2 with one line matching ${message}, got ${r.status}: ${JSON.stringify(r.stderr)}`,
    );
  }
}
