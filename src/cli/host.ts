/**
 * What the process's main thread (main.ts) hands the command worker (command.ts): the
 * arguments, the shared registry of temporary files, whether stderr is a terminal (a
 * worker's stderr is a pipe to the main thread, so it cannot tell) and when the process
 * started (`--time` counts the whole process).
 */
import { isMainThread, workerData } from 'node:worker_threads';
import { TempRegistry } from './temp-registry.ts';

export interface HostData {
  argv: string[];
  temps: SharedArrayBuffer;
  /** Columns of stderr when it is a terminal, else 0. */
  stderrColumns: number;
  /** performance.timeOrigin of the main thread (ms since the epoch). */
  timeOrigin: number;
}

const host: HostData | undefined = isMainThread ? undefined : (workerData as HostData);

/** The command's temporary files, watched by the main thread (a local one in tests). */
export const temps = new TempRegistry(host?.temps);

/** Columns of stderr when it is a terminal (a progress bar is drawn), else 0. */
export function stderrColumns(): number {
  if (host) return host.stderrColumns;
  return process.stderr.isTTY === true ? process.stderr.columns || 80 : 0;
}

/** Seconds since the process started. */
export function processSeconds(): number {
  const origin = host?.timeOrigin ?? performance.timeOrigin;
  return (performance.timeOrigin + performance.now() - origin) / 1000;
}

export function commandArgv(): string[] {
  return host?.argv ?? process.argv.slice(2);
}
