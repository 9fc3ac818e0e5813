/**
 * Starting the render workers early, and warming them up. A short render is mostly
 * cold code: a 1-spp image of the 10,000-sphere field costs about as much as a 4-spp
 * one, because each worker interprets the tracer until V8 has optimised it
 * (docs/performance.md, third round). So the workers start before the scene is read
 * and, while the main thread reads, parses and compiles it, trace small built-in
 * scenes to nothing (workers/warm-up.ts) until the real scene is ready (RenderPool
 * raises the stop word) or WARM_BUDGET_MS is spent. Only as many workers warm up as
 * leave a core to the main thread, whose work is on the critical path.
 */
import { availableParallelism } from 'node:os';
import type { WarmJob } from '../../workers/warm-up.ts';
import { EarlyWorkers } from './render.ts';

/** Longest warm-up (ms): past it a worker waits idle for a scene that takes long to load. */
export const WARM_BUDGET_MS = 100;

/** Starts a render's `threads` workers now, warming up those a core is left for. */
export function startWarmWorkers(threads: number, workerUrl: URL, job: WarmJob): EarlyWorkers {
  const warmCount = Math.min(threads, availableParallelism() - 1);
  return new EarlyWorkers(
    threads,
    workerUrl,
    warmCount > 0 ? { type: 'warm', job, budgetMs: WARM_BUDGET_MS } : null,
    warmCount,
  );
}
