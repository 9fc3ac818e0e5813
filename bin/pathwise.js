#!/usr/bin/env node
// The CLI is bundled to dist/cli (npm run build:cli). The published package
// ships the bundle; in a source checkout it is built here on first use, so
// the package needs no install-time script.
import { execFileSync, spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import { availableParallelism } from 'node:os';
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

/** Worker threads a render will start (what --threads says, else one per core). */
function renderThreads(args) {
  if (args[0] !== 'render') return 0;
  for (let i = 1; i < args.length; i++) {
    if (args[i] === '--threads') return Number(args[i + 1]) || 0;
    if (args[i].startsWith('--threads=')) return Number(args[i].slice(10)) || 0;
  }
  return availableParallelism();
}

// V8's background threads (the optimising compiler, the garbage collector's
// helpers) form one pool per process, four by default, which every worker
// thread shares: past four workers they queue for it. Sized to the cores,
// 16 workers on 16 cores ran 23 % faster (bench/results/device/). Node takes
// the size only on its command line, so a render with more than four
// workers runs in a child started with it; a node started with options of
// its own is left as it is.
const args = process.argv.slice(2);
if (renderThreads(args) > 4 && process.execArgv.length === 0) {
  const child = spawn(
    process.execPath,
    ['--v8-pool-size=0', fileURLToPath(import.meta.url), ...args],
    { stdio: 'inherit' },
  );
  for (const signal of ['SIGINT', 'SIGTERM']) process.on(signal, () => child.kill(signal));
  child.on('exit', (code, signal) => {
    if (signal) {
      // Die of the same signal (our own handler out of the way).
      process.removeAllListeners(signal);
      process.kill(process.pid, signal);
    } else process.exit(code ?? 1);
  });
} else {
  await import(entry.href);
}
