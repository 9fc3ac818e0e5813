/**
 * The `pathwise` process's main thread: it runs the command (command.ts) in a worker
 * thread and does nothing else but wait, so that SIGINT and SIGTERM are handled within
 * milliseconds at every stage of the command, however long its synchronous work (reading
 * a FIFO, parsing a 16 MiB scene, loading a large mesh or model, building a BVH,
 * encoding a large image, merging parts). The handler removes the command's temporary
 * files (temp-registry.ts: recorded in shared memory before each is created) and exits
 * with 130 (SIGINT) or 143 (SIGTERM); earlier outputs and checkpoints are renamed into
 * place whole or not at all, so they stay as they were or loadable.
 *
 * Measured before choosing this (docs/performance.md, "Signals"): cooperative yields
 * would have to reach into every loader, the BVH builder and the encoders, and still
 * leave a long JSON.parse or a synchronous read uninterruptible.
 */
import { Worker } from 'node:worker_threads';
import type { HostData } from './host.ts';
import { TempRegistry } from './temp-registry.ts';

const temps = new TempRegistry();
const data: HostData = {
  argv: process.argv.slice(2),
  temps: temps.buffer,
  stderrColumns: process.stderr.isTTY === true ? process.stderr.columns || 80 : 0,
  timeOrigin: performance.timeOrigin,
};

const sleep = (ms: number) => new Promise<false>((resolve) => setTimeout(resolve, ms, false));

/** Most milliseconds to wait for the command's thread to stop before leaving without it. */
const STOP_MS = 600;

async function onSignal(signal: NodeJS.Signals): Promise<void> {
  temps.removeAll();
  // The command's thread is stopped first (V8 interrupts even a busy loop), then any file
  // it created meanwhile is removed too.
  const stopped = await Promise.race([command.terminate().then(() => true), sleep(STOP_MS)]);
  temps.removeAll();
  if (stopped) process.exit(signal === 'SIGINT' ? 130 : 143);
  // A thread blocked in a read the system cannot cancel (a FIFO nobody writes to, a pipe
  // without data) never stops, and process.exit would wait for it: the process leaves by
  // the signal itself, as it would without a handler (a shell still reports 130 / 143).
  process.removeAllListeners(signal);
  process.kill(process.pid, signal);
}
process.once('SIGINT', onSignal);
process.once('SIGTERM', onSignal);

const command = new Worker(new URL('./command.js', import.meta.url), { workerData: data });
command.on('error', (e) => {
  // A bug that escaped the command's own handling.
  process.stderr.write(`pathwise: ${e.stack ?? e}\n`);
  process.exitCode = 1;
});
command.on('exit', (code) => {
  process.exitCode ||= code;
  process.off('SIGINT', onSignal);
  process.off('SIGTERM', onSignal);
});
