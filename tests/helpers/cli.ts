/**
 * Runs the real command line (bin/pathwise.js, bundled by tests/global-setup.ts) the way
 * a careless script would, and watches it: a wall-clock limit (a hang is killed and
 * reported as such), a V8 heap cap, and a watchdog on the resident memory of the process
 * read from /proc (Buffers live outside the V8 heap, so the heap cap alone would not stop
 * a reader that grows without bound). Also the contract every run must meet.
 */
import { spawn } from 'node:child_process';
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { expect } from 'vitest';
import { decodePfm } from '../../src/core/index.ts';
import { ROOT } from './render.ts';

/**
 * The command line under test. PATHWISE_TEST_BIN runs the same tests against another
 * build (e.g. one of an older commit, to see a regression test fail there).
 */
export const BIN = process.env.PATHWISE_TEST_BIN ?? join(ROOT, 'bin/pathwise.js');

export interface CliRun {
  status: number | null;
  signal: NodeJS.Signals | null;
  stdout: string;
  stderr: string;
  /** Why the watchdog killed the process, if it did. */
  killed: 'timeout' | 'memory' | null;
  /** Highest resident memory seen, MiB (sampled every 50 ms). */
  peakRssMiB: number;
  seconds: number;
}

export interface CliOptions {
  /** Bytes written to stdin (then closed); default: stdin closed at once. */
  stdin?: Uint8Array | string;
  /** A shell command whose stdout is piped into the CLI's stdin (e.g. `yes '['`). */
  pipeFrom?: string;
  timeoutMs?: number;
  /** Kill the process when its resident memory passes this (MiB). */
  rssCapMiB?: number;
  /** V8 old-space cap passed to node (MiB). */
  heapMiB?: number;
  cwd?: string;
}

/** Resident memory of a process and all its descendants, MiB (0 once it is gone). */
function treeRssMiB(pid: number): number {
  let kib = 0;
  try {
    const m = /VmRSS:\s+(\d+) kB/.exec(readFileSync(`/proc/${pid}/status`, 'utf8'));
    if (m) kib += Number(m[1]);
    for (const tid of readdirSync(`/proc/${pid}/task`)) {
      const children = readFileSync(`/proc/${pid}/task/${tid}/children`, 'utf8').trim();
      for (const child of children.split(/\s+/).filter(Boolean)) {
        kib += treeRssMiB(Number(child)) * 1024;
      }
    }
  } catch {
    // the process ended between two reads
  }
  return kib / 1024;
}

export function runCli(args: string[], options: CliOptions = {}): Promise<CliRun> {
  const timeoutMs = options.timeoutMs ?? 30_000;
  const rssCap = options.rssCapMiB ?? 1024;
  const node = [`--max-old-space-size=${options.heapMiB ?? 512}`, BIN, ...args];
  const start = performance.now();
  // A pipe from a shell command is a real pipe (Node's own stdio pipes are sockets).
  const child =
    options.pipeFrom === undefined
      ? spawn(process.execPath, node, { cwd: options.cwd ?? ROOT, stdio: 'pipe', detached: true })
      : spawn('bash', ['-c', `${options.pipeFrom} | "$0" "$@"`, process.execPath, ...node], {
          cwd: options.cwd ?? ROOT,
          stdio: 'pipe',
          detached: true,
        });
  // Its own process group (detached), so that a kill reaches every process of a pipeline.
  const killAll = () => {
    try {
      process.kill(-child.pid!, 'SIGKILL');
    } catch {
      // already gone
    }
  };
  let stdout = '';
  let stderr = '';
  child.stdout.setEncoding('utf8').on('data', (d: string) => (stdout += d));
  child.stderr.setEncoding('utf8').on('data', (d: string) => (stderr += d));
  child.stdin.on('error', () => undefined); // the CLI may exit without reading it all
  child.stdin.end(options.stdin ?? '');
  let killed: CliRun['killed'] = null;
  let peak = 0;
  const watch = setInterval(() => {
    const rss = treeRssMiB(child.pid!);
    peak = Math.max(peak, rss);
    if (rss > rssCap && killed === null) {
      killed = 'memory';
      killAll();
    }
  }, 50);
  const timer = setTimeout(() => {
    if (killed === null) killed = 'timeout';
    killAll();
  }, timeoutMs);
  return new Promise((resolve, reject) => {
    child.on('error', reject);
    child.on('close', (status, signal) => {
      clearInterval(watch);
      clearTimeout(timer);
      resolve({
        status,
        signal,
        stdout,
        stderr,
        killed,
        peakRssMiB: peak,
        seconds: (performance.now() - start) / 1000,
      });
    });
  });
}

/** One line of printable ASCII or printable Unicode, no control characters. */
export const PRINTABLE_LINE = /^[^\p{Cc}\p{Cf}\p{Zl}\p{Zp}\p{Co}\p{Cs}]*$/u;

/**
 * The command-line contract: exit 0 having written a finite image, or exit 2 with exactly
 * one printable line on stderr (starting `pathwise: `); never a crash (exit 1, a signal),
 * a hang or unbounded memory. `out` is the --out path of the run, if any.
 */
export function expectContract(r: CliRun, out?: string): void {
  const context = JSON.stringify({ status: r.status, killed: r.killed, stderr: r.stderr });
  expect(r.killed, context).toBeNull();
  expect(r.signal, context).toBeNull();
  expect([0, 2], context).toContain(r.status);
  if (r.status === 2) {
    expectOneLine(r.stderr);
  } else if (out !== undefined && /\.pfm$/i.test(out)) {
    const img = decodePfm(readFileSync(out));
    expect(img.rgb.every(Number.isFinite), context).toBe(true);
  } else if (out !== undefined) {
    expect(readFileSync(out).subarray(1, 4).toString('latin1')).toBe('PNG');
  }
}

/** stderr is exactly one printable line `pathwise: …` ending in a newline. */
export function expectOneLine(stderr: string): void {
  expect(stderr.endsWith('\n'), JSON.stringify(stderr)).toBe(true);
  const lines = stderr.slice(0, -1).split('\n');
  expect(lines, JSON.stringify(stderr)).toHaveLength(1);
  expect(lines[0], JSON.stringify(stderr)).toMatch(/^pathwise: /);
  expect(PRINTABLE_LINE.test(lines[0]), JSON.stringify(stderr)).toBe(true);
}
