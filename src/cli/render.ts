/**
 * `pathwise render`'s worker pool: compiles the scene once (BVH included)
 * into shared memory, then worker_threads trace stripes into one
 * SharedArrayBuffer film, round by round. A round adds samples [s0, s1) of
 * every pixel; between rounds the main thread may read the film (noise
 * estimate, checkpoint) because no worker is writing it. One round of all
 * samples is the plain render.
 *
 * A worker thread that dies (an uncaught error, out of memory, killed) is
 * replaced in its slot and the round goes on: its stripes are finished from
 * its journal or rendered again (workers/node/round-claims.ts), so the film is
 * bit-identical to an undisturbed render's. Workers that keep dying
 * (DEATH_LIMIT) stop the render with the error, as before.
 */
import { availableParallelism } from 'node:os';
import { Worker } from 'node:worker_threads';
import { Film } from '../core/film/film.ts';
import { buildSampleMap } from '../core/film/adaptive.ts';
import { RenderStats } from '../core/integrator/render-stats.ts';
import { compileScene } from '../core/scene/compile/compile.ts';
import { packScene } from '../core/scene/compile/pack.ts';
import type { Scene } from '../core/scene/format/types.ts';
import type {
  InitMessage,
  ReadyReport,
  RoundMessage,
  RoundReport,
  WarmMessage,
  WorkerInput,
} from '../../workers/node/render-worker.ts';
import {
  addRoundStats,
  recoverSlot,
  roundBuffers,
  roundMemory,
  startRound,
  stripesDone,
  type RoundMemory,
  type RoundRecovery,
} from '../../workers/node/round-claims.ts';
import { testStage } from './test-stages.ts';
import { renderSettingsOf, type RenderSettings } from '../core/scene/format/render-settings.ts';

export interface PoolRequest extends RenderSettings {
  scene: Scene;
  threads?: number;
  stripeRows?: number;
  /** Path of the bundled worker script. */
  workerUrl: URL;
  /** Workers started earlier (EarlyWorkers, warm-up.ts), taken over by the pool; `threads` must match. */
  early?: EarlyWorkers;
  /** Record albedo and normal (the film's aux planes) as well as radiance. */
  aux?: boolean;
}

function spawn(workerUrl: URL, workerData: WorkerInput): Worker {
  return new Worker(workerUrl, { workerData });
}

/**
 * Worker threads started before the scene is read, so that their start-up (a V8
 * isolate each, the worker script) and a warm-up (WarmMessage) overlap the main
 * thread's reading, parsing and compiling; a RenderPool then takes them over. Those
 * it does not take are ended by `close`.
 */
export class EarlyWorkers {
  readonly threads: number;
  readonly faults: SharedArrayBuffer;
  readonly stop = new SharedArrayBuffer(4);
  private readonly workers: (Worker | null)[];
  private readonly exited: boolean[];

  /** Starts `threads` workers; the first `warmCount` get `warm`. */
  constructor(threads: number, workerUrl: URL, warm: WarmMessage | null, warmCount: number) {
    this.threads = threads;
    this.faults = new SharedArrayBuffer(4 * threads);
    this.exited = new Array<boolean>(threads).fill(false);
    this.workers = Array.from({ length: threads }, (_, k) => {
      const w = spawn(workerUrl, { slot: k, faults: this.faults, stop: this.stop });
      // Until taken over: an error or exit is only noted (the pool replaces a dead one).
      w.on('error', () => {});
      w.on('exit', () => (this.exited[k] = true));
      if (warm && k < warmCount) w.postMessage(warm);
      return w;
    });
  }

  /** The worker of slot `k`, if it is still there (then it is the caller's). */
  take(k: number): Worker | null {
    const w = this.workers[k];
    this.workers[k] = null;
    if (w === null || this.exited[k]) return null;
    w.removeAllListeners();
    return w;
  }

  /** Ends the workers not taken. */
  async close(): Promise<void> {
    Atomics.store(new Int32Array(this.stop), 0, 1);
    const left = this.workers.filter((w): w is Worker => w !== null);
    this.workers.fill(null);
    for (const w of left) w.removeAllListeners();
    await Promise.all(left.map((w) => w.terminate()));
  }
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

/** What the pool survived (--json, tests). */
export interface PoolFaults extends RoundRecovery {
  /** Worker threads that died and were replaced. */
  replaced: number;
}

interface Slot {
  worker: Worker;
  journal: SharedArrayBuffer;
  /** A round message is out and its `done` has not come back. */
  inRound: boolean;
  /** The last error the thread reported, for the message should the render stop. */
  lastError: string | null;
  /** Test hook: killWorker ended it; its exit has not come yet. */
  killed: boolean;
}

export class RenderPool {
  readonly film: Film;
  readonly threads: number;
  readonly stripes: number;
  /** Counters of every round so far (summed from the stripes: the same whatever died). */
  readonly stats = new RenderStats();
  /** performance.now() when the workers were started. */
  readonly startedAt: number;
  /** What was survived so far. */
  readonly faults: PoolFaults = { replaced: 0, freed: 0, finished: 0 };
  /** Worker deaths survived at most: 2 per thread + 4 (a worker that always dies stops the render). */
  readonly deathLimit: number;
  private readonly slots: Slot[];
  private readonly memory: RoundMemory;
  private readonly filmBuffer: SharedArrayBuffer;
  /** An adaptive render's per-pixel rates (core/film/adaptive.ts), shared with the workers. */
  private readonly mapBuffer: SharedArrayBuffer | null;
  private readonly faultWords: Int32Array;
  private readonly stopWord: SharedArrayBuffer;
  private readonly stripeRows: number;
  private readonly workerUrl: URL;
  private readonly job: InitMessage['job'];
  private readonly scene: InitMessage['scene'];
  private readonly roundBuffers: SharedArrayBuffer[];
  private readonly compileSeconds: number;
  private readonly sceneBytes: number;
  private readonly readyAt: number[] = [];
  private readonly heapBytes: number[];
  private deaths = 0;
  private round_: RoundMessage | null = null;
  private failure: Error | undefined;
  private pending: ((e?: Error) => void) | undefined;
  private closed = false;

  constructor(req: PoolRequest) {
    const threads = req.threads ?? availableParallelism();
    const early = req.early;
    if (early && early.threads !== threads) {
      throw new Error(`${early.threads} early workers for a pool of ${threads}`);
    }
    // Enough stripes for load balance (~16 per thread), each at least a row.
    const stripeRows = req.stripeRows ?? Math.max(1, Math.floor(req.height / (threads * 16)));
    const aux = req.aux ?? false;
    this.filmBuffer = new SharedArrayBuffer(Film.byteLength(req.width, req.height, aux));
    // Written once here, before any worker reads it: a page a worker first reads is mapped
    // to the kernel's zero page, and its first write then replaces that mapping, which
    // interrupts every other core running this process (a TLB shootdown; costly in a VM).
    // Measured on 2 cores: 5–12 ms per stripe commit of a 1-spp render without this.
    new Uint8Array(this.filmBuffer).fill(0);
    this.film = new Film(req.width, req.height, this.filmBuffer, 0, 0, aux);
    this.mapBuffer = req.adaptive === true ? new SharedArrayBuffer(req.width * req.height) : null;
    this.threads = threads;
    this.stripeRows = stripeRows;
    this.stripes = Math.ceil(req.height / stripeRows);
    this.memory = roundMemory(this.stripes, threads);
    this.roundBuffers = roundBuffers(this.memory);
    this.faultWords = new Int32Array(early?.faults ?? new SharedArrayBuffer(4 * threads));
    this.stopWord = early?.stop ?? new SharedArrayBuffer(4);
    this.heapBytes = new Array<number>(threads).fill(0);
    this.deathLimit = 2 * threads + 4;
    this.workerUrl = req.workerUrl;
    this.startedAt = performance.now();
    // The workers start first (unless they were started earlier still): their
    // start-up (a new V8 isolate each, loading the worker script) overlaps
    // the compilation below.
    this.slots = Array.from({ length: threads }, (_, k) => {
      const worker = early?.take(k) ?? this.spawn(k);
      this.listen(k, worker);
      return {
        worker,
        journal: new SharedArrayBuffer(Film.byteLength(req.width, stripeRows, aux)),
        inRound: false,
        lastError: null,
        killed: false,
      };
    });
    // Compiled once here; every worker maps the same shared buffer. Should that
    // fail, the workers are ended (they would keep the process alive).
    try {
      testStage('compile');
      this.scene = packScene(compileScene(req.scene), true);
    } catch (e) {
      this.closed = true;
      for (const { worker } of this.slots) {
        worker.removeAllListeners();
        void worker.terminate();
      }
      throw e;
    }
    this.compileSeconds = (performance.now() - this.startedAt) / 1000;
    this.sceneBytes = this.scene.buffer.byteLength;
    this.job = { ...renderSettingsOf(req), camera: req.scene.camera, stripeRows, aux };
    // A warm-up in progress ends at its next row.
    Atomics.store(new Int32Array(this.stopWord), 0, 1);
    for (let k = 0; k < threads; k++) this.slots[k].worker.postMessage(this.initFor(k));
  }

  /** The init message of slot `k`: the job, the scene and the shared memory. */
  private initFor(k: number): InitMessage {
    return {
      type: 'init',
      job: this.job,
      scene: this.scene,
      film: this.filmBuffer,
      round: this.roundBuffers,
      journal: this.slots[k].journal,
      map: this.mapBuffer,
    };
  }

  /**
   * An adaptive render: sets every pixel's rate from `pilot`, a film of the uniform
   * pilot passes (core/film/adaptive.ts). Between rounds only: the workers read the
   * map while they render.
   */
  setSampleMap(pilot: Film): void {
    if (this.mapBuffer === null) throw new Error('setSampleMap: the render is not adaptive');
    buildSampleMap(pilot, new Uint8Array(this.mapBuffer));
  }

  /** Starts a worker for slot `k`. */
  private spawn(k: number): Worker {
    return spawn(this.workerUrl, {
      slot: k,
      faults: this.faultWords.buffer as SharedArrayBuffer,
      stop: this.stopWord,
    });
  }

  /** Follows the worker of slot `k`. */
  private listen(k: number, w: Worker): void {
    w.on('error', (e) => {
      const slot = this.slots?.[k];
      if (slot && slot.worker === w) slot.lastError = e.message;
    });
    // The thread is gone for certain once `exit` fires: recover, replace.
    w.on('exit', (code) => this.died(k, w, code));
    w.on('message', (m: ReadyReport | RoundReport) => {
      if (m.type === 'ready') {
        this.readyAt.push(m.readyAt);
        return;
      }
      this.heapBytes[k] = m.heapBytes;
      const slot = this.slots[k];
      if (slot.worker === w) slot.inRound = false;
      this.check();
    });
  }

  private died(k: number, w: Worker, code: number): void {
    const slot = this.slots[k];
    if (this.closed || slot.worker !== w) return;
    this.deaths++;
    // What it held: its published stripe finished, any other claim freed.
    recoverSlot(this.memory, k, this.film, slot.journal, this.stripeRows, this.faults);
    Atomics.store(this.faultWords, k, 0);
    if (this.deaths > this.deathLimit) {
      this.fail(
        new Error(
          `render worker exited with code ${code}${slot.lastError ? ` (${slot.lastError})` : ''}; ` +
            `${this.deaths} worker threads died, so the render stops`,
        ),
      );
      return;
    }
    slot.worker = this.spawn(k);
    this.listen(k, slot.worker);
    slot.lastError = null;
    slot.killed = false;
    slot.inRound = false;
    this.faults.replaced++;
    // Messages are handled in order: the replacement initialises, then joins the round.
    slot.worker.postMessage(this.initFor(k));
    if (this.round_) {
      slot.inRound = true;
      slot.worker.postMessage(this.round_);
    }
    this.check();
  }

  private fail(e: Error): void {
    this.failure ??= e;
    this.pending?.(this.failure);
  }

  /** The round is over once every stripe is done and no worker is still in it. */
  private check(): void {
    if (!this.round_ || !this.pending) return;
    if (this.slots.some((s) => s.inRound)) return;
    if (stripesDone(this.memory) === this.stripes) this.pending();
  }

  /** Stripes finished in the current round (for progress). */
  stripesDone(): number {
    return stripesDone(this.memory);
  }

  /** Adds samples [s0, s1) of every pixel to the film. */
  async round(s0: number, s1: number): Promise<void> {
    if (this.failure) throw this.failure;
    startRound(this.memory);
    const message: RoundMessage = { type: 'round', s0, s1 };
    try {
      await new Promise<void>((resolve, reject) => {
        this.pending = (e) => (e ? reject(e) : resolve());
        this.round_ = message;
        for (const slot of this.slots) {
          slot.inRound = true;
          slot.worker.postMessage(message);
        }
      });
    } finally {
      this.pending = undefined;
      this.round_ = null;
    }
    addRoundStats(this.memory, this.stats);
  }

  /**
   * Test hook, not API: terminates the worker of slot `k` (modulo the
   * thread count) now, wherever it is. It is replaced as any dead worker is.
   * False when that worker was already killed and has not exited yet.
   */
  killWorker(k: number): boolean {
    const slot = this.slots[Math.abs(Math.floor(k)) % this.threads];
    if (slot.killed) return false;
    slot.killed = true;
    void slot.worker.terminate();
    return true;
  }

  /**
   * Test hook, not API: makes the worker of slot `k` throw an uncaught
   * error at step `step` (1–4) of its next stripe (round-claims.ts).
   */
  crashWorker(k: number, step: number): void {
    Atomics.store(this.faultWords, Math.abs(Math.floor(k)) % this.threads, step);
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
    this.closed = true;
    this.failure ??= new Error('render pool closed');
    for (const { worker } of this.slots) worker.removeAllListeners();
    await Promise.all(this.slots.map(({ worker }) => worker.terminate()));
  }
}
