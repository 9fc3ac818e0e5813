/**
 * Loading a scene off the page's thread: one module worker (workers/browser/model-worker.ts)
 * reads a pathwise-scene/1 file and the files it names, or a bare glTF model (parse,
 * images, flattening), builds its BVH and packs the compiled scene; the page only
 * installs views of the result, so it stays responsive however large the scene. Where
 * the worker cannot start (a host whose bundler or CDN breaks the worker's URL), the
 * result is null and the caller loads the scene on the page instead.
 */
import type { LoadStage, PackedScene, Scene } from '../core/index.ts';
import type { LoadRequest, ModelReply } from '../../workers/browser/model-protocol.ts';
import { startModuleWorker } from './worker-source.ts';

/** `new Worker` through the same-origin shim (see pool.ts: Vite bundles the worker by this pattern). */
const ModuleWorker = function (url: URL): Worker {
  return startModuleWorker(url);
} as unknown as new (url: URL, options: WorkerOptions) => Worker;

export interface LoadedModel {
  /** Without the model's arrays (see model-protocol.ts). */
  scene: Scene;
  packed: PackedScene;
  skippedTriangles: number;
  warnings: string[];
}

export interface ModelJob {
  /** The loaded model; null when the worker could not run at all; rejects with the loader's message. */
  readonly promise: Promise<LoadedModel | null>;
  /**
   * Stops the worker (a newer scene superseded this one): its stop word is raised, which
   * its loops check, then it is terminated; the promise then never settles.
   */
  cancel(): void;
}

/** Scene workers running now (tests: a superseded load leaves none behind). */
let live = 0;
export function liveSceneWorkers(): number {
  return live;
}

/**
 * A scene worker failed to start on this page (a Content-Security-Policy without
 * worker-src, a bundler that broke its URL): it would fail again, so later loads go
 * straight to the page's own loader instead of trying (and logging a violation) each time.
 */
let cannotStart = false;

/** A request as the caller gives it: the stop word is the job's own. */
type WithoutStop<T> = T extends unknown ? Omit<T, 'stop'> : never;

/**
 * Starts the scene worker and, once its script runs, sends it `request`, transferring
 * `transfer` (buffers the caller owns and gives up: a 6 MB scene copied into the message
 * took ~60 ms of the page's thread). Until the worker says it runs, nothing is sent, so
 * a worker that cannot start leaves the caller its bytes for loading on the page.
 */
export function loadModelInWorker(
  request: WithoutStop<LoadRequest>,
  onProgress: (stage: LoadStage, done: number, total: number) => void,
  transfer: ArrayBuffer[] = [],
): ModelJob {
  let worker: Worker | null = null;
  const stop = typeof SharedArrayBuffer === 'function' ? new SharedArrayBuffer(4) : null;
  let ended = false;
  const end = () => {
    if (ended || worker === null) return;
    ended = true;
    live--;
    if (stop !== null) Atomics.store(new Int32Array(stop), 0, 1);
    worker.terminate();
  };
  const promise = new Promise<LoadedModel | null>((resolve, reject) => {
    if (cannotStart) {
      resolve(null);
      return;
    }
    try {
      const Worker = ModuleWorker;
      worker = new Worker(new URL('../../workers/browser/model-worker.ts', import.meta.url), {
        type: 'module',
      });
    } catch {
      cannotStart = true;
      resolve(null);
      return;
    }
    live++;
    const w = worker;
    let heard = false;
    const shapes: Scene['shapes'][] = [];
    w.onmessage = (e: MessageEvent<ModelReply>) => {
      heard = true;
      const reply = e.data;
      if (reply.type === 'ready') {
        w.postMessage({ ...request, stop } as LoadRequest, transfer);
        return;
      }
      if (reply.type === 'progress') {
        onProgress(reply.stage, reply.done, reply.total);
        return;
      }
      if (reply.type === 'shapes') {
        shapes.push(reply.shapes);
        return;
      }
      end();
      if (reply.type === 'done') {
        const { packed, skippedTriangles, warnings } = reply;
        const scene = shapes.length > 0 ? { ...reply.scene, shapes: shapes.flat() } : reply.scene;
        resolve({ scene, packed, skippedTriangles, warnings });
      } else reject(new Error(reply.message));
    };
    w.onerror = (e: ErrorEvent) => {
      e.preventDefault();
      end();
      // Nothing heard: the script did not load or start; the caller loads on the page.
      if (!heard) {
        cannotStart = true;
        resolve(null);
      } else reject(new Error(`the model worker failed: ${e.message || 'unknown error'}`));
    };
  });
  return { promise, cancel: end };
}
