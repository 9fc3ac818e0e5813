/**
 * createPathTracer: one canvas, one scene, rendered progressively by the
 * page's shared worker pool and shown every animation frame.
 *
 * Every change that alters the image (scene, camera, bounces, seed, size)
 * goes through `restart`: a new configuration version, a reset of the film
 * (which bumps its generation, so workers drop stale rows) and the new
 * configuration sent to the workers. Exposure is display-only and never
 * restarts anything.
 *
 * While the user drags, the job switches to a preview film a quarter of the
 * size in each direction, so each camera step shows within a frame or two;
 * when the pointer rests the full film takes over again.
 */
import {
  PathTracer,
  compileScene,
  encodePfm,
  estimateNoise,
  parseScene,
  tonemapSums,
  validateScene,
  type CameraDesc,
  type CompiledScene,
  type Scene,
} from '../core/index.ts';
import { chooseStripeRows, type JobConfig } from '../../workers/render-protocol.ts';
import type { Display, DisplayPixels } from './display.ts';
import type { FilmJob } from './film-job.ts';
import { attachCameraControls } from './interaction.ts';
import { chooseCompute, createDisplay } from './mode.ts';
import { dollyCamera, orbitCamera } from './orbit.ts';
import { releasePool, sharedPool, type PoolClient, type WorkerPool } from './pool.ts';
import { SharedFilmJob } from './shared-job.ts';
import { RateMeter } from './rate-meter.ts';
import { TransferFilmJob } from './transfer-job.ts';
import type {
  FallbackInfo,
  PathTracerController,
  PathTracerOptions,
  ProgressInfo,
  RenderStatsInfo,
} from './types.ts';

let nextJobId = 1;
/** Preview films are this many times smaller in each direction. */
const PREVIEW_DIVISOR = 4;
/** Noise is estimated at most this often (it reads the whole film). */
const NOISE_INTERVAL_MS = 500;

export class Controller extends EventTarget implements PathTracerController {
  readonly canvas: HTMLCanvasElement;
  readonly mode: FallbackInfo;
  private readonly options: PathTracerOptions;
  private readonly id = nextJobId++;
  private readonly pool: WorkerPool;
  private readonly client: PoolClient;
  private readonly display: Display;
  private currentScene: Scene | null = null;
  private compiled: CompiledScene | null = null;
  private sceneId = 0;
  private camera: CameraDesc | null = null;
  private bounces = 6;
  private exposure: number;
  private seed: number;
  private target: number;
  private renderScale: number;
  private isPaused = false;
  private version = 0;
  private config: JobConfig | null = null;
  private full: FilmJob | null = null;
  private preview: FilmJob | null = null;
  private previewing = false;
  /** The pointer is moving: the next camera change switches to the preview film. */
  private wantPreview = false;
  private raf = 0;
  /** Exposure changed: redraw without new samples. */
  private displayDirty = true;
  /** The film was switched or remade: upload all of it. */
  private uploadAll = true;
  private convergedSent = false;
  private destroyed = false;
  private readonly rays = new RateMeter();
  private readonly frames = new RateMeter();
  private frameMs = 0;
  private segmentsTotal = 0;
  private noise = NaN;
  private noiseAt = 0;
  private lastProgressAt = 0;
  private detachControls: (() => void) | null = null;
  private picker: PathTracer | null = null;

  constructor(canvas: HTMLCanvasElement, options: PathTracerOptions) {
    super();
    this.canvas = canvas;
    this.options = options;
    this.exposure = options.exposure ?? 1;
    this.seed = options.seed ?? 0;
    this.target = options.spp ?? 512;
    this.renderScale = options.renderScale ?? 1;
    this.isPaused = options.autoplay === false;
    const compute = chooseCompute(options);
    const { display, why } = createDisplay(canvas, options);
    this.display = display;
    this.mode = {
      display: display.mode,
      compute: compute.compute,
      reason: `${why}; ${compute.why}`,
    };
    this.pool = sharedPool(options, options.workers);
    if (options.workers !== undefined && options.workers !== this.pool.size) {
      void this.pool.setSize(options.workers);
    }
    this.client = {
      id: this.id,
      config: () => this.config!,
      nextTask: () => (this.previewing ? this.preview : this.full)?.nextTask?.(this.id) ?? null,
      onResult: (r) => {
        const job = this.activeJob();
        if (job && r.version === this.version) job.onResult?.(r);
      },
      onWorkerError: (message) => this.emit('error', { message }),
    };
    if (options.cameraControls !== false) {
      this.detachControls = attachCameraControls(this, canvas);
    }
    // Let the caller attach listeners before the first events.
    queueMicrotask(() => this.emit('fallback', this.mode));
    if (options.scene !== undefined) {
      this.setScene(options.scene).catch(() => {});
    } else if (options.src) {
      this.load(options.src).catch(() => {});
    }
    this.raf = requestAnimationFrame(this.frame);
  }

  get scene(): Scene | null {
    return this.currentScene;
  }

  get paused(): boolean {
    return this.isPaused;
  }

  private emit<K extends string>(type: K, detail: unknown): void {
    this.dispatchEvent(new CustomEvent(type, { detail }));
  }

  private activeJob(): FilmJob | null {
    return this.previewing ? this.preview : this.full;
  }

  // ---- scene -------------------------------------------------------------

  async setScene(value: unknown): Promise<void> {
    let scene: Scene;
    try {
      scene = typeof value === 'string' ? parseScene(value) : validateScene(value);
    } catch (e) {
      const message = e instanceof Error ? e.message : String(e);
      this.emit('error', { message });
      throw new Error(message);
    }
    const first = this.currentScene === null;
    this.currentScene = scene;
    this.compiled = compileScene(scene);
    this.picker = null;
    this.sceneId++;
    this.camera = { ...scene.camera };
    this.bounces =
      first && this.options.bounces !== undefined
        ? this.options.bounces
        : scene.settings.maxBounces;
    this.restart();
    this.emit('load', { scene });
  }

  async load(url: string): Promise<void> {
    let text: string;
    try {
      const response = await fetch(url);
      if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
      text = await response.text();
    } catch (e) {
      const message = e instanceof Error ? e.message : String(e);
      this.emit('error', { message });
      throw new Error(message);
    }
    await this.setScene(text);
  }

  // ---- restart machinery -------------------------------------------------

  /** The full render size: fixed, or the canvas's CSS size × devicePixelRatio × renderScale. */
  private fullSize(): [number, number] {
    const o = this.options;
    if (o.width && o.height) return [Math.floor(o.width), Math.floor(o.height)];
    const dpr = typeof devicePixelRatio === 'number' ? devicePixelRatio : 1;
    const w = this.canvas.clientWidth || this.canvas.width || 300;
    const h = this.canvas.clientHeight || this.canvas.height || 150;
    const s = dpr * this.renderScale;
    return [Math.max(1, Math.round(w * s)), Math.max(1, Math.round(h * s))];
  }

  private makeJob(width: number, height: number): FilmJob {
    const rows = chooseStripeRows(height, this.pool.size);
    return this.mode.compute === 'shared'
      ? new SharedFilmJob(width, height, rows, this.target)
      : new TransferFilmJob(width, height, rows, this.target);
  }

  /** Makes sure the full film matches the wanted size; returns true when it was (re)made. */
  private ensureFullJob(): boolean {
    const [w, h] = this.fullSize();
    if (this.full && this.full.width === w && this.full.height === h) return false;
    this.full?.setVersion(-1);
    this.full = this.makeJob(w, h);
    this.preview = null;
    this.canvas.width = w;
    this.canvas.height = h;
    this.uploadAll = true;
    return true;
  }

  private ensurePreviewJob(): FilmJob {
    const full = this.full!;
    const w = Math.max(1, Math.round(full.width / PREVIEW_DIVISOR));
    const h = Math.max(1, Math.round(full.height / PREVIEW_DIVISOR));
    if (!this.preview || this.preview.width !== w || this.preview.height !== h) {
      this.preview = this.makeJob(w, h);
    }
    return this.preview;
  }

  /** New configuration version, reset of the active film, configuration to the workers. */
  private restart(): void {
    if (!this.currentScene || !this.camera || this.destroyed) return;
    this.ensureFullJob();
    if (this.wantPreview) this.previewing = true;
    const active = this.previewing ? this.ensurePreviewJob() : this.full!;
    const inactive = this.previewing ? this.full : this.preview;
    this.version++;
    inactive?.setVersion(-1);
    // Version first, then reset: a worker still holding the old
    // configuration can claim nothing once the version moved on.
    active.setVersion(this.version);
    active.setTarget(this.target);
    active.setPaused(this.isPaused);
    active.reset();
    const shared = active instanceof SharedFilmJob ? active : null;
    this.config = {
      mode: this.mode.compute,
      version: this.version,
      sceneId: this.sceneId,
      scene: this.currentScene,
      width: active.width,
      height: active.height,
      maxBounces: this.bounces,
      seed: this.seed,
      estimator: 'nee-mis',
      sampler: 'independent',
      camera: this.camera,
      stripeRows: active.stripeRows,
      film: shared?.filmBuffer,
      ctrl: shared?.ctrlBuffer,
    };
    this.convergedSent = false;
    this.uploadAll = true;
    this.rays.reset();
    this.noise = NaN;
    this.pool.register(this.client);
    this.pool.configure(this.client);
    this.pool.kick();
  }

  reset(): void {
    const job = this.activeJob();
    if (!job || !this.config) return;
    job.reset();
    this.convergedSent = false;
    this.displayDirty = true;
    this.noise = NaN;
    this.pool.kick();
  }

  pause(): void {
    this.isPaused = true;
    this.activeJob()?.setPaused(true);
  }

  resume(): void {
    this.isPaused = false;
    this.activeJob()?.setPaused(false);
    this.pool.kick();
  }

  setTargetSpp(spp: number): void {
    this.target = Math.max(1, Math.floor(spp));
    this.full?.setTarget(this.target);
    this.preview?.setTarget(this.target);
    this.convergedSent = false;
    this.pool.kick();
  }

  setBounces(bounces: number): void {
    this.bounces = Math.max(0, Math.floor(bounces));
    this.restart();
  }

  setExposure(exposure: number): void {
    this.exposure = exposure;
    this.displayDirty = true;
  }

  setSeed(seed: number): void {
    this.seed = seed >>> 0;
    this.restart();
  }

  setRenderScale(scale: number): void {
    this.renderScale = Math.max(0.05, Math.min(4, scale));
    if (this.ensureFullJob()) this.restart();
  }

  async setWorkers(count: number): Promise<void> {
    await this.pool.setSize(count);
    this.pool.kick();
  }

  // ---- camera ------------------------------------------------------------

  getCamera(): CameraDesc {
    const c = this.camera ?? this.currentScene?.camera;
    if (!c) throw new Error('no scene loaded');
    return structuredClone(c);
  }

  setCamera(camera: CameraDesc): void {
    this.camera = structuredClone(camera);
    this.picker = null;
    this.restart();
  }

  orbit(dxPixels: number, dyPixels: number): void {
    if (!this.camera) return;
    // A drag across the canvas's width turns the view half way round.
    const perPixel = Math.PI / Math.max(1, this.canvas.clientWidth || this.canvas.width);
    this.setCamera(orbitCamera(this.camera, dxPixels * perPixel, dyPixels * perPixel));
  }

  dolly(factor: number): void {
    if (!this.camera) return;
    this.setCamera(dollyCamera(this.camera, factor));
  }

  setAperture(aperture: number): void {
    if (!this.camera) return;
    this.setCamera({ ...this.camera, aperture: Math.max(0, aperture) });
  }

  focusAt(x: number, y: number): boolean {
    if (!this.camera || !this.compiled || !this.full) return false;
    const { width, height } = this.full;
    const rect = this.canvas.getBoundingClientRect();
    const fx = (x / (rect.width || width)) * width;
    const fy = (y / (rect.height || height)) * height;
    if (!this.picker || this.picker.width !== width || this.picker.height !== height) {
      this.picker = new PathTracer(this.compiled, {
        width,
        height,
        maxBounces: this.bounces,
        camera: this.camera,
      });
    }
    this.picker.setCamera(this.camera);
    const distance = this.picker.pick(fx, fy);
    if (!(distance > 0)) return false;
    if (this.camera.aperture > 0) {
      this.setCamera({ ...this.camera, focusDistance: distance });
    } else {
      // A pinhole images every distance sharply: keep the focus for when the
      // aperture opens, but do not throw away the samples.
      this.camera = { ...this.camera, focusDistance: distance };
      if (this.config) this.config = { ...this.config, camera: this.camera };
    }
    return true;
  }

  /** Interaction hooks: the preview film while the pointer moves, the full film when it rests. */
  beginPreview(): void {
    this.wantPreview = true;
  }

  endPreview(): void {
    this.wantPreview = false;
    if (!this.previewing) return;
    this.previewing = false;
    this.restart();
  }

  // ---- per frame ---------------------------------------------------------

  /**
   * Uploads the rows that changed since the last draw and draws; with
   * `force`, draws even when nothing changed. Returns whether it drew.
   */
  private present(job: FilmJob, force: boolean): boolean {
    const dirty = job.takeDirtyRows();
    if (!force && dirty.length === 0 && !this.displayDirty && !this.uploadAll) return false;
    const rows = this.uploadAll ? null : dirty;
    this.display.draw(job.film.sums, job.width, job.height, this.exposure, rows);
    this.displayDirty = false;
    this.uploadAll = false;
    return true;
  }

  private readonly frame = (now: number): void => {
    if (this.destroyed) return;
    this.raf = requestAnimationFrame(this.frame);
    if (!this.options.width && this.full && !this.previewing && this.ensureFullJob()) {
      this.restart();
    }
    const job = this.activeJob();
    if (!job) return;
    const segments = job.takeSegments();
    this.segmentsTotal += segments;
    this.rays.add(now, segments);
    const t0 = performance.now();
    if (this.present(job, false)) {
      this.frameMs = performance.now() - t0;
      this.frames.add(now, 1);
    }
    const spp = job.passesDone();
    if (now - this.noiseAt > NOISE_INTERVAL_MS) {
      this.noiseAt = now;
      // Every 4th pixel is plenty for a figure shown with two digits.
      this.noise = estimateNoise(job.film, 4);
    }
    if (now - this.lastProgressAt > 100) {
      this.lastProgressAt = now;
      this.emit('progress', this.progressInfo(spp));
    }
    if (!this.convergedSent && !this.previewing && spp >= this.target) {
      this.convergedSent = true;
      this.emit('converged', this.progressInfo(spp));
    }
  };

  private progressInfo(spp: number): ProgressInfo {
    return {
      spp,
      target: this.target,
      raysPerSecond: this.rays.rate(performance.now()),
      noise: this.noise,
    };
  }

  stats(): RenderStatsInfo {
    const job = this.activeJob();
    const now = performance.now();
    const textureBytes = job && this.mode.display === 'webgl2' ? job.width * job.height * 16 : 0;
    return {
      ...this.progressInfo(job ? job.passesDone() : 0),
      fps: this.frames.rate(now),
      frameMs: this.frameMs,
      width: job?.width ?? 0,
      height: job?.height ?? 0,
      workers: this.pool.size,
      memoryBytes: (this.full?.memoryBytes ?? 0) + (this.preview?.memoryBytes ?? 0) + textureBytes,
      rejected: job?.rejected() ?? 0,
      paused: this.isPaused,
    };
  }

  /** Segments traced since the controller was made (for benchmarks: a difference over time). */
  segmentsTraced(): number {
    return this.segmentsTotal;
  }

  /** Fractional passes of the active film (for a smooth progress bar). */
  progress(): number {
    return this.activeJob()?.progress() ?? 0;
  }

  // ---- output ------------------------------------------------------------

  readLinear(): { width: number; height: number; rgb: Float32Array } {
    const job = this.full;
    if (!job) return { width: 0, height: 0, rgb: new Float32Array(0) };
    return { width: job.width, height: job.height, rgb: job.film.mean() };
  }

  /** The canvas's displayed pixels (redrawn first, so WebGL2's buffer is current). */
  readDisplay(): DisplayPixels {
    // Drawn as a frame would be (only changed rows uploaded), so a read-back
    // checks the incremental upload too; WebGL2 needs the draw because its
    // buffer is not preserved after a frame is shown.
    const job = this.activeJob();
    if (job) this.present(job, true);
    return this.display.readPixels();
  }

  toBlob(): Promise<Blob> {
    const job = this.full;
    if (!job) return Promise.reject(new Error('no image yet'));
    const image = new ImageData(job.width, job.height);
    tonemapSums(job.film.sums, this.exposure, image.data);
    const canvas = document.createElement('canvas');
    canvas.width = job.width;
    canvas.height = job.height;
    canvas.getContext('2d')!.putImageData(image, 0, 0);
    return new Promise((resolve, reject) =>
      canvas.toBlob(
        (b) => (b ? resolve(b) : reject(new Error('PNG encoding failed'))),
        'image/png',
      ),
    );
  }

  toPFM(): Uint8Array {
    const { width, height, rgb } = this.readLinear();
    return encodePfm(width, height, rgb);
  }

  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    cancelAnimationFrame(this.raf);
    this.detachControls?.();
    this.full?.setVersion(-1);
    this.preview?.setVersion(-1);
    this.pool.unregister(this.client);
    releasePool(this.pool);
    this.display.destroy();
  }
}
