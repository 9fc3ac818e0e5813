/**
 * `pathwise render`: compiles the scene once (BVH included) into shared
 * memory, then renders it with a pool of worker_threads tracing stripes
 * into one SharedArrayBuffer film; the caller writes PFM or PNG.
 */
import { availableParallelism } from 'node:os';
import { Worker } from 'node:worker_threads';
import { Film, RenderStats, compileScene, packScene, type Scene } from '../core/index.ts';
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
  /** From starting the workers (compilation overlaps their start-up) to the last one finished. */
  seconds: number;
  threads: number;
  /** Compiling the scene and building its BVH, once, on the main thread. */
  compileSeconds: number;
  /** From starting the workers to the first / last one ready to trace. */
  firstReadySeconds: number;
  lastReadySeconds: number;
  /** Bytes of the packed scene, shared by every worker. */
  sceneBytes: number;
  /** Per worker: its V8 heap in use at the end (the shared scene and film are not in it). */
  workerHeapBytes: number[];
}

interface WorkerReport {
  paths: number;
  segments: number;
  rejected: number;
  readyAt: number;
  heapBytes: number;
  externalBytes: number;
}

export async function renderWithWorkers(req: RenderRequest): Promise<RenderResult> {
  const threads = req.threads ?? availableParallelism();
  // Enough stripes for load balance (~16 per thread), each at least a row.
  const stripeRows = req.stripeRows ?? Math.max(1, Math.floor(req.height / (threads * 16)));
  const filmBuffer = new SharedArrayBuffer(Film.byteLength(req.width, req.height));
  const counterBuffer = new SharedArrayBuffer(8);
  const counter = new Int32Array(counterBuffer);
  const stripes = stripeCount(req.height, stripeRows);
  const stats = new RenderStats();
  const start = performance.now();
  const startedAt = performance.timeOrigin + start;
  // The workers start first: their start-up (a new V8 isolate each, loading
  // the worker script) overlaps the compilation below.
  const workers = Array.from(
    { length: threads },
    () => new Worker(req.workerUrl, { workerData: { film: filmBuffer, counter: counterBuffer } }),
  );
  // Compiled once here; every worker maps the same shared buffer.
  const scene = packScene(compileScene(req.scene), true);
  const compileSeconds = (performance.now() - start) / 1000;
  const job: StripeJob = {
    camera: req.scene.camera,
    width: req.width,
    height: req.height,
    maxBounces: req.maxBounces,
    seed: req.seed,
    estimator: req.estimator,
    sampler: req.sampler,
    stripeRows,
  };
  for (const w of workers) w.postMessage({ job, scene, spp: req.spp });
  const timer = req.onProgress
    ? setInterval(() => req.onProgress!(Math.min(1, Atomics.load(counter, 1) / stripes)), 200)
    : undefined;
  const reports: WorkerReport[] = [];
  try {
    await Promise.all(
      workers.map(
        (w) =>
          new Promise<void>((resolve, reject) => {
            w.once('message', (m: WorkerReport) => {
              stats.paths += m.paths;
              stats.segments += m.segments;
              stats.rejected += m.rejected;
              reports.push(m);
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
  const ready = reports.map((r) => (r.readyAt - startedAt) / 1000);
  return {
    film: new Film(req.width, req.height, filmBuffer),
    stats,
    seconds,
    threads,
    compileSeconds,
    firstReadySeconds: Math.min(...ready),
    lastReadySeconds: Math.max(...ready),
    sceneBytes: scene.buffer.byteLength,
    workerHeapBytes: reports.map((r) => r.heapBytes),
  };
}
