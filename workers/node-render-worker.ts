/**
 * worker_threads entry of the command line. For each round the main thread
 * posts ({ s0, s1 }), the worker claims stripes from the shared counter
 * until none are left, adds samples [s0, s1) of each into the shared film,
 * and replies with its counters for the round. The film's sums are exact,
 * so which worker renders which stripe, and in which order, never changes
 * a bit.
 */
import { parentPort, workerData } from 'node:worker_threads';
import { Film, RenderStats } from '../src/core/index.ts';
import { createTracer, renderStripe, stripeCount, type StripeJob } from './stripes.ts';

interface WorkerInput {
  job: StripeJob;
  film: SharedArrayBuffer;
  /** Int32Array[0]: next stripe to claim; [1]: stripes finished (both reset by the main thread per round). */
  counter: SharedArrayBuffer;
}

/** A round: add samples [s0, s1) of every stripe. */
export interface RoundMessage {
  s0: number;
  s1: number;
}

export interface RoundDone {
  paths: number;
  segments: number;
  rejected: number;
}

const { job, film: filmBuffer, counter: counterBuffer } = workerData as WorkerInput;
const tracer = createTracer(job);
const film = new Film(job.width, job.height, filmBuffer);
const counter = new Int32Array(counterBuffer);
const stripes = stripeCount(job.height, job.stripeRows);
parentPort!.on('message', ({ s0, s1 }: RoundMessage) => {
  const stats = new RenderStats();
  for (;;) {
    const stripe = Atomics.add(counter, 0, 1);
    if (stripe >= stripes) break;
    renderStripe(tracer, film, job, stripe, s0, s1, stats);
    Atomics.add(counter, 1, 1);
  }
  const done: RoundDone = {
    paths: stats.paths,
    segments: stats.segments,
    rejected: stats.rejected,
  };
  parentPort!.postMessage(done);
});
