/**
 * A worker_threads entry written in TypeScript, bundled by esbuild into a temporary .mjs
 * that `new Worker(file)` can load (Node runs no TypeScript). Call in beforeAll; `dispose`
 * in afterAll removes the folder.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { build } from 'esbuild';

export async function bundleWorker(
  entry: string,
  name: string,
): Promise<{ file: string; dispose: () => void }> {
  const dir = mkdtempSync(join(tmpdir(), `pathwise-${name}-`));
  const file = join(dir, `${name}.mjs`);
  await build({
    entryPoints: [entry],
    outfile: file,
    bundle: true,
    platform: 'node',
    format: 'esm',
    target: 'node20',
    logLevel: 'warning',
    ignoreAnnotations: true,
  });
  return { file, dispose: () => rmSync(dir, { recursive: true, force: true }) };
}
