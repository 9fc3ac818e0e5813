/**
 * worker_threads entry of the command line. The first message brings the
 * job and the scene the main thread compiled (shared memory, no parsing or
 * BVH build here); the worker then says when it was ready to trace. For
 * each round that follows ({ s0, s1 }) it claims stripes from the shared
 * counter until none are left, adds samples [s0, s1) of each into the
 * shared film, and replies with its counters for the round and its heap.
 * The film's sums are exact, so which worker renders which stripe, and in
 * which order, never changes a bit.
 */
import { getHeapStatistics } from 'node:v8';
import { parentPort, workerData } from 'node:worker_threads';
import {
  Film,
  RenderStats,
  unpackScene,
  type PackedScene,
  type PathTracer,
} from '../src/core/index.ts';
import { createTracer, renderStripe, stripeCount, type StripeJob } from './stripes.ts';

interface WorkerInput {
  film: SharedArrayBuffer;
  /** Int32Array[0]: next stripe to claim; [1]: stripes finished (both reset by the main thread per round). */
  counter: SharedArrayBuffer;
}

/** Sent once the main thread has compiled the scene (the worker starts before that). */
export interface InitMessage {
  type: 'init';
  job: StripeJob;
  scene: PackedScene;
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

export interface RoundReport {
  type: 'done';
  paths: number;
  segments: number;
  rejected: number;
  heapBytes: number;
}

const { film: filmBuffer, counter: counterBuffer } = workerData as WorkerInput;
const counter = new Int32Array(counterBuffer);
let tracer: PathTracer;
let film: Film;
let job: StripeJob;
let stripes = 0;

parentPort!.on('message', (m: InitMessage | RoundMessage) => {
  if (m.type === 'init') {
    job = m.job;
    tracer = createTracer(job, unpackScene(m.scene));
    film = new Film(job.width, job.height, filmBuffer);
    stripes = stripeCount(job.height, job.stripeRows);
    const ready: ReadyReport = {
      type: 'ready',
      readyAt: performance.timeOrigin + performance.now(),
    };
    parentPort!.postMessage(ready);
    return;
  }
  const stats = new RenderStats();
  for (;;) {
    const stripe = Atomics.add(counter, 0, 1);
    if (stripe >= stripes) break;
    renderStripe(tracer, film, job, stripe, m.s0, m.s1, stats);
    Atomics.add(counter, 1, 1);
  }
  const done: RoundReport = {
    type: 'done',
    paths: stats.paths,
    segments: stats.segments,
    rejected: stats.rejected,
    heapBytes: getHeapStatistics().used_heap_size,
  };
  parentPort!.postMessage(done);
});
