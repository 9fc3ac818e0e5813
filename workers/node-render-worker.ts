/**
 * worker_threads entry of the command line: claims stripes from the shared
 * counter until none are left, renders all samples of each into the shared
 * film, and reports its counters.
 */
import { parentPort, workerData } from 'node:worker_threads';
import { Film, RenderStats } from '../src/core/index.ts';
import { createTracer, renderStripe, stripeCount, type StripeJob } from './stripes.ts';

interface WorkerInput {
  job: StripeJob;
  spp: number;
  film: SharedArrayBuffer;
  /** Int32Array[0]: next stripe to claim; [1]: stripes finished. */
  counter: SharedArrayBuffer;
}

const { job, spp, film: filmBuffer, counter: counterBuffer } = workerData as WorkerInput;
const tracer = createTracer(job);
const film = new Film(job.width, job.height, filmBuffer);
const counter = new Int32Array(counterBuffer);
const stats = new RenderStats();
const stripes = stripeCount(job.height, job.stripeRows);
for (;;) {
  const stripe = Atomics.add(counter, 0, 1);
  if (stripe >= stripes) break;
  renderStripe(tracer, film, job, stripe, 0, spp, stats);
  Atomics.add(counter, 1, 1);
}
parentPort!.postMessage({ paths: stats.paths, segments: stats.segments, rejected: stats.rejected });
