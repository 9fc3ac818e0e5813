#!/usr/bin/env node
// The CLI is bundled to dist/cli by `npm run build:cli` (run by `npm ci` through "prepare").
import { existsSync } from 'node:fs';

const entry = new URL('../dist/cli/pathwise.js', import.meta.url);
if (!existsSync(entry)) {
  process.stderr.write('pathwise: the command line is not built yet; run `npm run build:cli`\n');
  process.exit(1);
}
await import(entry.href);
