/**
 * worker_threads entry of the command line. The worker starts while the main
 * thread is still reading and compiling the scene; it may first get a warm-up
 * ({ type: 'warm' }, warm-up.ts: small built-in scenes traced to nothing, so
 * that V8 has compiled the tracer by the time the real scene comes; it stops
 * as soon as the main thread raises the shared stop word).
 * Then the init message brings the job, the scene the main thread compiled
 * (shared memory, no parsing or BVH build here) and the shared film, round
 * memory and journal; the worker says when it was ready to trace. For
 * each round that follows ({ s0, s1 }) it claims stripes until none are
 * left, adds samples [s0, s1) of each into the shared film through its
 * journal (round-claims.ts: a worker may die anywhere, and its stripes are
 * finished or rendered again by others), and replies with its heap. The
 * film's sums are exact, so which worker renders which stripe, and in
 * which order, never changes a bit; the warm-up touches none of it.
 */
import { getHeapStatistics } from 'node:v8';
import { parentPort, workerData } from 'node:worker_threads';
import { Film } from '../../src/core/film/film.ts';
import type { PathTracer } from '../../src/core/integrator/path-tracer.ts';
import { RenderStats } from '../../src/core/integrator/render-stats.ts';
import { unpackScene, type PackedScene } from '../../src/core/scene/compile/pack.ts';
import {
  claimStripe,
  renderStripeRound,
  roundMemoryFrom,
  type Die,
  type RoundMemory,
} from './round-claims.ts';
import { createTracer, type StripeJob } from './stripes.ts';
import { warmUp, type WarmJob } from './warm-up.ts';

export interface WorkerInput {
  /** This worker's slot. */
  slot: number;
  /**
   * Test hook (RenderPool.crashWorker): per slot, a step of
   * renderStripeRound at which to throw (0: none), read once per stripe.
   */
  faults: SharedArrayBuffer;
  /** One Int32 word, raised (non-zero) when the scene is ready: ends a warm-up. */
  stop: SharedArrayBuffer;
}

/** Warm up (warm-up.ts) for at most `budgetMs`, until `stop` is raised. */
export interface WarmMessage {
  type: 'warm';
  job: WarmJob;
  budgetMs: number;
}

/** Sent once the main thread has compiled the scene (the worker starts before that). */
export interface InitMessage {
  type: 'init';
  job: StripeJob;
  scene: PackedScene;
  film: SharedArrayBuffer;
  /** The round memory's buffers (round-claims.ts roundBuffers). */
  round: SharedArrayBuffer[];
  /** This worker's journal (one stripe of film). */
  journal: SharedArrayBuffer;
  /** An adaptive render's per-pixel rates, filled by the main thread after the pilot; else null. */
  map: SharedArrayBuffer | null;
}

/** A round: add samples [s0, s1) of every stripe. */
export interface RoundMessage {
  type: 'round';
  s0: number;
  s1: number;
}

export interface ReadyReport {
  type: 'ready';
  /** Absolute time (ms since the epoch, sub-millisecond): comparable across threads. */
  readyAt: number;
}

/** The round's counters are summed from its stripes (round-claims.ts), not sent here. */
export interface RoundReport {
  type: 'done';
  heapBytes: number;
}

const input = workerData as WorkerInput;
const faults = new Int32Array(input.faults);
const stop = new Int32Array(input.stop);
let memory: RoundMemory;
let journal: SharedArrayBuffer;
let tracer: PathTracer;
let film: Film;
let job: StripeJob;

parentPort!.on('message', (m: WarmMessage | InitMessage | RoundMessage) => {
  if (m.type === 'warm') {
    warmUp(m.job, m.budgetMs, stop);
    return;
  }
  if (m.type === 'init') {
    job = m.job;
    tracer = createTracer(job, unpackScene(m.scene));
    // Read in place each round: the main thread fills it once the pilot is done (rounds of
    // pilot passes never read it, core/film/adaptive.ts).
    if (m.map !== null) tracer.sampleMap = new Uint8Array(m.map);
    film = new Film(job.width, job.height, m.film, 0, 0, job.aux ?? false);
    memory = roundMemoryFrom(m.round);
    journal = m.journal;
    const ready: ReadyReport = {
      type: 'ready',
      readyAt: performance.timeOrigin + performance.now(),
    };
    parentPort!.postMessage(ready);
    return;
  }
  const stats = new RenderStats();
  for (;;) {
    const stripe = claimStripe(memory, input.slot);
    if (stripe < 0) break;
    const crashAt = Atomics.load(faults, input.slot);
    const die: Die | undefined = crashAt
      ? (step) => {
          if (step !== crashAt) return;
          Atomics.store(faults, input.slot, 0);
          throw new Error(`render worker crashed at step ${step} of a stripe (test hook)`);
        }
      : undefined;
    renderStripeRound(
      memory,
      input.slot,
      tracer,
      film,
      journal,
      job.stripeRows,
      stripe,
      m.s0,
      m.s1,
      stats,
      die,
    );
  }
  const done: RoundReport = { type: 'done', heapBytes: getHeapStatistics().used_heap_size };
  parentPort!.postMessage(done);
});
