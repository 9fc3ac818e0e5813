/**
 * `pathwise render`'s worker pool: worker_threads trace stripes into one
 * SharedArrayBuffer film, round by round. A round adds samples [s0, s1) of
 * every pixel; between rounds the main thread may read the film (noise
 * estimate, checkpoint) because no worker is writing it. One round of all
 * samples is the plain render.
 */
import { availableParallelism } from 'node:os';
import { Worker } from 'node:worker_threads';
import { Film, RenderStats, type Scene } from '../core/index.ts';
import type { StripeJob } from '../../workers/stripes.ts';
import { stripeCount } from '../../workers/stripes.ts';
import type { RoundDone, RoundMessage } from '../../workers/node-render-worker.ts';

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

export class RenderPool {
  readonly film: Film;
  readonly threads: number;
  readonly stripes: number;
  /** Counters of every round so far. */
  readonly stats = new RenderStats();
  private readonly workers: Worker[];
  private readonly counter: Int32Array;
  private failure: Error | undefined;
  private pending: ((e?: Error) => void) | undefined;

  constructor(req: PoolRequest) {
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
    this.film = new Film(req.width, req.height, filmBuffer);
    this.counter = new Int32Array(counterBuffer);
    this.threads = threads;
    this.stripes = stripeCount(req.height, stripeRows);
    this.workers = Array.from(
      { length: threads },
      () =>
        new Worker(req.workerUrl, {
          workerData: { job, film: filmBuffer, counter: counterBuffer },
        }),
    );
    for (const w of this.workers) {
      const fail = (e: Error) => {
        this.failure ??= e;
        this.pending?.(this.failure);
      };
      w.on('error', fail);
      w.on('exit', (code) => fail(new Error(`render worker exited with code ${code}`)));
    }
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
    await new Promise<void>((resolve, reject) => {
      this.pending = (e) => (e ? reject(e) : --left === 0 && resolve());
      const message: RoundMessage = { s0, s1 };
      for (const w of this.workers) {
        w.once('message', (m: RoundDone) => {
          this.stats.paths += m.paths;
          this.stats.segments += m.segments;
          this.stats.rejected += m.rejected;
          this.pending?.();
        });
        w.postMessage(message);
      }
    });
    this.pending = undefined;
  }

  async close(): Promise<void> {
    this.failure ??= new Error('render pool closed');
    for (const w of this.workers) w.removeAllListeners();
    await Promise.all(this.workers.map((w) => w.terminate()));
  }
}
