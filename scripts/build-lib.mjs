// Builds the npm library: JavaScript into dist/lib (vite.lib.config.ts) and
// type declarations into dist/types (tsconfig.lib.json). dist/types is
// cleared first because tsc never deletes declarations of removed files.
import { execFileSync } from 'node:child_process';
import { rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import { build } from 'vite';

const root = fileURLToPath(new URL('..', import.meta.url));
const require = createRequire(import.meta.url);

await build({
  root,
  configFile: fileURLToPath(new URL('../vite.lib.config.ts', import.meta.url)),
  logLevel: 'warn',
});
rmSync(new URL('../dist/types', import.meta.url), { recursive: true, force: true });
execFileSync(process.execPath, [require.resolve('typescript/bin/tsc'), '-p', 'tsconfig.lib.json'], {
  cwd: root,
  stdio: 'inherit',
});
