/**
 * Starting the render workers early, and warming them up. A short render is mostly
 * cold code: a 1-spp image of the 10,000-sphere field costs about as much as a 4-spp
 * one, because each worker interprets the tracer until V8 has optimised it
 * (docs/performance.md, third round). So the workers start before the scene is read
 * and, while the main thread reads, parses and compiles it, trace small built-in
 * scenes to nothing (workers/node/warm-up.ts) until the real scene is ready (RenderPool
 * raises the stop word) or WARM_BUDGET_MS is spent.
 *
 * A warm-up only pays where a core would otherwise be idle: on the shared 2-core
 * development machine (load average 4–10 from others) it took the main thread's CPU
 * and made the compile as much slower (71 → 129 ms) as it made the first round
 * faster (143 → 94 ms). So only the workers that the idle cores (the cores, less the
 * main thread's, less the 1-minute load average) can hold warm up; the others just
 * start early.
 */
import { availableParallelism, loadavg } from 'node:os';
import type { WarmJob } from '../../workers/node/warm-up.ts';
import { EarlyWorkers } from './render.ts';

/** Longest warm-up (ms): past it a worker waits idle for a scene that takes long to load. */
export const WARM_BUDGET_MS = 100;

/** Workers that can warm up on idle cores, leaving one to the main thread. */
export function warmCount(
  threads: number,
  cores = availableParallelism(),
  load = loadavg()[0],
): number {
  return Math.max(0, Math.min(threads, Math.floor(cores - 1 - load)));
}

/** Starts a render's `threads` workers now, warming up those idle cores can hold. */
export function startWarmWorkers(threads: number, workerUrl: URL, job: WarmJob): EarlyWorkers {
  const warm = warmCount(threads);
  return new EarlyWorkers(
    threads,
    workerUrl,
    warm > 0 ? { type: 'warm', job, budgetMs: WARM_BUDGET_MS } : null,
    warm,
  );
}
