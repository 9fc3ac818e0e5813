/**
 * One render worker as the pool (pool.ts) keeps it: the Worker, its Comlink
 * proxy and task port, and the state of its life — starting, running,
 * retiring, dead and recovered from. Also where workers come from (a
 * factory, a URL, or the package's own script) and the window in which
 * crashes are counted before the pool stops replacing them.
 *
 * Nothing here touches the DOM or creates a worker at import time.
 */
import * as Comlink from 'comlink';
import type { RenderWorkerApi, StripeTask } from '../../workers/browser/render-protocol.ts';
import { startModuleWorker } from './worker-source.ts';

export interface PoolWorker {
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
  /** Its record in the control blocks, and its lock token. */
  slot: number;
  token: number;
  /** init has answered: it started, and claims only from now on. */
  ready: boolean;
  /** The Web Lock it holds while it lives ('' without Web Locks). */
  lifeLock: string;
  /** Out of service: terminated, or found dead. */
  gone: boolean;
  /** Ended by the pool on purpose (retired, pool closed): nothing to recover. */
  ended: boolean;
  /** Its death is certain and was recovered from. */
  buried: boolean;
  /** Transfer mode: the task it holds. */
  task: StripeTask | null;
  /** Settles a retire waiting on stop() should the worker die first. */
  stopAnswered: (() => void) | null;
}

/** A fresh record for a worker just started; `pageId` names its life lock (null: no Web Locks). */
export function newPoolWorker(
  worker: Worker,
  port: MessagePort,
  slot: number,
  token: number,
  pageId: string | null,
): PoolWorker {
  return {
    worker,
    api: Comlink.wrap<RenderWorkerApi>(worker),
    port,
    busy: false,
    retiring: false,
    stopped: false,
    sceneIds: new Map(),
    acked: new Map(),
    slot,
    token,
    ready: false,
    lifeLock: pageId !== null ? `pathwise-render-worker-${pageId}-${token}` : '',
    gone: false,
    ended: false,
    buried: false,
    task: null,
    stopAnswered: null,
  };
}

export interface WorkerSource {
  workerUrl?: string | URL;
  workerFactory?: () => Worker;
}

export function defaultWorkerCount(): number {
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

/** Starts a render worker from `source`; throws what `new Worker` throws (a SecurityError). */
export function createWorker(source: WorkerSource): Worker {
  if (source.workerFactory) return source.workerFactory();
  if (source.workerUrl) return startModuleWorker(source.workerUrl);
  // The package's own worker sits next to this module, which may have come
  // from a CDN: `Worker` is shadowed so that the expression below stays
  // written out in full (Vite recognises and bundles the worker by that
  // pattern) while the URL goes through the same-origin shim.
  const Worker = ModuleWorker;
  return new Worker(new URL('../../workers/browser/render-worker.ts', import.meta.url), {
    type: 'module',
  });
}

/** More crashes than the pool allows (2 per worker + 4) within this window and it gives up. */
export const CRASH_WINDOW_MS = 10_000;

/** Crash times within a sliding window. */
export class CrashWindow {
  private times: number[] = [];
  constructor(private readonly windowMs: number) {}

  /** Counts a crash at `now` (ms); returns the crashes within the window, this one included. */
  note(now: number): number {
    this.times = this.times.filter((t) => now - t < this.windowMs);
    this.times.push(now);
    return this.times.length;
  }
}
