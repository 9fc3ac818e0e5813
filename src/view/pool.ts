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
 * Nothing here touches the DOM or creates a worker at import time.
 */
import * as Comlink from 'comlink';
import type {
  JobConfig,
  RenderWorkerApi,
  StripeResult,
  StripeTask,
} from '../../workers/render-protocol.ts';
import { startModuleWorker } from './worker-source.ts';

export interface PoolClient {
  readonly id: number;
  /** The job's current configuration (the scene included; the pool strips it when it can). */
  config(): JobConfig;
  /** Transfer mode: the next stripe pass to render, or null. */
  nextTask(): StripeTask | null;
  onResult(result: StripeResult): void;
  onWorkerError(message: string): void;
}

interface PoolWorker {
  worker: Worker;
  api: Comlink.Remote<RenderWorkerApi>;
  port: MessagePort;
  busy: boolean;
  retiring: boolean;
  /** Its stop() has answered: no claim in hand, safe to terminate once no task is out. */
  stopped: boolean;
  /** Per job: the scene id this worker holds and the config version it acknowledged. */
  sceneIds: Map<number, number>;
  acked: Map<number, number>;
}

export interface WorkerSource {
  workerUrl?: string | URL;
  workerFactory?: () => Worker;
}

function defaultWorkerCount(): number {
  const cores = typeof navigator !== 'undefined' ? navigator.hardwareConcurrency : 0;
  return Math.max(1, Math.min(64, cores || 4));
}

/**
 * Starts the worker at `url` like `new Worker`, but through a same-origin
 * shim when the package was loaded from another origin (see createWorker).
 */
const ModuleWorker = function (url: URL): Worker {
  return startModuleWorker(url);
} as unknown as new (url: URL, options: WorkerOptions) => Worker;

export class WorkerPool {
  private readonly workers: PoolWorker[] = [];
  private readonly clients = new Map<number, PoolClient>();
  private readonly source: WorkerSource;
  private turn = 0;
  private target: number;

  constructor(source: WorkerSource, size?: number) {
    this.source = source;
    this.target = size ?? defaultWorkerCount();
  }

  get size(): number {
    return this.target;
  }

  register(client: PoolClient): void {
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
    for (const w of this.workers) if (!w.retiring) this.sendConfig(w, client);
  }

  /** Shared mode: wakes every worker to look for work. Transfer mode: hands out tasks. */
  kick(): void {
    for (const w of this.workers) if (!w.retiring) void w.api.kick().catch(() => {});
    this.pump();
  }

  async setSize(count: number): Promise<void> {
    this.target = Math.max(1, Math.min(64, Math.floor(count)));
    await this.resize();
  }

  terminate(): void {
    for (const w of this.workers) {
      w.port.close();
      w.worker.terminate();
    }
    this.workers.length = 0;
  }

  private active(): PoolWorker[] {
    return this.workers.filter((w) => !w.retiring);
  }

  private async resize(): Promise<void> {
    const active = this.active();
    for (let i = active.length; i < this.target; i++) this.spawn();
    const extra = active.slice(this.target);
    // Retire gracefully: a worker killed with a claim in hand would leave its
    // stripe's pass unfinished and every later pass of that stripe waiting.
    await Promise.all(extra.map((w) => this.retire(w)));
  }

  private async retire(w: PoolWorker): Promise<void> {
    w.retiring = true;
    await w.api.stop().catch(() => {});
    w.stopped = true;
    // Transfer mode: a task still out comes back first (onResult removes the worker then).
    if (!w.busy) this.remove(w);
  }

  private remove(w: PoolWorker): void {
    const i = this.workers.indexOf(w);
    if (i >= 0) this.workers.splice(i, 1);
    w.port.close();
    w.worker.terminate();
  }

  private createWorker(): Worker {
    if (this.source.workerFactory) return this.source.workerFactory();
    if (this.source.workerUrl) return startModuleWorker(this.source.workerUrl);
    // The package's own worker sits next to this module, which may have come
    // from a CDN: `Worker` is shadowed so that the expression below stays
    // written out in full (Vite recognises and bundles the worker by that
    // pattern) while the URL goes through the same-origin shim.
    const Worker = ModuleWorker;
    return new Worker(new URL('../../workers/render-worker.ts', import.meta.url), {
      type: 'module',
    });
  }

  /** Reports a failure to every client: each shows it through its controller's error event. */
  private fail(message: string): void {
    for (const c of this.clients.values()) c.onWorkerError(message);
  }

  private spawn(): void {
    let worker: Worker;
    try {
      worker = this.createWorker();
    } catch (e) {
      // Thrown synchronously (a SecurityError for a script the page may not
      // start, a throwing factory): inside resize() nobody else would see it.
      // Reported a microtask later, like a worker's own error event: spawns
      // happen inside a restart, whose `load` event would hide the message.
      const message = `render worker could not start: ${e instanceof Error ? e.message : String(e)}`;
      queueMicrotask(() => this.fail(message));
      return;
    }
    const api = Comlink.wrap<RenderWorkerApi>(worker);
    const channel = new MessageChannel();
    const w: PoolWorker = {
      worker,
      api,
      port: channel.port1,
      busy: false,
      retiring: false,
      stopped: false,
      sceneIds: new Map(),
      acked: new Map(),
    };
    worker.addEventListener('error', (e) => {
      // A script that fails to load gives an ErrorEvent without a message.
      this.fail(e.message || 'render worker failed to load or crashed');
    });
    channel.port1.onmessage = (e: MessageEvent<StripeResult>) => this.onResult(w, e.data);
    void api.setTaskPort(Comlink.transfer(channel.port2, [channel.port2]));
    this.workers.push(w);
    for (const c of this.clients.values()) this.sendConfig(w, c);
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
    w.busy = false;
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
      if (w.busy || w.retiring) continue;
      for (let k = 0; k < clients.length; k++) {
        const client = clients[(this.turn + k) % clients.length];
        if (w.acked.get(client.id) !== client.config().version) continue;
        const task = client.nextTask();
        if (!task) continue;
        this.turn = (this.turn + k + 1) % clients.length;
        w.busy = true;
        w.port.postMessage(task, [task.buffer]);
        break;
      }
    }
  }
}

let shared: WorkerPool | null = null;

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
