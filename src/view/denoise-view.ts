/**
 * The denoised picture of a still view (the widget's `denoise`, the demo's switch):
 * while the full film renders and the camera rests, its mean radiance, albedo and normal
 * go to the denoise workers (workers/browser/denoise-worker.ts, threads beside the
 * render workers, started on first use) and the result replaces the noisy picture
 * (Presenter.showDenoised) until the next restart.
 *
 * The image is cut into OIDN's overlapped tiles (src/core/denoise/tiles.ts) and the
 * tiles are dealt out to the workers; each writes its tiles' own regions, and a tile's
 * bits depend only on the image, so the picture is the same bits for any worker count.
 * One worker on small machines (a quarter of the cores, at most four): on two cores a
 * second denoise thread would only take time from the render's two.
 *
 * Refreshes follow the samples: the next denoise starts when the previous one is back
 * and the film has REFRESH_GROWTH× its samples, so the picture on screen is as fresh as
 * the denoiser can make it while samples pour in (the first seconds), and refreshes thin
 * out geometrically after. The render's workers keep tracing meanwhile. The last pass
 * (the target reached) is always denoised. Results for an older film (a restart or reset
 * since) are dropped; on isolated pages the picture in progress stops at its next layer.
 */
import {
  DENOISE_TILE_OPTIONS,
  type DenoiseReply,
  type DenoiseRequest,
} from '../../workers/browser/denoise-protocol.ts';
import { planTiles, type TilePlan } from '../core/denoise/tiles.ts';
import type { FilmJob } from './film-job.ts';
import { startModuleWorker } from './worker-source.ts';

/** `new Worker` through the same-origin shim (see pool.ts: Vite bundles the worker by this pattern). */
const ModuleWorker = function (url: URL): Worker {
  return startModuleWorker(url);
} as unknown as new (url: URL, options: WorkerOptions) => Worker;

/** A denoise is due again once the film has this many times its samples. */
const REFRESH_GROWTH = 1.5;
/** At most this many denoise workers. */
const MAX_DENOISE_WORKERS = 4;

/** The default number of denoise workers for `cores` logical cores. */
export function denoiseWorkerCount(cores: number): number {
  return Math.max(1, Math.min(MAX_DENOISE_WORKERS, Math.floor(cores / 4)));
}

/** A denoised picture, as the display takes film sums: RGBA with A = 1. */
export interface DenoisedImage {
  spp: number;
  width: number;
  height: number;
  sums: Float32Array;
  /** From the request to the last tile back, in ms (the network's wall time). */
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
  plan: TilePlan;
  /** Workers yet to answer, and whether one said it stopped. */
  pending: number;
  cancelled: boolean;
  started: number;
  /** The picture as tiles come back: RGBA, A = 1. */
  sums: Float32Array;
}

export class ViewDenoiser {
  enabled: boolean;
  private readonly host: DenoiseHost;
  private readonly maxWorkers: number;
  private workers: Worker[] = [];
  private failed = false;
  private nextId = 1;
  private inFlight: InFlight | null = null;
  /** The film generation and samples of the last denoised picture. */
  private lastGeneration = -1;
  private lastSpp = 0;
  /** When the film last started over (restart or reset). */
  private restartedAt = 0;
  /** Counts the film's restarts and resets: results for an older one are dropped. */
  private generation = 0;
  /** Denoised pictures shown (tests, stats). */
  count = 0;
  /**
   * The id of the request still wanted, shared with the workers so that a restart drops
   * the picture in progress at its next layer (isolated pages; elsewhere it finishes and
   * is dropped here).
   */
  private readonly wanted =
    typeof SharedArrayBuffer === 'function' && globalThis.crossOriginIsolated === true
      ? new Int32Array(new SharedArrayBuffer(4))
      : null;

  /** `workers`: denoise threads (default denoiseWorkerCount of the cores). */
  constructor(enabled: boolean, host: DenoiseHost, workers?: number) {
    this.enabled = enabled;
    this.host = host;
    const cores = typeof navigator !== 'undefined' ? navigator.hardwareConcurrency || 2 : 2;
    this.maxWorkers = Math.max(1, Math.floor(workers ?? denoiseWorkerCount(cores)));
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
    try {
      this.start(job, spp);
    } catch (e) {
      // No memory for the images, or a message that could not be sent: said once, and
      // denoising stops (the frame loop must not see the exception).
      this.fail(`denoising failed: ${e instanceof Error ? e.message : String(e)}`);
    }
    return this.inFlight !== null;
  }

  private start(job: FilmJob, spp: number): void {
    const { width, height, film } = job;
    const plan = planTiles(width, height, DENOISE_TILE_OPTIONS);
    const lanes = Math.min(this.maxWorkers, plan.tiles.length);
    const workers = this.ensureWorkers(lanes);
    if (!workers) return;
    const id = this.nextId++;
    const color = film.mean();
    const albedo = film.auxMean(0);
    const normal = film.auxMean(3);
    if (this.wanted) Atomics.store(this.wanted, 0, id);
    const inFlight: InFlight = {
      id,
      generation: this.generation,
      spp,
      width,
      height,
      plan,
      pending: lanes,
      cancelled: false,
      started: performance.now(),
      sums: new Float32Array(width * height * 4),
    };
    for (let k = 0; k < lanes; k++) {
      const req: DenoiseRequest = {
        type: 'denoise',
        id,
        width,
        height,
        color,
        albedo,
        normal,
        tiles: plan.tiles.map((_, i) => i).filter((i) => i % lanes === k),
        stop: this.wanted ? (this.wanted.buffer as SharedArrayBuffer) : null,
      };
      // The last worker takes the arrays themselves; the others get copies.
      const transfer = k === lanes - 1 ? [color.buffer, albedo.buffer, normal.buffer] : [];
      workers[k]!.postMessage(req, transfer);
    }
    // Only once every worker has its part: a post that threw leaves nothing waiting.
    this.inFlight = inFlight;
  }

  private ensureWorkers(count: number): Worker[] | null {
    try {
      while (this.workers.length < count) {
        const Worker = ModuleWorker;
        const worker = new Worker(
          new URL('../../workers/browser/denoise-worker.ts', import.meta.url),
          { type: 'module' },
        );
        worker.onmessage = (e: MessageEvent<DenoiseReply>) => this.onReply(e.data);
        worker.onerror = (e: ErrorEvent) => {
          e.preventDefault();
          this.fail(`the denoiser stopped: ${e.message || 'its script did not load'}`);
        };
        worker.onmessageerror = () =>
          this.fail('the denoiser sent a message that could not be read');
        this.workers.push(worker);
      }
    } catch (e) {
      this.fail(`the denoiser could not start: ${e instanceof Error ? e.message : String(e)}`);
      return null;
    }
    return this.workers;
  }

  /** Denoising stops (switched off: the caller may switch it on again to retry). */
  private fail(message: string): void {
    this.failed = true;
    this.enabled = false;
    this.inFlight = null;
    for (const w of this.workers) w.terminate();
    this.workers = [];
    this.host.error(message);
  }

  private onReply(reply: DenoiseReply): void {
    if (reply.type === 'ready') return;
    const job = this.inFlight;
    if (!job || reply.id !== job.id) return;
    if (reply.type === 'error') {
      this.fail(`denoising failed: ${reply.message}`);
      return;
    }
    if (reply.type === 'cancelled') job.cancelled = true;
    else {
      // This worker's tiles, from its full-size output into the picture.
      const { width } = job;
      const rgb = reply.rgb;
      const sums = job.sums;
      for (const i of reply.tiles) {
        const t = job.plan.tiles[i]!;
        for (let y = t.outY; y < t.outY + t.outH; y++) {
          for (let x = t.outX; x < t.outX + t.outW; x++) {
            const p = y * width + x;
            sums[4 * p] = rgb[3 * p]!;
            sums[4 * p + 1] = rgb[3 * p + 1]!;
            sums[4 * p + 2] = rgb[3 * p + 2]!;
            sums[4 * p + 3] = 1;
          }
        }
      }
    }
    if (--job.pending > 0) return;
    this.inFlight = null;
    if (job.cancelled || job.generation !== this.generation || !this.enabled) return;
    const now = performance.now();
    this.lastGeneration = job.generation;
    this.lastSpp = job.spp;
    this.count++;
    this.host.show({
      spp: job.spp,
      width: job.width,
      height: job.height,
      sums: job.sums,
      ms: now - job.started,
      sinceRestartMs: now - this.restartedAt,
      seconds: this.host.seconds(now),
    });
  }

  /** Turned off: nothing in flight is shown; the workers stay for the next time. */
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
    for (const w of this.workers) w.terminate();
    this.workers = [];
    this.inFlight = null;
  }
}
