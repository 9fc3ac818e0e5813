/**
 * The page's one pool of render workers, shared by every controller on it
 * (the demo's canvas, any number of <pathwise-view> elements): the machine
 * has a fixed number of cores, and two pools would only fight over them.
 *
 * Each controller registers as a client with its own job id. In shared
 * mode the workers pull work from the client's control block themselves
 * and the pool only forwards configurations and wake-ups. In transfer mode
 * the pool is the scheduler: whenever a worker is free it asks the clients
 * in turn for a task and posts it on that worker's task port.
 *
 * Workers die: an uncaught error, the browser reclaiming memory, the test
 * hook. The pool notices (an `error` event after start-up, or the worker's
 * life lock — a Web Lock it holds while it lives — being granted to the
 * pool; an `exit` event where a stand-in for Worker has one), starts a
 * replacement at once, and, once the death is certain,
 * lets each client hand the dead worker's claims to the living
 * (workers/browser/shared-claims.ts) — or, in transfer mode, sends the stripe it
 * held out again. A worker that fails to start (a bad URL, a CSP) is not
 * replaced: that is reported as an `error` event, as before. Workers that
 * keep crashing are not replaced for ever either (CRASH_LIMIT).
 *
 * Nothing here touches the DOM or creates a worker at import time.
 */
import * as Comlink from 'comlink';
import {
  MAX_SLOTS,
  type JobConfig,
  type StripeResult,
  type StripeTask,
} from '../../workers/browser/render-protocol.ts';
import {
  CRASH_WINDOW_MS,
  CrashWindow,
  createWorker,
  defaultWorkerCount,
  newPoolWorker,
  type PoolWorker,
  type WorkerSource,
} from './pool-worker.ts';
import { faults, markDead, newWorkerToken } from './worker-deaths.ts';

export type { WorkerSource } from './pool-worker.ts';

/**
 * Without Web Locks a death cannot be confirmed, only waited out: Chromium
 * stops a terminated worker that is busy within two seconds.
 */
const DEATH_GRACE_MS = 3000;
/** Pause before trying a recovery again when a film's lock stayed busy. */
const RECOVERY_RETRY_MS = 20;
/** Names the page's life locks apart from other tabs' (Web Locks are per origin). */
const PAGE_ID = Math.random().toString(36).slice(2);

export interface PoolClient {
  readonly id: number;
  /** The job's current configuration (the scene included; the pool strips it when it can). */
  config(): JobConfig;
  /** Transfer mode: the next stripe pass to render, or null. */
  nextTask(): StripeTask | null;
  onResult(result: StripeResult): void;
  onWorkerError(message: string): void;
  /** Transfer mode: the worker holding `task` died before answering. */
  onTaskLost(task: StripeTask): void;
  /**
   * Shared mode: workers are known dead (worker-deaths.ts); hand on what
   * they held. False when a film's lock stayed busy: asked again shortly.
   */
  recover(): boolean;
}

export class WorkerPool {
  private readonly workers: PoolWorker[] = [];
  private readonly clients = new Map<number, PoolClient>();
  private readonly source: WorkerSource;
  private turn = 0;
  private target: number;
  /** Slots in use, by live workers and by dead ones not yet recovered from. */
  private readonly slots = new Uint8Array(MAX_SLOTS);
  private readonly crashes = new CrashWindow(CRASH_WINDOW_MS);
  /** Workers crashed too often: no more replacements. */
  private halted = false;
  /** Why workers could not start here, once that was reported (see failToStart). */
  private startFailure: string | null = null;
  private closed = false;

  constructor(source: WorkerSource, size?: number) {
    this.source = source;
    this.target = size ?? defaultWorkerCount();
  }

  get size(): number {
    return this.target;
  }

  register(client: PoolClient): void {
    const failure = this.startFailure;
    if (failure !== null && !this.clients.has(client.id)) {
      queueMicrotask(() => client.onWorkerError(failure));
    }
    this.clients.set(client.id, client);
    void this.resize();
  }

  unregister(client: PoolClient): void {
    this.clients.delete(client.id);
    for (const w of this.workers) {
      void w.api.removeJob(client.id).catch(() => {});
      w.sceneIds.delete(client.id);
      w.acked.delete(client.id);
    }
  }

  get empty(): boolean {
    return this.clients.size === 0;
  }

  /** Sends a client's configuration to every worker (the scene only where it is new). */
  configure(client: PoolClient): void {
    for (const w of this.workers) if (!w.retiring && !w.gone) this.sendConfig(w, client);
  }

  /** Shared mode: wakes every worker to look for work. Transfer mode: hands out tasks. */
  kick(): void {
    for (const w of this.workers) if (!w.retiring && !w.gone) void w.api.kick().catch(() => {});
    this.pump();
  }

  async setSize(count: number): Promise<void> {
    this.target = Math.max(1, Math.min(64, Math.floor(count)));
    await this.resize();
  }

  terminate(): void {
    this.closed = true;
    for (const w of this.workers) {
      w.ended = true;
      w.gone = true;
      w.port.close();
      w.worker.terminate();
    }
    this.workers.length = 0;
  }

  /** Test hook: the running worker `index` (modulo their count), or null when none runs. */
  private running(index: number): PoolWorker | null {
    const running = this.workers.filter((w) => w.ready && !w.gone && !w.retiring);
    if (running.length === 0) return null;
    return running[Math.abs(Math.floor(index)) % running.length];
  }

  /**
   * Test hook, not API: terminates running worker `index` (modulo their
   * count) now, in the middle of whatever it does; or the worker with lock
   * token `token`. Returns the token of the worker killed, 0 when none.
   */
  killWorker(index = 0, token = 0): number {
    const w = token ? this.workers.find((x) => x.token === token && !x.gone) : this.running(index);
    if (!w) return 0;
    faults.killed++;
    this.lose(w);
    return w.token;
  }

  /**
   * Test hook, not API: makes running worker `index` throw an uncaught
   * error in its next stripe after committing `rows` (≥ 1) rows of it
   * (transfer mode: on its next task), as a bug would. Returns its token, 0
   * when none runs.
   */
  crashWorker(index = 0, rows = 1): number {
    const w = this.running(index);
    if (!w) return 0;
    void w.api.crash(rows).catch(() => {});
    return w.token;
  }

  /**
   * Test hook, not API: makes running worker `index` freeze for good inside
   * its next row commit (at `step` of commitRow), holding the lock; pair it
   * with killWorker(0, token). Returns its token, 0 when none runs.
   */
  hangWorker(index = 0, step = 2): number {
    const w = this.running(index);
    if (!w) return 0;
    void w.api.hang(step).catch(() => {});
    return w.token;
  }

  /** Workers started and not yet found dead or ended (test hook). */
  get liveWorkers(): number {
    return this.workers.filter((w) => !w.gone).length;
  }

  private active(): PoolWorker[] {
    return this.workers.filter((w) => !w.retiring);
  }

  private async resize(): Promise<void> {
    if (this.closed) return;
    const active = this.active();
    for (let i = active.length; i < this.target && !this.halted; i++) {
      if (!this.spawn()) break;
    }
    const extra = active.slice(this.target);
    // Retire gracefully: a worker killed with a claim in hand would leave its
    // stripe's pass unfinished and every later pass of that stripe waiting.
    await Promise.all(extra.map((w) => this.retire(w)));
  }

  private async retire(w: PoolWorker): Promise<void> {
    w.retiring = true;
    // A worker that dies meanwhile never answers: its death settles the wait.
    await Promise.race([
      w.api.stop().catch(() => {}),
      new Promise<void>((resolve) => (w.stopAnswered = resolve)),
    ]);
    w.stopped = true;
    // Transfer mode: a task still out comes back first (onResult removes the worker then).
    if (!w.busy && !w.gone) this.remove(w);
  }

  /** Ends a worker that holds nothing (retired): its slot is free at once. */
  private remove(w: PoolWorker): void {
    const i = this.workers.indexOf(w);
    if (i >= 0) this.workers.splice(i, 1);
    w.ended = true;
    w.gone = true;
    w.port.close();
    w.worker.terminate();
    this.slots[w.slot] = 0;
  }

  /**
   * Takes a worker out of service now (crashed, found dead, or killed by the
   * test hook) and starts its replacement. What it held in shared memory is
   * recovered once its death is certain (bury); a transfer task it held
   * goes out again at once, since its rows never left the client's film.
   */
  private lose(w: PoolWorker): void {
    if (w.gone) return;
    w.gone = true;
    const i = this.workers.indexOf(w);
    if (i >= 0) this.workers.splice(i, 1);
    w.port.close();
    w.worker.terminate();
    w.stopAnswered?.();
    if (w.task) {
      const task = w.task;
      w.task = null;
      faults.tasksResent++;
      this.clients.get(task.job)?.onTaskLost(task);
    }
    w.busy = false;
    if (!w.lifeLock || !w.ready) setTimeout(() => this.bury(w), DEATH_GRACE_MS);
    if (!w.retiring && !this.halted && !this.closed) faults.replaced++;
    void this.resize();
    this.pump();
  }

  /**
   * The worker is certainly dead (its life lock was granted to the pool,
   * or the grace period passed): its token is marked dead and every client
   * recovers what it held. Also how a death with no error event is found.
   */
  private bury(w: PoolWorker): void {
    if (w.buried) return;
    w.buried = true;
    markDead(w.token);
    if (w.ended) return;
    if (!w.gone) {
      faults.vanished++;
      this.noteCrash('a render worker stopped without an error');
      this.lose(w);
    }
    faults.confirmed++;
    this.recoverFrom(w);
  }

  private recoverFrom(w: PoolWorker): void {
    if (this.closed) return;
    let done = true;
    for (const c of this.clients.values()) if (!c.recover()) done = false;
    if (!done) {
      setTimeout(() => this.recoverFrom(w), RECOVERY_RETRY_MS);
      return;
    }
    this.slots[w.slot] = 0;
    // The reclaimed claims wait in the films: wake idle workers to take them.
    this.kick();
    void this.resize();
  }

  /** Counts a crash; too many too fast and the pool stops replacing workers. */
  private noteCrash(message: string): void {
    const count = this.crashes.note(performance.now());
    if (!this.halted && count > 2 * this.target + 4) {
      this.halted = true;
      this.fail(
        `render workers keep crashing (${count} in ${CRASH_WINDOW_MS / 1000} s), so no more are started; the last: ${message}`,
      );
    }
  }

  private freeSlot(): number {
    const slot = this.slots.indexOf(0);
    if (slot >= 0) this.slots[slot] = 1;
    return slot;
  }

  /** Reports a failure to every client: each shows it through its controller's error event. */
  private fail(message: string): void {
    for (const c of this.clients.values()) c.onWorkerError(message);
  }

  /**
   * Workers cannot start here: said once, however many fail the same way,
   * and to clients that register later (they would wait for ever otherwise).
   */
  private failToStart(message: string): void {
    if (this.startFailure !== null) return;
    this.startFailure = message;
    this.fail(message);
  }

  /** Starts a worker; false when it could not (reported) or no slot is free yet. */
  private spawn(): boolean {
    const slot = this.freeSlot();
    // Every slot waits for a dead worker's recovery: resize runs again after it.
    if (slot < 0) return false;
    let worker: Worker;
    try {
      worker = createWorker(this.source);
    } catch (e) {
      this.slots[slot] = 0;
      // Thrown synchronously (a SecurityError for a script the page may not
      // start, a throwing factory): inside resize() nobody else would see it.
      // Reported a microtask later, like a worker's own error event: spawns
      // happen inside a restart, whose `load` event would hide the message.
      const message = `render worker could not start: ${e instanceof Error ? e.message : String(e)}`;
      queueMicrotask(() => this.failToStart(message));
      return false;
    }
    const channel = new MessageChannel();
    const token = newWorkerToken();
    const locks = typeof navigator !== 'undefined' ? navigator.locks : undefined;
    const w = newPoolWorker(worker, channel.port1, slot, token, locks ? PAGE_ID : null);
    worker.addEventListener('error', (e) => {
      if (w.gone) return;
      if (!w.ready) {
        // It never started (a bad URL, a CSP): say so, as before; no
        // replacement, which would only fail the same way. A script that
        // fails to load gives an ErrorEvent without a message.
        this.failToStart(
          e.message ||
            `render worker failed to load: its script could not be fetched or run on this page (a wrong worker URL, or a Content-Security-Policy whose worker-src forbids it)`,
        );
        return;
      }
      const message = e.message || 'render worker crashed';
      // It was running: a crash. Replace it; recover what it held.
      console.warn(`pathwise: ${message}; the render worker is replaced`);
      faults.crashed++;
      this.noteCrash(message);
      this.lose(w);
    });
    // Not a Web Worker event: a stand-in (Node's worker_threads behind a
    // shim, as in the benchmarks and tests) may say when its thread ended.
    worker.addEventListener('exit', () => this.bury(w));
    channel.port1.onmessage = (e: MessageEvent<StripeResult>) => this.onResult(w, e.data);
    void w.api.setTaskPort(Comlink.transfer(channel.port2, [channel.port2]));
    void w.api.init({ slot, token, lifeLock: w.lifeLock || null }).then(
      (held) => {
        w.ready = true;
        if (!held) w.lifeLock = '';
        if (w.lifeLock && locks) {
          // Granted only once the worker is gone, however it went.
          void locks.request(w.lifeLock, () => this.bury(w)).catch(() => {});
        }
        this.pump();
      },
      (e: unknown) => {
        // It loaded but cannot start: as a start-up failure, said once.
        if (!w.gone)
          this.failToStart(
            `render worker could not start: ${e instanceof Error ? e.message : String(e)}`,
          );
      },
    );
    this.workers.push(w);
    for (const c of this.clients.values()) this.sendConfig(w, c);
    return true;
  }

  private sendConfig(w: PoolWorker, client: PoolClient): void {
    const full = client.config();
    const needsScene = w.sceneIds.get(client.id) !== full.sceneId;
    const config: JobConfig = needsScene ? full : { ...full, scene: undefined };
    w.sceneIds.set(client.id, full.sceneId);
    void w.api.configure(client.id, config).then(
      () => {
        const seen = w.acked.get(client.id) ?? -1;
        if (config.version > seen) w.acked.set(client.id, config.version);
        this.pump();
      },
      (e: unknown) => {
        // Forget the scene so the next configuration ships it again.
        w.sceneIds.delete(client.id);
        client.onWorkerError(e instanceof Error ? e.message : String(e));
      },
    );
  }

  private onResult(w: PoolWorker, result: StripeResult): void {
    if (w.gone) return;
    w.busy = false;
    w.task = null;
    this.clients.get(result.job)?.onResult(result);
    // Not before stop() has answered: terminating earlier would leave that call unanswered.
    if (w.retiring && w.stopped) this.remove(w);
    this.pump();
  }

  /** Transfer mode: gives every free worker a task from the clients in turn. */
  private pump(): void {
    const clients = [...this.clients.values()];
    if (clients.length === 0) return;
    for (const w of this.workers) {
      if (w.busy || w.retiring || w.gone) continue;
      for (let k = 0; k < clients.length; k++) {
        const client = clients[(this.turn + k) % clients.length];
        if (w.acked.get(client.id) !== client.config().version) continue;
        const task = client.nextTask();
        if (!task) continue;
        this.turn = (this.turn + k + 1) % clients.length;
        w.busy = true;
        w.task = task;
        w.port.postMessage(task, [task.buffer]);
        break;
      }
    }
  }
}

let shared: WorkerPool | null = null;

/** Test hook, not API: the page's pool, if one is running. */
export function currentPool(): WorkerPool | null {
  return shared;
}

/** The page's pool, created on first use with the first caller's worker source. */
export function sharedPool(source: WorkerSource, size?: number): WorkerPool {
  if (!shared) shared = new WorkerPool(source, size);
  return shared;
}

/** Ends the pool when its last client leaves, so an idle page holds no workers. */
export function releasePool(pool: WorkerPool): void {
  if (pool === shared && pool.empty) {
    pool.terminate();
    shared = null;
  }
}
