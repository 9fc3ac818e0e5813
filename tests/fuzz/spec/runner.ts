/**
 * Runs one case through the real command line in a child process, in a temporary folder of
 * its own: a wall-clock limit, a watchdog on resident memory (read from /proc every 25 ms,
 * to kill a runaway before it hurts the machine) and the child's own peak RSS
 * (getrusage, reported by rss-probe.mjs at exit). Nothing here imports the project's code.
 */
import { spawn } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { classify, readPfm, type Outcome } from './classify.ts';
import type { FuzzCase } from './cases.ts';

export interface RunOptions {
  /** bin/pathwise.js of the build under test. */
  bin: string;
  /** rss-probe.mjs (a bundle moves it: the campaign passes its own copy). */
  probe?: string;
  timeoutMs: number;
  rssCapMiB: number;
  /** Keep the case folder (for a failure being saved). */
  keep?: boolean;
}

export interface CaseResult {
  id: string;
  format: string;
  variant: string;
  mutation: string;
  outcome: Outcome;
  why: string;
  status: number | null;
  seconds: number;
  rssMiB: number;
  stderr: string;
  dir?: string;
}

/** The flags every case gets: the acceptance's 16×16 at 1 spp, on one render thread. */
export function fullArgs(args: string[]): string[] {
  const out = ['--out', 'out.pfm'];
  return args[0] === 'render'
    ? [...args, '--width', '16', '--height', '16', '--spp', '1', '--threads', '1', ...out]
    : [...args, ...out];
}

export function writeCase(dir: string, c: FuzzCase): void {
  mkdirSync(dir, { recursive: true });
  for (const [name, bytes] of Object.entries(c.files)) {
    mkdirSync(dirname(join(dir, name)), { recursive: true });
    writeFileSync(join(dir, name), bytes);
  }
  writeFileSync(
    join(dir, 'case.json'),
    JSON.stringify(
      {
        id: c.id,
        format: c.format,
        variant: c.variant,
        mutation: c.mutation,
        invalid: c.invalid,
        expect: c.expect,
        lit: c.lit,
        args: c.args,
      },
      null,
      2,
    ) + '\n',
  );
}

function rssMiB(pid: number): number {
  try {
    const m = /VmRSS:\s+(\d+) kB/.exec(readFileSync(`/proc/${pid}/status`, 'utf8'));
    return m ? Number(m[1]) / 1024 : 0;
  } catch {
    return 0;
  }
}

const DEFAULT_PROBE = fileURLToPath(new URL('./rss-probe.mjs', import.meta.url));

export function runCase(c: FuzzCase, o: RunOptions): Promise<CaseResult> {
  const dir = mkdtempSync(join(tmpdir(), 'specfuzz-'));
  writeCase(dir, c);
  const rssFile = join(dir, '.rss');
  const start = performance.now();
  const child = spawn(
    process.execPath,
    ['--import', `file://${o.probe ?? DEFAULT_PROBE}`, o.bin, ...fullArgs(c.args)],
    {
      cwd: dir,
      stdio: ['ignore', 'ignore', 'pipe'],
      env: { ...process.env, SPECFUZZ_RSS_OUT: rssFile, NODE_OPTIONS: '' },
    },
  );
  let stderr = '';
  child.stderr.setEncoding('utf8').on('data', (d: string) => {
    if (stderr.length < 20_000) stderr += d;
  });
  let killed: 'timeout' | 'memory' | null = null;
  let peak = 0;
  const watch = setInterval(() => {
    const rss = rssMiB(child.pid!);
    peak = Math.max(peak, rss);
    if (rss > o.rssCapMiB && !killed) {
      killed = 'memory';
      child.kill('SIGKILL');
    }
  }, 25);
  const timer = setTimeout(() => {
    if (!killed) killed = 'timeout';
    child.kill('SIGKILL');
  }, o.timeoutMs);
  return new Promise((resolve, reject) => {
    child.on('error', reject);
    child.on('close', (status, signal) => {
      const seconds = (performance.now() - start) / 1000;
      clearInterval(watch);
      clearTimeout(timer);
      if (existsSync(rssFile)) peak = Math.max(peak, Number(readFileSync(rssFile, 'utf8')) / 1024);
      const out = join(dir, 'out.pfm');
      const image = status === 0 && existsSync(out) ? readPfm(readFileSync(out)) : null;
      const { outcome, why } = classify({
        status,
        signal: killed ? null : signal,
        killed,
        stderr,
        image,
        lit: c.lit,
        invalid: c.invalid,
        expect: c.expect,
      });
      if (!o.keep) rmSync(dir, { recursive: true, force: true });
      resolve({
        id: c.id,
        format: c.format,
        variant: c.variant,
        mutation: c.mutation,
        outcome,
        why,
        status,
        seconds,
        rssMiB: peak,
        stderr: stderr.slice(0, 2000),
        dir: o.keep ? dir : undefined,
      });
    });
  });
}
