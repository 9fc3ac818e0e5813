/**
 * `pathwise render`'s worker pool: compiles the scene once (BVH included)
 * into shared memory, then worker_threads trace stripes into one
 * SharedArrayBuffer film, round by round. A round adds samples [s0, s1) of
 * every pixel; between rounds the main thread may read the film (noise
 * estimate, checkpoint) because no worker is writing it. One round of all
 * samples is the plain render.
 */
import { availableParallelism } from 'node:os';
import { Worker } from 'node:worker_threads';
import { Film, RenderStats, compileScene, packScene, type Scene } from '../core/index.ts';
import type { StripeJob } from '../../workers/stripes.ts';
import { stripeCount } from '../../workers/stripes.ts';
import type {
  InitMessage,
  ReadyReport,
  RoundMessage,
  RoundReport,
} from '../../workers/node-render-worker.ts';

export interface PoolRequest {
  scene: Scene;
  width: number;
  height: number;
  maxBounces: number;
  seed: number;
  threads?: number;
  estimator: StripeJob['estimator'];
  sampler: StripeJob['sampler'];
  stripeRows?: number;
  /** Path of the bundled worker script. */
  workerUrl: URL;
}

/** What the pool measured about itself (for --json and the benchmarks). */
export interface PoolReport {
  /** Compiling the scene and building its BVH, once, on the main thread. */
  compileSeconds: number;
  /** From starting the workers to the first / last one ready to trace. */
  firstReadySeconds: number;
  lastReadySeconds: number;
  /** Bytes of the packed scene, shared by every worker. */
  sceneBytes: number;
  /** Per worker: its V8 heap in use after its last round (the shared scene and film are not in it). */
  workerHeapBytes: number[];
}

export class RenderPool {
  readonly film: Film;
  readonly threads: number;
  readonly stripes: number;
  /** Counters of every round so far. */
  readonly stats = new RenderStats();
  /** performance.now() when the workers were started. */
  readonly startedAt: number;
  private readonly workers: Worker[];
  private readonly counter: Int32Array;
  private readonly compileSeconds: number;
  private readonly sceneBytes: number;
  private readonly readyAt: number[] = [];
  private readonly heapBytes: number[];
  private failure: Error | undefined;
  private pending: ((e?: Error) => void) | undefined;

  constructor(req: PoolRequest) {
    const threads = req.threads ?? availableParallelism();
    // Enough stripes for load balance (~16 per thread), each at least a row.
    const stripeRows = req.stripeRows ?? Math.max(1, Math.floor(req.height / (threads * 16)));
    const filmBuffer = new SharedArrayBuffer(Film.byteLength(req.width, req.height));
    const counterBuffer = new SharedArrayBuffer(8);
    this.film = new Film(req.width, req.height, filmBuffer);
    this.counter = new Int32Array(counterBuffer);
    this.threads = threads;
    this.stripes = stripeCount(req.height, stripeRows);
    this.heapBytes = new Array<number>(threads).fill(0);
    this.startedAt = performance.now();
    // The workers start first: their start-up (a new V8 isolate each, loading
    // the worker script) overlaps the compilation below.
    this.workers = Array.from(
      { length: threads },
      () => new Worker(req.workerUrl, { workerData: { film: filmBuffer, counter: counterBuffer } }),
    );
    this.workers.forEach((w, k) => {
      const fail = (e: Error) => {
        this.failure ??= e;
        this.pending?.(this.failure);
      };
      w.on('error', fail);
      w.on('exit', (code) => fail(new Error(`render worker exited with code ${code}`)));
      w.on('message', (m: ReadyReport | RoundReport) => {
        if (m.type === 'ready') {
          this.readyAt.push(m.readyAt);
          return;
        }
        this.stats.paths += m.paths;
        this.stats.segments += m.segments;
        this.stats.rejected += m.rejected;
        this.heapBytes[k] = m.heapBytes;
        this.pending?.();
      });
    });
    // Compiled once here; every worker maps the same shared buffer.
    const scene = packScene(compileScene(req.scene), true);
    this.compileSeconds = (performance.now() - this.startedAt) / 1000;
    this.sceneBytes = scene.buffer.byteLength;
    const init: InitMessage = {
      type: 'init',
      job: {
        camera: req.scene.camera,
        width: req.width,
        height: req.height,
        maxBounces: req.maxBounces,
        seed: req.seed,
        estimator: req.estimator,
        sampler: req.sampler,
        stripeRows,
      },
      scene,
    };
    for (const w of this.workers) w.postMessage(init);
  }

  /** Stripes finished in the current round (for progress). */
  stripesDone(): number {
    return Math.min(this.stripes, Atomics.load(this.counter, 1));
  }

  /** Adds samples [s0, s1) of every pixel to the film. */
  async round(s0: number, s1: number): Promise<void> {
    if (this.failure) throw this.failure;
    Atomics.store(this.counter, 0, 0);
    Atomics.store(this.counter, 1, 0);
    let left = this.workers.length;
    try {
      await new Promise<void>((resolve, reject) => {
        this.pending = (e) => (e ? reject(e) : --left === 0 && resolve());
        const message: RoundMessage = { type: 'round', s0, s1 };
        for (const w of this.workers) w.postMessage(message);
      });
    } finally {
      this.pending = undefined;
    }
  }

  report(): PoolReport {
    const origin = performance.timeOrigin + this.startedAt;
    const ready = this.readyAt.map((t) => (t - origin) / 1000);
    return {
      compileSeconds: this.compileSeconds,
      firstReadySeconds: ready.length > 0 ? Math.min(...ready) : NaN,
      lastReadySeconds: ready.length > 0 ? Math.max(...ready) : NaN,
      sceneBytes: this.sceneBytes,
      workerHeapBytes: [...this.heapBytes],
    };
  }

  async close(): Promise<void> {
    this.failure ??= new Error('render pool closed');
    for (const w of this.workers) w.removeAllListeners();
    await Promise.all(this.workers.map((w) => w.terminate()));
  }
}
