/**
 * worker_threads entry of the command line: unpacks the scene the main
 * thread compiled (shared memory, no parsing or BVH build here), claims
 * stripes from the shared counter until none are left, renders all samples
 * of each into the shared film, and reports its counters, when it was
 * ready to trace and its heap.
 */
import { getHeapStatistics } from 'node:v8';
import { parentPort, workerData } from 'node:worker_threads';
import { Film, RenderStats, unpackScene, type PackedScene } from '../src/core/index.ts';
import { createTracer, renderStripe, stripeCount, type StripeJob } from './stripes.ts';

interface WorkerInput {
  film: SharedArrayBuffer;
  /** Int32Array[0]: next stripe to claim; [1]: stripes finished. */
  counter: SharedArrayBuffer;
}

/** Sent once the main thread has compiled the scene (the worker starts before that). */
interface RenderMessage {
  job: StripeJob;
  scene: PackedScene;
  spp: number;
}

const { film: filmBuffer, counter: counterBuffer } = workerData as WorkerInput;
parentPort!.once('message', ({ job, scene, spp }: RenderMessage) => {
  const tracer = createTracer(job, unpackScene(scene));
  const film = new Film(job.width, job.height, filmBuffer);
  const counter = new Int32Array(counterBuffer);
  const stats = new RenderStats();
  const stripes = stripeCount(job.height, job.stripeRows);
  // Absolute time (ms since the epoch, sub-millisecond): comparable across threads.
  const readyAt = performance.timeOrigin + performance.now();
  for (;;) {
    const stripe = Atomics.add(counter, 0, 1);
    if (stripe >= stripes) break;
    renderStripe(tracer, film, job, stripe, 0, spp, stats);
    Atomics.add(counter, 1, 1);
  }
  const heap = getHeapStatistics();
  parentPort!.postMessage({
    paths: stats.paths,
    segments: stats.segments,
    rejected: stats.rejected,
    readyAt,
    heapBytes: heap.used_heap_size,
    externalBytes: heap.external_memory,
  });
  // Nothing else keeps this thread: it exits once the message is out.
  parentPort!.close();
});
