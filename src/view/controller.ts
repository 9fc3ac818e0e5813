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
 * when the pointer rests the full film takes over again. Each new scene
 * starts the same way: one quick pass in the preview film puts a whole
 * picture up at once and measures the speed from which the automatic
 * render scale is chosen (auto-scale.ts).
 *
 * A restart never blanks the screen: what was shown becomes the backdrop
 * (backdrop.ts), which the display keeps under every pixel the new pass
 * has not reached yet, and passes visit stripes spread over the frame
 * (stripeOrder), so the new picture refines on top of the old one
 * everywhere at once.
 *
 * The animation-frame loop (frame-loop.ts) runs only while something can
 * change on screen, and every call that can change the picture wakes it.
 *
 * The class wires the parts: scene requests (scene-request.ts), the job in
 * the worker pool (render-job.ts), the display and backdrop (presenter.ts),
 * rates and progress events (progress-meter.ts), modes and fallbacks
 * (fallbacks.ts), click-to-focus (focus-pick.ts) and export (film-export.ts).
 */
import {
  unpackScene,
  emptyImageMessage,
  encodePfm,
  type CameraDesc,
  type CompiledScene,
  type PackedScene,
  type Scene,
  type SceneFileReader,
} from '../core/index.ts';
import type { JobConfig } from '../../workers/browser/render-protocol.ts';
import type { DisplayPixels } from './display.ts';
import { StandInDisplay } from './display-standin.ts';
import type { FilmJob, FilmSnapshot } from './film-job.ts';
import { MAX_FILM_SIDE } from './film-cap.ts';
import { linearImage, pngBlob } from './film-export.ts';
import { Fallbacks } from './fallbacks.ts';
import { Films } from './films.ts';
import { DenoiseControl } from './denoise-control.ts';
import type { DenoisedImage } from './denoise-view.ts';
import { FirstPass, type Timeline } from './first-pass.ts';
import { FocusPicker } from './focus-pick.ts';
import { FrameLoop, REST_DRAW_MS } from './frame-loop.ts';
import { attachCameraControls } from './interaction.ts';
import { chooseCompute, createDisplay } from './mode.ts';
import { dollyCamera, orbitCamera } from './orbit.ts';
import { sharedPool } from './pool.ts';
import { Presenter } from './presenter.ts';
import { ProgressMeter } from './progress-meter.ts';
import { RenderJob } from './render-job.ts';
import { SceneRequests } from './scene-request.ts';
import type {
  FallbackInfo,
  PathTracerController,
  PathTracerOptions,
  RenderStatsInfo,
} from './types.ts';

let nextJobId = 1;

export class Controller extends EventTarget implements PathTracerController {
  readonly canvas: HTMLCanvasElement;
  private readonly options: PathTracerOptions;
  private readonly id = nextJobId++;
  /** The configuration the workers render, and the pool they are in. */
  private readonly job: RenderJob;
  /** The display, the exposure and the backdrop. */
  private readonly screen: Presenter;
  /** The mode, and what could not be had (fallback and error events). */
  private readonly fallbacks: Fallbacks;
  /** setScene and load: the latest request wins. */
  private readonly requests: SceneRequests;
  private readonly loop: FrameLoop;
  private currentScene: Scene | null = null;
  private compiled: CompiledScene | null = null;
  /** The compiled scene packed for the workers (shared memory when the page is isolated). */
  private packed: PackedScene | null = null;
  private sceneId = 0;
  private camera: CameraDesc | null = null;
  private bounces = 6;
  private seed: number;
  private target: number;
  private isPaused = false;
  private readonly films: Films;
  private destroyed = false;
  /** Rates, noise, and the progress and converged events. */
  private readonly meter = new ProgressMeter({
    emit: (type, detail) => this.emit(type, detail),
    target: () => this.target,
    previewing: () => this.films.previewing,
    emptyImage: (rejected) => this.emptyImage(rejected),
  });
  private resizeObserver: ResizeObserver | null = null;
  private detachControls: (() => void) | null = null;
  private readonly focus = new FocusPicker();
  /** The pointer (or keyboard) is moving the camera: restarts go to the preview film. */
  private interacting = false;
  /** The quick first pass of a new scene and the automatic scale. */
  private readonly firstPass: FirstPass;
  /** The denoised picture of a resting view (options.denoise). */
  private readonly denoising: DenoiseControl;
  constructor(canvas: HTMLCanvasElement, options: PathTracerOptions) {
    super();
    this.canvas = canvas;
    this.options = options;
    const exposure = options.exposure ?? 1;
    this.seed = options.seed ?? 0;
    this.target = options.spp ?? 512;
    this.isPaused = options.autoplay === false;
    const compute = chooseCompute(options);
    const { display, why } = createDisplay(canvas, options);
    this.screen = new Presenter(display, exposure);
    const emit = (type: string, detail: unknown) => this.emit(type, detail);
    this.fallbacks = new Fallbacks(
      { display: display.mode, compute: compute.compute, reason: `${why}; ${compute.why}` },
      emit,
    );
    this.fallbacks.watch(display, () => {
      // The picture moved to another canvas (or back): draw it all, now.
      this.screen.dirty = true;
      this.emit('fallback', this.mode);
      this.wake();
    });
    const pool = sharedPool(options, options.workers);
    this.films = new Films(canvas, options, compute.compute, () => pool.size);
    // A film wider than a texture could not be shown.
    if (display instanceof StandInDisplay) {
      this.films.maxSide = Math.min(MAX_FILM_SIDE, display.maxTextureSize);
    }
    this.firstPass = new FirstPass(this.films);
    this.denoising = new DenoiseControl(
      options.denoise === true,
      {
        films: this.films,
        firstPass: this.firstPass,
        screen: this.screen,
        restart: () => this.restart(),
        wake: () => this.wake(),
        emit: (type, detail) => this.emit(type, detail),
        seconds: (now) => this.job.clock.seconds(now),
      },
      options.denoiseWorkers,
    );
    if (options.workers !== undefined && options.workers !== pool.size) {
      void pool.setSize(options.workers);
    }
    this.job = new RenderJob(this.id, pool, this.films, () => this.wake(), emit);
    this.requests = new SceneRequests({
      canvas,
      options,
      shared: () => this.mode.compute === 'shared',
      hasScene: () => this.currentScene !== null,
      destroyed: () => this.destroyed,
      emit,
      use: (scene, packed, first, compiled) => this.use(scene, packed, first, compiled),
    });
    this.loop = new FrameLoop(
      {
        destroyed: () => this.destroyed,
        target: () => this.target,
        paused: () => this.isPaused,
        interacting: () => this.interacting,
        restDrawMs: () => this.options.restDrawMs ?? REST_DRAW_MS,
        restart: () => this.restart(),
        wakeWorkers: () => this.job.pool.kick(),
        denoise: (spp) => this.denoising.update(spp, this.target),
      },
      this.films,
      this.firstPass,
      this.screen,
      this.meter,
      this.fallbacks,
    );
    if (options.cameraControls !== false) {
      this.detachControls = attachCameraControls(this, canvas);
    }
    // Let the caller attach listeners before the first events.
    queueMicrotask(() => this.emit('fallback', this.mode));
    // The first scene loads in a microtask too, so a 'load' listener added
    // right after createPathTracer hears it; a scene set by the caller
    // before then wins.
    queueMicrotask(() => {
      if (this.requests.requested) return;
      if (options.scene !== undefined) this.setScene(options.scene).catch(() => {});
      else if (options.src) this.load(options.src).catch(() => {});
    });
    // The film follows the canvas's size, which is checked on each frame;
    // an idle loop learns of a new size from here.
    if (typeof ResizeObserver !== 'undefined') {
      this.resizeObserver = new ResizeObserver(() => this.wake());
      this.resizeObserver.observe(canvas);
    }
    this.wake();
  }

  /** Makes sure an animation frame is coming (the loop stops itself when idle). */
  private wake(): void {
    this.loop.wake();
  }

  /** How it runs now: the display changes while a lost WebGL2 context is away. */
  get mode(): FallbackInfo {
    return this.fallbacks.mode;
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
    return this.films.active();
  }

  /** The configuration the workers render (the browser tests read it too). */
  private get config(): JobConfig | null {
    return this.job.config;
  }

  // ---- scene -------------------------------------------------------------

  /**
   * Loads a scene. A request superseded by a later one (setScene or load)
   * before it was read resolves without loading anything.
   */
  setScene(value: unknown, files?: SceneFileReader): Promise<void> {
    return this.requests.setScene(value, files);
  }

  /** Fetches and loads a scene; superseded like setScene (its fetch is aborted then). */
  load(url: string): Promise<void> {
    return this.requests.load(url);
  }

  /** Installs a scene the requests compiled and packed, and restarts on it. */
  private use(
    scene: Scene,
    packed: PackedScene,
    first: boolean,
    compiled: CompiledScene | null,
  ): void {
    this.currentScene = scene;
    // Views of the packed scene, made when click-to-focus first needs them (unpacking
    // rebuilds light tables: a task the page need not run at every load).
    this.compiled = compiled;
    this.packed = packed;
    this.focus.invalidate();
    this.sceneId++;
    this.denoising.sceneLoaded();
    this.camera = { ...scene.camera };
    this.bounces =
      first && this.options.bounces !== undefined
        ? this.options.bounces
        : scene.settings.maxBounces;
    this.firstPass.sceneLoaded(performance.now());
    this.restart();
  }

  // ---- restart machinery -------------------------------------------------

  /** New configuration version, reset of the active film, configuration to the workers. */
  private restart(): void {
    if (!this.currentScene || !this.camera || this.destroyed) return;
    this.screen.captureBackdrop();
    this.denoising.restarted(performance.now());
    this.films.wantPreview = this.interacting || this.firstPass.active;
    let active: FilmJob;
    try {
      active = this.films.select(this.target);
    } catch (e) {
      this.fallbacks.filmFailed(e);
      return;
    }
    this.fallbacks.reportCap(this.films);
    const image = {
      mode: this.mode.compute,
      sceneId: this.sceneId,
      scene: this.packed!,
      maxBounces: this.bounces,
      seed: this.seed,
      camera: this.camera,
    };
    this.job.start(active, image, this.target, this.isPaused);
    this.meter.restarted();
    this.job.clock.restart(performance.now(), this.isPaused);
    this.firstPass.interrupted();
    this.job.send();
    this.wake();
  }

  reset(): void {
    const job = this.activeJob();
    if (!job || !this.config) return;
    this.screen.captureBackdrop();
    this.denoising.restarted(performance.now());
    this.job.reset(job, this.isPaused);
    this.screen.dirty = true;
    this.meter.cleared();
    this.job.pool.kick();
    this.wake();
  }

  /** Every sample of the film's first pass was dropped: an error, and no more passes of it. */
  private emptyImage(rejected: number): void {
    const job = this.activeJob();
    if (!job || !this.camera) return;
    this.pause();
    this.emit('error', {
      message: emptyImageMessage(this.camera, job.width, job.height, rejected),
    });
  }

  pause(): void {
    this.job.clock.pause(performance.now());
    this.isPaused = true;
    this.activeJob()?.setPaused(true);
    // Stripes already in hand still finish and should be shown; the loop
    // stops once they have.
    this.wake();
  }

  resume(): void {
    this.job.clock.resume(performance.now());
    // A measurement window must not span a pause.
    if (this.isPaused) this.firstPass.interrupted();
    this.isPaused = false;
    this.activeJob()?.setPaused(false);
    this.job.pool.kick();
    this.wake();
  }

  setTargetSpp(spp: number): void {
    this.target = Math.max(1, Math.floor(spp));
    this.films.full?.setTarget(this.target);
    this.films.preview?.setTarget(this.target);
    this.meter.targetChanged();
    this.job.pool.kick();
    this.wake();
  }

  setBounces(bounces: number): void {
    this.bounces = Math.max(0, Math.floor(bounces));
    this.restart();
  }

  setExposure(exposure: number): void {
    this.screen.exposure = exposure;
    this.screen.dirty = true;
    this.wake();
  }

  setSeed(seed: number): void {
    this.seed = seed >>> 0;
    this.restart();
  }

  setRenderScale(scale: number | null): void {
    if (scale === null) {
      // Back to automatic: measure again with a quick first pass.
      if (this.films.autoScale || this.films.fixedSize) return;
      this.films.autoScale = true;
      this.firstPass.start(performance.now());
      this.restart();
      return;
    }
    this.films.autoScale = false;
    this.firstPass.manual();
    this.films.renderScale = Math.max(0.05, Math.min(4, scale));
    try {
      if (this.films.ensureFull(this.target)) this.restart();
    } catch (e) {
      this.fallbacks.filmFailed(e);
    }
  }

  get denoise(): boolean {
    return this.denoising.on;
  }

  setDenoise(on: boolean): void {
    this.denoising.set(on);
  }

  /** See PathTracerOptions.adaptive; the film is remade and the render starts over. */
  setAdaptive(on: boolean): void {
    if (this.films.adaptive === on) return;
    this.films.adaptive = on;
    this.restart();
  }

  get adaptive(): boolean {
    return this.films.adaptive;
  }

  /** See PathTracerOptions.sizeStep; applies from the next restart that sizes the film. */
  setSizeStep(step: number): void {
    this.films.sizeStep = Math.max(1, Math.floor(step));
  }

  /** Max bounces in use. */
  get maxBounces(): number {
    return this.bounces;
  }

  setWorkers(count: number): Promise<void> {
    return this.job.setWorkers(count);
  }

  // ---- camera ------------------------------------------------------------

  getCamera(): CameraDesc {
    const c = this.camera ?? this.currentScene?.camera;
    if (!c) throw new Error('no scene loaded');
    return structuredClone(c);
  }

  setCamera(camera: CameraDesc): void {
    this.camera = structuredClone(camera);
    this.focus.invalidate();
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
    if (!this.camera || !this.packed || !this.films.full) return false;
    this.compiled ??= unpackScene(this.packed);
    const { width, height } = this.films.full;
    const distance = this.focus.distance(
      this.canvas,
      this.compiled,
      this.camera,
      this.bounces,
      width,
      height,
      x,
      y,
    );
    if (!(distance > 0)) return false;
    if (this.camera.aperture > 0) {
      this.setCamera({ ...this.camera, focusDistance: distance });
    } else {
      // A pinhole images every distance sharply: keep the focus for when the
      // aperture opens, but do not throw away the samples.
      this.camera = { ...this.camera, focusDistance: distance };
      this.job.setCamera(this.camera);
    }
    return true;
  }

  /** Interaction hooks: the preview film while the pointer moves, the full film when it rests. */
  beginPreview(): void {
    this.interacting = true;
    this.films.wantPreview = true;
    this.wake();
  }

  endPreview(): void {
    this.interacting = false;
    this.films.wantPreview = this.firstPass.active;
    // The quick first pass, if still running, hands over to the full film itself.
    if (!this.films.previewing || this.firstPass.active) return;
    this.restart();
  }

  stats(): RenderStatsInfo {
    const job = this.activeJob();
    const now = performance.now();
    const textureBytes = job && this.mode.display === 'webgl2' ? job.width * job.height * 16 : 0;
    return {
      ...(job && !this.films.previewing
        ? this.meter.info(job.passesDone(), job.meanSamples())
        : this.meter.info(0)),
      fps: this.meter.fps(now),
      frameMs: this.meter.frameMs,
      width: job?.width ?? 0,
      height: job?.height ?? 0,
      workers: this.job.pool.size,
      memoryBytes: this.films.memoryBytes + textureBytes + this.screen.backdropBytes,
      rejected: job?.rejected() ?? 0,
      paused: this.isPaused,
      denoised: this.denoising.info(),
    };
  }

  /**
   * Animation frames the controller has run: constant while it idles
   * (paused, converged, hidden), for tests and benchmarks.
   */
  framesRun(): number {
    return this.loop.count;
  }

  /**
   * When the latest scene was loaded, and when the first whole picture
   * (any film, the quick preview pass included) and the first whole image
   * of the full film were drawn (frame times, performance.now()), for
   * benchmarks of the time to first image.
   */
  timeline(): Timeline {
    return { ...this.firstPass.times };
  }

  /** Segments traced since the controller was made (for benchmarks: a difference over time). */
  segmentsTraced(): number {
    return this.meter.segmentsTotal;
  }

  /** Fractional passes of the active film (for a smooth progress bar). */
  progress(): number {
    return this.films.previewing ? 0 : (this.activeJob()?.progress() ?? 0);
  }

  /**
   * The render scale in use, whether it was chosen automatically, the
   * measured speed (samples per second) it was chosen from, and whether a
   * measurement that may still change it is under way (the quick pass, or
   * the warm one over the full film's next passes).
   */
  renderScaleInfo(): {
    scale: number;
    auto: boolean;
    samplesPerSecond: number;
    measuring: boolean;
  } {
    const full = this.films.full;
    return {
      scale: this.films.renderScale,
      auto: this.films.autoScale,
      samplesPerSecond: this.firstPass.rate,
      measuring:
        this.films.autoScale &&
        this.firstPass.measuring(full !== null && full.passesDone() >= this.target),
    };
  }

  /**
   * The full film as it is now, for measurements off the hot path (the
   * demo's error plot): its sums and per-pixel squared luminance (live
   * views, not copies: read them at once), complete passes, tracing
   * seconds, and the configuration version, which changes on every
   * restart. Null while the preview is active.
   */
  filmSnapshot(): FilmSnapshot | null {
    const job = this.films.full;
    if (!job || this.films.previewing || !this.config || !this.camera) return null;
    return {
      version: this.job.version,
      width: job.width,
      height: job.height,
      sums: job.film.sums,
      hi: job.film.hi,
      lo: job.film.lo,
      spp: job.passesDone(),
      seconds: this.job.clock.seconds(performance.now()),
      camera: this.camera,
      bounces: this.bounces,
      seed: this.seed,
    };
  }

  /**
   * The denoised picture on screen (RGBA sums with A = 1, a film's layout), with the
   * configuration version it belongs to; null when none is shown. Live, not a copy.
   */
  denoisedSnapshot(): (DenoisedImage & { version: number }) | null {
    return this.denoising.snapshot(this.job.version);
  }

  // ---- output ------------------------------------------------------------

  readLinear(): { width: number; height: number; rgb: Float32Array } {
    return linearImage(this.films.full);
  }

  /** The canvas's displayed pixels (redrawn first, so WebGL2's buffer is current). */
  readDisplay(): DisplayPixels {
    return this.screen.readPixels(this.activeJob());
  }

  toBlob(): Promise<Blob> {
    // The picture on screen: the denoised one while it is shown (the PFM stays raw).
    const denoised = this.denoising.snapshot(this.job.version);
    const full = this.films.full;
    const sums =
      denoised && full && denoised.width === full.width && denoised.height === full.height
        ? denoised.sums
        : full?.film.sums;
    return pngBlob(full, this.screen.exposure, sums);
  }

  toPFM(): Uint8Array {
    const { width, height, rgb } = this.readLinear();
    return encodePfm(width, height, rgb);
  }

  destroy(): void {
    if (this.destroyed) return;
    this.destroyed = true;
    // A scene still loading is dropped (and its fetch aborted).
    this.requests.newSceneRequest();
    this.loop.stop();
    this.resizeObserver?.disconnect();
    this.requests.cancelModel();
    this.detachControls?.();
    this.films.park();
    this.denoising.destroy();
    this.job.release();
    this.screen.display.destroy();
  }
}
