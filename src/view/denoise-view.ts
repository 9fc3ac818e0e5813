/**
 * The denoised picture of a still view (the widget's `denoise`, the demo's switch):
 * while the full film renders and the camera rests, its mean radiance, albedo and normal
 * go to the denoise worker (workers/browser/denoise-worker.ts, one thread beside the
 * render workers, started on first use) and the result replaces the noisy picture
 * (Presenter.showDenoised) until the next restart.
 *
 * Refreshes follow the samples: the next denoise starts when the previous one is back
 * and the film has REFRESH_GROWTH× its samples, so the picture on screen is as fresh as
 * one thread can make it while samples pour in (the first seconds), and refreshes thin
 * out geometrically after. The denoiser holds at most one core; the render's workers
 * keep tracing meanwhile. The last pass (the target reached) is always denoised.
 * Results for an older film (a restart or reset since) are dropped.
 */
import type { DenoiseReply, DenoiseRequest } from '../../workers/browser/denoise-protocol.ts';
import type { FilmJob } from './film-job.ts';
import { startModuleWorker } from './worker-source.ts';

/** `new Worker` through the same-origin shim (see pool.ts: Vite bundles the worker by this pattern). */
const ModuleWorker = function (url: URL): Worker {
  return startModuleWorker(url);
} as unknown as new (url: URL, options: WorkerOptions) => Worker;

/** A denoise is due again once the film has this many times its samples. */
const REFRESH_GROWTH = 1.5;

/** A denoised picture, as the display takes film sums: RGBA with A = 1. */
export interface DenoisedImage {
  spp: number;
  width: number;
  height: number;
  sums: Float32Array;
  /** The network's time on the worker. */
  ms: number;
  /** From the camera's last restart to this picture on screen (performance.now() ms). */
  sinceRestartMs: number;
  /** The film's tracing seconds when it arrived (the error plot's time axis). */
  seconds: number;
}

export interface DenoiseHost {
  /** A denoised picture for the current configuration arrived (show it, wake the loop). */
  show(image: DenoisedImage): void;
  error(message: string): void;
  /** The film's tracing seconds now. */
  seconds(now: number): number;
}

interface InFlight {
  id: number;
  generation: number;
  spp: number;
  width: number;
  height: number;
}

export class ViewDenoiser {
  enabled: boolean;
  private readonly host: DenoiseHost;
  private worker: Worker | null = null;
  private failed = false;
  private nextId = 1;
  private inFlight: InFlight | null = null;
  /** The film generation and samples of the last denoised picture, and when. */
  private lastGeneration = -1;
  private lastSpp = 0;
  /** The network's time on the worker for the last picture, and that picture's pixels. */
  lastMs = 0;
  lastPixels = 0;
  /** When the film last started over (restart or reset). */
  private restartedAt = 0;
  /** Counts the film's restarts and resets: results for an older one are dropped. */
  private generation = 0;
  /** Denoised pictures shown (tests, stats). */
  count = 0;
  /**
   * The id of the request still wanted, shared with the worker so that a restart drops
   * the picture in progress at its next layer (isolated pages; elsewhere it finishes and
   * is dropped here).
   */
  private readonly wanted =
    typeof SharedArrayBuffer === 'function' && globalThis.crossOriginIsolated === true
      ? new Int32Array(new SharedArrayBuffer(4))
      : null;

  constructor(enabled: boolean, host: DenoiseHost) {
    this.enabled = enabled;
    this.host = host;
  }

  /** The film started over (a restart or reset): what is in flight is for the old one. */
  restarted(now: number): void {
    this.generation++;
    this.restartedAt = now;
    if (this.wanted) Atomics.store(this.wanted, 0, 0);
  }

  /**
   * Called each frame with the full film while the view rests. Starts a denoise when
   * one is due; returns true while one is in flight or due (the loop keeps running).
   */
  update(job: FilmJob, spp: number, target: number): boolean {
    if (!this.enabled || this.failed || !job.aux || spp < 1) return false;
    if (this.inFlight !== null) return true;
    const fresh = this.lastGeneration !== this.generation;
    const grown = spp >= Math.max(this.lastSpp + 1, Math.ceil(this.lastSpp * REFRESH_GROWTH));
    const last = spp >= target && this.lastSpp < target;
    if (!fresh && !grown && !last) return false;
    this.start(job, spp);
    return this.inFlight !== null;
  }

  private start(job: FilmJob, spp: number): void {
    const worker = this.ensureWorker();
    if (!worker) return;
    const { width, height, film } = job;
    const req: DenoiseRequest = {
      type: 'denoise',
      id: this.nextId++,
      width,
      height,
      color: film.mean(),
      albedo: film.auxMean(0),
      normal: film.auxMean(3),
      stop: this.wanted ? (this.wanted.buffer as SharedArrayBuffer) : null,
    };
    if (this.wanted) Atomics.store(this.wanted, 0, req.id);
    this.inFlight = { id: req.id, generation: this.generation, spp, width, height };
    worker.postMessage(req, [req.color.buffer, req.albedo.buffer, req.normal.buffer]);
  }

  private ensureWorker(): Worker | null {
    if (this.worker) return this.worker;
    try {
      const Worker = ModuleWorker;
      this.worker = new Worker(
        new URL('../../workers/browser/denoise-worker.ts', import.meta.url),
        {
          type: 'module',
        },
      );
    } catch (e) {
      this.fail(`the denoiser could not start: ${e instanceof Error ? e.message : String(e)}`);
      return null;
    }
    this.worker.onmessage = (e: MessageEvent<DenoiseReply>) => this.onReply(e.data);
    this.worker.onerror = (e: ErrorEvent) => {
      e.preventDefault();
      this.fail(`the denoiser stopped: ${e.message || 'its script did not load'}`);
    };
    return this.worker;
  }

  private fail(message: string): void {
    this.failed = true;
    this.inFlight = null;
    this.worker?.terminate();
    this.worker = null;
    this.host.error(message);
  }

  private onReply(reply: DenoiseReply): void {
    if (reply.type === 'ready') return;
    const job = this.inFlight;
    if (!job || reply.id !== job.id) return;
    this.inFlight = null;
    const now = performance.now();
    if (reply.type === 'cancelled') return;
    if (reply.type === 'error') {
      this.fail(`denoising failed: ${reply.message}`);
      return;
    }
    this.lastMs = reply.ms;
    this.lastPixels = job.width * job.height;
    if (job.generation !== this.generation || !this.enabled) return;
    this.lastGeneration = job.generation;
    this.lastSpp = job.spp;
    const n = job.width * job.height;
    const sums = new Float32Array(n * 4);
    const rgb = reply.rgb;
    for (let p = 0; p < n; p++) {
      sums[4 * p] = rgb[3 * p]!;
      sums[4 * p + 1] = rgb[3 * p + 1]!;
      sums[4 * p + 2] = rgb[3 * p + 2]!;
      sums[4 * p + 3] = 1;
    }
    this.count++;
    this.host.show({
      spp: job.spp,
      width: job.width,
      height: job.height,
      sums,
      ms: reply.ms,
      sinceRestartMs: now - this.restartedAt,
      seconds: this.host.seconds(now),
    });
  }

  /** Turned off: nothing in flight is shown; the worker stays for the next time. */
  disable(): void {
    this.enabled = false;
    if (this.wanted) Atomics.store(this.wanted, 0, 0);
    this.lastGeneration = -1;
    this.lastSpp = 0;
  }

  enable(): void {
    this.enabled = true;
    this.failed = false;
  }

  destroy(): void {
    this.worker?.terminate();
    this.worker = null;
    this.inFlight = null;
  }
}
