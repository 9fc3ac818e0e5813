#!/usr/bin/env node
// The CLI is bundled to dist/cli (npm run build:cli). The published package
// ships the bundle; in a source checkout it is built here on first use, so
// the package needs no install-time script.
import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

const entry = new URL('../dist/cli/pathwise.js', import.meta.url);
const builder = new URL('../scripts/build-cli.mjs', import.meta.url);
if (!existsSync(entry) && existsSync(builder)) {
  execFileSync(process.execPath, [fileURLToPath(builder)], {
    stdio: ['ignore', 'ignore', 'inherit'],
  });
}
if (!existsSync(entry)) {
  process.stderr.write('pathwise: the command line is not built; run `npm run build:cli`\n');
  process.exit(1);
}
await import(entry.href);
