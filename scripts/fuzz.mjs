// `npm run fuzz`: the format fuzzer of tests/fuzz/spec (issue 27). Builds the command line
// under test (dist/cli), bundles the fuzzer with esbuild into dist/fuzz (so it runs on plain
// Node, also on a machine with nothing but node and this folder), then runs it.
// FUZZ_SEED, FUZZ_CASES; flags: --jobs N, --failures DIR, --json FILE, --replay DIR.
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { build } from 'esbuild';

const root = fileURLToPath(new URL('..', import.meta.url));
execFileSync(process.execPath, ['scripts/build-cli.mjs'], { cwd: root, stdio: 'inherit' });
mkdirSync(`${root}/dist/fuzz`, { recursive: true });
await build({
  absWorkingDir: root,
  entryPoints: ['tests/fuzz/spec/main.ts'],
  outfile: 'dist/fuzz/spec-fuzz.mjs',
  bundle: true,
  platform: 'node',
  format: 'esm',
  target: 'node20',
  logLevel: 'warning',
});
copyFileSync(`${root}/tests/fuzz/spec/rss-probe.mjs`, `${root}/dist/fuzz/rss-probe.mjs`);
try {
  execFileSync(process.execPath, ['dist/fuzz/spec-fuzz.mjs', ...process.argv.slice(2)], {
    cwd: root,
    stdio: 'inherit',
  });
} catch (e) {
  process.exit(e.status ?? 1);
}
