/**
 * `pathwise render`: renders a scene with a pool of worker_threads tracing
 * stripes into one SharedArrayBuffer film, then writes PFM or PNG.
 */
import { availableParallelism } from 'node:os';
import { Worker } from 'node:worker_threads';
import { Film, RenderStats, type Scene } from '../core/index.ts';
import type { StripeJob } from '../../workers/stripes.ts';
import { stripeCount } from '../../workers/stripes.ts';

export interface RenderRequest {
  scene: Scene;
  width: number;
  height: number;
  maxBounces: number;
  spp: number;
  seed: number;
  threads?: number;
  estimator: StripeJob['estimator'];
  sampler: StripeJob['sampler'];
  stripeRows?: number;
  /** Path of the bundled worker script. */
  workerUrl: URL;
  onProgress?: (fraction: number) => void;
}

export interface RenderResult {
  film: Film;
  stats: RenderStats;
  seconds: number;
  threads: number;
}

export async function renderWithWorkers(req: RenderRequest): Promise<RenderResult> {
  const threads = req.threads ?? availableParallelism();
  // Enough stripes for load balance (~16 per thread), each at least a row.
  const stripeRows = req.stripeRows ?? Math.max(1, Math.floor(req.height / (threads * 16)));
  const job: StripeJob = {
    scene: req.scene,
    width: req.width,
    height: req.height,
    maxBounces: req.maxBounces,
    seed: req.seed,
    estimator: req.estimator,
    sampler: req.sampler,
    stripeRows,
  };
  const filmBuffer = new SharedArrayBuffer(Film.byteLength(req.width, req.height));
  const counterBuffer = new SharedArrayBuffer(8);
  const counter = new Int32Array(counterBuffer);
  const stripes = stripeCount(req.height, stripeRows);
  const stats = new RenderStats();
  const start = performance.now();
  const workers = Array.from(
    { length: threads },
    () =>
      new Worker(req.workerUrl, {
        workerData: { job, spp: req.spp, film: filmBuffer, counter: counterBuffer },
      }),
  );
  const timer = req.onProgress
    ? setInterval(() => req.onProgress!(Math.min(1, Atomics.load(counter, 1) / stripes)), 200)
    : undefined;
  try {
    await Promise.all(
      workers.map(
        (w) =>
          new Promise<void>((resolve, reject) => {
            w.once('message', (m: { paths: number; segments: number; rejected: number }) => {
              stats.paths += m.paths;
              stats.segments += m.segments;
              stats.rejected += m.rejected;
            });
            w.once('error', reject);
            w.once('exit', (code) =>
              code === 0 ? resolve() : reject(new Error(`render worker exited with code ${code}`)),
            );
          }),
      ),
    );
  } finally {
    if (timer) clearInterval(timer);
    await Promise.all(workers.map((w) => w.terminate()));
  }
  const seconds = (performance.now() - start) / 1000;
  req.onProgress?.(1);
  return { film: new Film(req.width, req.height, filmBuffer), stats, seconds, threads };
}
