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
 * The animation-frame loop runs only while something can change on screen:
 * samples arriving, a pending resize, a redraw asked for. Paused, converged
 * or in a hidden tab it stops asking for frames (a page of idle views costs
 * nothing), and every call that can change the picture wakes it again.
 */
import {
  DEFAULT_SAMPLER,
  LIMITS,
  PathTracer,
  SceneError,
  compileScene,
  encodePfm,
  estimateNoise,
  countSkippedTriangles,
  isGlbBytes,
  isModelFileName,
  isValidatedScene,
  loadBareModel,
  parseScene,
  sceneWarnings,
  resolveSceneFiles,
  sceneNeedsFiles,
  tonemapSums,
  validateScene,
  type CameraDesc,
  packScene,
  unpackScene,
  type CompiledScene,
  type PackedScene,
  type Scene,
  type LoadStage,
  type ResolveOptions,
  type SceneFileReader,
} from '../core/index.ts';
import { GLTF_FILE_BYTES } from '../core/gltf/load.ts';
import { sceneSizeProblem } from '../core/scene/load.ts';
import type { JobConfig } from '../../workers/render-protocol.ts';
import { compositeBackdrop, type Backdrop } from './backdrop.ts';
import type { Display, DisplayPixels } from './display.ts';
import { StandInDisplay } from './display-standin.ts';
import type { FilmJob, FilmSnapshot } from './film-job.ts';
import { MAX_FILM_SIDE } from './film-cap.ts';
import { FilmMemoryError, Films } from './films.ts';
import { FirstPass, type Timeline } from './first-pass.ts';
import { attachCameraControls } from './interaction.ts';
import { chooseCompute, createDisplay } from './mode.ts';
import { dollyCamera, orbitCamera } from './orbit.ts';
import { releasePool, sharedPool, type PoolClient, type WorkerPool } from './pool.ts';
import { ByteLimitError, readBlobBounded, readResponseBounded } from './read-bounded.ts';
import { RateMeter } from './rate-meter.ts';
import { loadModelInWorker, type LoadedModel, type ModelJob } from './model-load.ts';
import { urlSceneFiles, type PortableReader } from './scene-files.ts';
import { SharedFilmJob } from './shared-job.ts';
import { TraceClock } from './trace-clock.ts';
import type {
  FallbackInfo,
  PathTracerController,
  PathTracerOptions,
  ProgressInfo,
  RenderStatsInfo,
} from './types.ts';

let nextJobId = 1;

/**
 * A scene ready to install; compiled and packed already when the model worker loaded it
 * (which also counted what the model's arrays, left out of `scene`, said).
 */
type Loaded = { scene: Scene } | LoadedModel;

/** A model file's bytes, at most GLTF_FILE_BYTES (checked by its size before reading). */
async function readModelBlob(blob: Blob, name: string): Promise<Uint8Array> {
  if (blob.size > GLTF_FILE_BYTES) throw new Error(`${name}: ${modelSizeProblem(blob.size, true)}`);
  return new Uint8Array(await blob.arrayBuffer());
}

/** The last component of a URL's path, as its file's name. */
function fileNameOf(url: string): string {
  const last = new URL(url).pathname.replace(/^.*\//, '');
  try {
    return decodeURIComponent(last) || 'model.glb';
  } catch {
    return last || 'model.glb';
  }
}

function modelSizeProblem(size: number, exact: boolean): string {
  const got = exact ? `${size}` : `at least ${size}`;
  return `a glTF model must be at most ${GLTF_FILE_BYTES} bytes (1 GiB), got ${got} bytes`;
}
/** Noise is estimated at most this often (it reads the whole film). */
const NOISE_INTERVAL_MS = 500;

export class Controller extends EventTarget implements PathTracerController {
  readonly canvas: HTMLCanvasElement;
  private modeInfo: FallbackInfo;
  private readonly options: PathTracerOptions;
  private readonly id = nextJobId++;
  private readonly pool: WorkerPool;
  private readonly client: PoolClient;
  private readonly display: Display;
  private currentScene: Scene | null = null;
  private compiled: CompiledScene | null = null;
  /** The compiled scene packed for the workers (shared memory when the page is isolated). */
  private packed: PackedScene | null = null;
  private sceneId = 0;
  private camera: CameraDesc | null = null;
  private bounces = 6;
  private exposure: number;
  private seed: number;
  private target: number;
  private isPaused = false;
  private version = 0;
  private config: JobConfig | null = null;
  private readonly films: Films;
  /** The pending animation frame; 0 while the loop is idle. */
  private raf = 0;
  /** Animation frames the loop has run (see framesRun). */
  private framesCount = 0;
  /** Exposure changed: redraw without new samples. */
  private displayDirty = true;
  private convergedSent = false;
  private destroyed = false;
  private readonly rays = new RateMeter();
  private readonly frames = new RateMeter();
  private frameMs = 0;
  private segmentsTotal = 0;
  private noise = NaN;
  private noiseAt = 0;
  private changedSinceNoise = false;
  private lastProgressAt = 0;
  /** spp and target of the last progress event (-1: none since the last restart). */
  private lastProgressSpp = -1;
  private lastProgressTarget = -1;
  private resizeObserver: ResizeObserver | null = null;
  private detachControls: (() => void) | null = null;
  private picker: PathTracer | null = null;
  /** The model worker's current load, stopped when a newer scene or destroy() comes. */
  private modelJob: ModelJob | null = null;
  private sceneRequested = false;
  /**
   * Bumped by every scene request (setScene, load) and by destroy: a request
   * that is no longer the latest when its fetch or file read ends is
   * dropped, so the last request always wins.
   */
  private sceneRequest = 0;
  /** Aborts the fetch of a load that a newer request superseded. */
  private loadAbort: AbortController | null = null;
  /** The last picture, shown where the active film has no sample yet. */
  private backdrop: Backdrop | null = null;
  /** The film the display showed last (its pixels are what is on screen). */
  private shownJob: FilmJob | null = null;
  /** The pointer (or keyboard) is moving the camera: restarts go to the preview film. */
  private interacting = false;
  /** The quick first pass of a new scene and the automatic scale. */
  private readonly firstPass: FirstPass;
  /** Tracing time of the active film since its last restart. */
  private readonly clock = new TraceClock();
  /** The accumulator-cap reason last reported with a `fallback` event (null: none). */
  private capReported: string | null = null;
  constructor(canvas: HTMLCanvasElement, options: PathTracerOptions) {
    super();
    this.canvas = canvas;
    this.options = options;
    this.exposure = options.exposure ?? 1;
    this.seed = options.seed ?? 0;
    this.target = options.spp ?? 512;
    this.isPaused = options.autoplay === false;
    const compute = chooseCompute(options);
    const { display, why } = createDisplay(canvas, options);
    this.display = display;
    this.modeInfo = {
      display: display.mode,
      compute: compute.compute,
      reason: `${why}; ${compute.why}`,
    };
    if (display instanceof StandInDisplay) {
      display.onChange = (_event, reason) => {
        // The picture moved to another canvas (or back): draw it all, now.
        this.modeInfo = { ...this.modeInfo, display: display.mode, reason };
        this.displayDirty = true;
        this.emit('fallback', this.mode);
        this.wake();
      };
    }
    this.pool = sharedPool(options, options.workers);
    this.films = new Films(canvas, options, compute.compute, () => this.pool.size);
    // A film wider than a texture could not be shown.
    if (display instanceof StandInDisplay) {
      this.films.maxSide = Math.min(MAX_FILM_SIDE, display.maxTextureSize);
    }
    this.firstPass = new FirstPass(this.films);
    if (options.workers !== undefined && options.workers !== this.pool.size) {
      void this.pool.setSize(options.workers);
    }
    this.client = {
      id: this.id,
      config: () => this.config!,
      nextTask: () => this.films.active()?.nextTask?.(this.id) ?? null,
      onResult: (r) => {
        const job = this.activeJob();
        if (job && r.version === this.version) job.onResult?.(r);
        this.wake();
      },
      onWorkerError: (message) => this.emit('error', { message }),
      onTaskLost: (task) => {
        const job = this.activeJob();
        if (job && task.version === this.version) job.onTaskLost?.(task);
        this.wake();
      },
      recover: () => {
        let done = true;
        for (const job of [this.films.full, this.films.preview]) {
          if (job?.recover && !job.recover()) done = false;
        }
        this.wake();
        return done;
      },
    };
    if (options.cameraControls !== false) {
      this.detachControls = attachCameraControls(this, canvas);
    }
    // Let the caller attach listeners before the first events.
    queueMicrotask(() => this.emit('fallback', this.mode));
    // The first scene loads in a microtask too, so a 'load' listener added
    // right after createPathTracer hears it; a scene set by the caller
    // before then wins.
    queueMicrotask(() => {
      if (this.sceneRequested) return;
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
    if (this.destroyed || this.raf !== 0) return;
    this.raf = requestAnimationFrame(this.frame);
  }

  /** How it runs now: the display changes while a lost WebGL2 context is away. */
  get mode(): FallbackInfo {
    return this.modeInfo;
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

  // ---- scene -------------------------------------------------------------

  /**
   * Loads a scene. A request superseded by a later one (setScene or load)
   * before it was read resolves without loading anything.
   */
  async setScene(value: unknown, files?: SceneFileReader): Promise<void> {
    const request = this.newSceneRequest();
    // Mesh, glTF and environment-map files: fetched relative to the page unless the
    // caller says how (a scene's URL, dropped files, a preset's assets).
    const reader = files ?? this.options.files ?? urlSceneFiles(document.baseURI);
    return this.install(request, () => this.readScene(value, reader));
  }

  /** A new scene request: the older ones lose (a fetch in flight is aborted, a model load stopped). */
  private newSceneRequest(): number {
    this.sceneRequested = true;
    this.loadAbort?.abort();
    this.loadAbort = null;
    this.modelJob?.cancel();
    return ++this.sceneRequest;
  }

  /**
   * Reads a scene: a File named `.glb` / `.gltf`, or bytes that are a GLB, is a bare
   * model (core/gltf/bare-scene.ts), anything else a pathwise-scene/1 scene.
   */
  private async readScene(value: unknown, files: SceneFileReader): Promise<Loaded> {
    if (value instanceof Blob) {
      const name = value instanceof File ? value.name : '';
      if (isModelFileName(name)) {
        return this.readModel(await readModelBlob(value, name), name, files);
      }
      // Bytes and files get the loader's byte bound and strict UTF-8, as on the command line.
      value = await readBlobBounded(value, LIMITS.fileBytes);
    }
    if (value instanceof Uint8Array && isGlbBytes(value)) {
      return this.readModel(value, 'model.glb', files);
    }
    const scene = isValidatedScene(value)
      ? value
      : typeof value === 'string' || value instanceof Uint8Array
        ? parseScene(value)
        : validateScene(value);
    if (!sceneNeedsFiles(scene)) return { scene };
    // A scene file's glTF shapes load on the page (its reader may be any object).
    const hasGltf = scene.shapes.some((s) => s.type === 'gltf' && s.data === null);
    return {
      scene: await resolveSceneFiles(scene, files, hasGltf ? await this.gltfPlatform() : {}),
    };
  }

  /**
   * A bare model, framed at the aspect ratio of the picture it will be shown in: loaded,
   * compiled and packed in the model worker (model-load.ts) when its files can be read
   * there (a URL, dropped files), else on the page.
   */
  private async readModel(
    bytes: Uint8Array,
    name: string,
    files: SceneFileReader,
  ): Promise<Loaded> {
    const width = this.options.width ?? Math.round(this.canvas.clientWidth || 512);
    const height = this.options.height ?? Math.round(this.canvas.clientHeight || 512);
    // Only the aspect ratio matters here (the film follows the canvas).
    const clamp = (n: number) => Math.min(4096, Math.max(1, n));
    const source = (files as Partial<PortableReader>).source;
    if (source !== undefined && typeof Worker !== 'undefined') {
      this.modelJob?.cancel();
      const job = loadModelInWorker(
        {
          bytes,
          name,
          source,
          width: clamp(width),
          height: clamp(height),
          shared: this.mode.compute === 'shared',
        },
        (stage, done, total) => this.progressLoad(stage, done, total),
      );
      this.modelJob = job;
      const loaded = await job.promise;
      if (loaded !== null) return loaded;
    }
    const scene = await loadBareModel(bytes, name, files, {
      ...(await this.gltfPlatform()),
      width: clamp(width),
      height: clamp(height),
    });
    return { scene };
  }

  /**
   * What loading glTF takes from the browser (gltf-browser.ts, imported only when a
   * model is loaded): createImageBitmap for images, MikkTSpace's WebAssembly, texels
   * in shared memory when the workers share it, and progress as `loadprogress` events.
   */
  private async gltfPlatform(): Promise<ResolveOptions> {
    const { browserTangentGenerator, decodeImageBrowser } =
      await import('../../workers/gltf-browser.ts');
    return {
      decodeImage: decodeImageBrowser,
      // Without it, normal maps of primitives that have no tangents are ignored with
      // a warning (the loader says so) rather than failing the whole model.
      generateTangents: await browserTangentGenerator().catch(() => null),
      sharedTextures: this.mode.compute === 'shared',
      onProgress: (stage, done, total) => this.progressLoad(stage, done, total),
    };
  }

  private progressLoad(stage: LoadStage, done: number, total: number): void {
    this.emit('loadprogress', { stage, done, total });
  }

  /**
   * Installs the scene `read` gives, unless a later request came first; every failure
   * is an `error` event and a rejection with the loader's message.
   */
  private async install(request: number, read: () => Promise<Loaded>): Promise<void> {
    let loaded: Loaded;
    try {
      loaded = await read();
    } catch (e) {
      // A superseded request's failure is nobody's concern any more.
      if (request !== this.sceneRequest) return;
      if (e instanceof ByteLimitError) e = new SceneError([sceneSizeProblem(e.size, e.exact)]);
      const message = e instanceof Error ? e.message : String(e);
      this.emit('error', { message });
      throw new Error(message);
    }
    // A later call started while this one read its files: that one wins.
    if (request !== this.sceneRequest || this.destroyed) return;
    const { scene } = loaded;
    const packed = 'packed' in loaded ? loaded.packed : undefined;
    const first = this.currentScene === null;
    const big =
      packed === undefined && scene.shapes.some((s) => s.type === 'gltf' || s.type === 'mesh');
    if (big) {
      // The BVH build is synchronous: let the page show the stage first.
      this.progressLoad('compile', 0, 1);
      await new Promise((resolve) => setTimeout(resolve, 0));
      if (request !== this.sceneRequest || this.destroyed) return;
    }
    let compiled: CompiledScene;
    let packedScene: PackedScene;
    try {
      if (packed !== undefined) {
        // Compiled and packed by the model worker: views into its buffer.
        compiled = unpackScene(packed);
        packedScene = packed;
      } else {
        compiled = compileScene(scene);
        if (big) this.progressLoad('compile', 1, 1);
        // Compiled once here (the picker uses it too) and shipped packed: the
        // workers neither parse nor compile nor build a BVH.
        packedScene = packScene(compiled, this.mode.compute === 'shared');
      }
    } catch (e) {
      if (!(e instanceof RangeError)) throw e;
      // Memory the scene's arrays (shared ones, when isolated) could not get.
      const message = `could not allocate memory for the compiled scene: ${e.message}`;
      this.emit('error', { message });
      throw new Error(message);
    }
    this.currentScene = scene;
    this.compiled = compiled;
    this.packed = packedScene;
    this.picker = null;
    this.sceneId++;
    this.camera = { ...scene.camera };
    this.bounces =
      first && this.options.bounces !== undefined
        ? this.options.bounces
        : scene.settings.maxBounces;
    this.firstPass.sceneLoaded(performance.now());
    this.restart();
    const warnings = 'warnings' in loaded ? loaded.warnings : sceneWarnings(scene);
    const skippedTriangles =
      'skippedTriangles' in loaded ? loaded.skippedTriangles : countSkippedTriangles(scene);
    this.emit('load', { scene, skippedTriangles, warnings });
    if (warnings.length > 0) this.emit('warning', { messages: warnings });
  }

  /** Fetches and loads a scene; superseded like setScene (its fetch is aborted then). */
  async load(url: string): Promise<void> {
    const request = this.newSceneRequest();
    const abort = typeof AbortController !== 'undefined' ? new AbortController() : null;
    this.loadAbort = abort;
    let bytes: Uint8Array;
    let base: string;
    let model = false;
    try {
      model = isModelFileName(new URL(url, document.baseURI).pathname);
    } catch {
      // Not a URL: fetch says so below.
    }
    try {
      if (model) this.progressLoad('read', 0, 1);
      const response = await fetch(url, abort ? { signal: abort.signal } : undefined);
      if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
      base = response.url || new URL(url, document.baseURI).href;
      bytes = await readResponseBounded(response, model ? GLTF_FILE_BYTES : LIMITS.fileBytes);
    } catch (e) {
      if (request !== this.sceneRequest) return;
      const message =
        e instanceof ByteLimitError
          ? `${url}: ${model ? modelSizeProblem(e.size, e.exact) : sceneSizeProblem(e.size, e.exact)}`
          : e instanceof Error
            ? e.message
            : String(e);
      this.emit('error', { message });
      throw new Error(message);
    }
    if (request !== this.sceneRequest) return;
    if (this.loadAbort === abort) this.loadAbort = null;
    if (model) this.progressLoad('read', 1, 1);
    // The files the scene (or the model) names live beside it.
    const files = urlSceneFiles(base);
    if (model || isGlbBytes(bytes)) {
      const name = fileNameOf(base);
      return this.install(request, () =>
        this.readModel(bytes, name, files).catch((e: unknown): never => {
          throw new Error(`${name}: ${e instanceof Error ? e.message : String(e)}`);
        }),
      );
    }
    await this.setScene(bytes, files);
  }

  // ---- restart machinery -------------------------------------------------

  /** New configuration version, reset of the active film, configuration to the workers. */
  private restart(): void {
    if (!this.currentScene || !this.camera || this.destroyed) return;
    this.captureBackdrop();
    this.films.wantPreview = this.interacting || this.firstPass.active;
    let active: FilmJob;
    try {
      active = this.films.select(this.target);
    } catch (e) {
      this.filmFailed(e);
      return;
    }
    this.reportCap();
    this.version++;
    // Version first, then reset: a worker still holding the old
    // configuration can claim nothing once the version moved on.
    active.setVersion(this.version);
    active.setTarget(this.target);
    active.setPaused(this.isPaused);
    active.reset();
    active.takeRenewed?.();
    const shared = active instanceof SharedFilmJob ? active : null;
    this.config = {
      mode: this.mode.compute,
      version: this.version,
      sceneId: this.sceneId,
      scene: this.packed!,
      width: active.width,
      height: active.height,
      maxBounces: this.bounces,
      seed: this.seed,
      estimator: 'nee-mis',
      sampler: DEFAULT_SAMPLER,
      camera: this.camera,
      stripeRows: active.stripeRows,
      film: shared?.filmBuffer,
      ctrl: shared?.ctrlBuffer,
      journal: shared?.journalBuffer,
    };
    this.convergedSent = false;
    this.rays.reset();
    this.noise = NaN;
    this.lastProgressSpp = -1;
    this.clock.restart(performance.now(), this.isPaused);
    this.firstPass.interrupted();
    this.pool.register(this.client);
    this.pool.configure(this.client);
    this.pool.kick();
    this.wake();
  }

  /** No film could be made (the accumulator cap, or no memory): said once, as an error. */
  private filmFailed(e: unknown): void {
    if (!(e instanceof FilmMemoryError)) throw e;
    this.emit('error', { message: e.message });
  }

  /** A full film smaller than the canvas asks is reported once per size, as a fallback. */
  private reportCap(): void {
    if (this.films.previewing) return;
    const cap = this.films.capped;
    const reason = cap?.reason ?? null;
    if (reason === this.capReported) return;
    this.capReported = reason;
    if (cap) this.emit('fallback', { ...this.mode, reason, renderScale: cap.scale });
  }

  reset(): void {
    const job = this.activeJob();
    if (!job || !this.config) return;
    this.captureBackdrop();
    job.reset();
    if (job instanceof SharedFilmJob && job.takeRenewed()) {
      // The film moved to new buffers (a lock its holder would not let go):
      // the workers need them.
      this.config = {
        ...this.config,
        film: job.filmBuffer,
        ctrl: job.ctrlBuffer,
        journal: job.journalBuffer,
      };
      this.pool.configure(this.client);
    }
    this.clock.restart(performance.now(), this.isPaused);
    this.convergedSent = false;
    this.displayDirty = true;
    this.noise = NaN;
    this.lastProgressSpp = -1;
    this.pool.kick();
    this.wake();
  }

  pause(): void {
    this.clock.pause(performance.now());
    this.isPaused = true;
    this.activeJob()?.setPaused(true);
    // Stripes already in hand still finish and should be shown; the loop
    // stops once they have.
    this.wake();
  }

  resume(): void {
    this.clock.resume(performance.now());
    // A measurement window must not span a pause.
    if (this.isPaused) this.firstPass.interrupted();
    this.isPaused = false;
    this.activeJob()?.setPaused(false);
    this.pool.kick();
    this.wake();
  }

  setTargetSpp(spp: number): void {
    this.target = Math.max(1, Math.floor(spp));
    this.films.full?.setTarget(this.target);
    this.films.preview?.setTarget(this.target);
    this.convergedSent = false;
    this.pool.kick();
    this.wake();
  }

  setBounces(bounces: number): void {
    this.bounces = Math.max(0, Math.floor(bounces));
    this.restart();
  }

  setExposure(exposure: number): void {
    this.exposure = exposure;
    this.displayDirty = true;
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
      this.filmFailed(e);
    }
  }

  /** See PathTracerOptions.sizeStep; applies from the next restart that sizes the film. */
  setSizeStep(step: number): void {
    this.films.sizeStep = Math.max(1, Math.floor(step));
  }

  /** Max bounces in use. */
  get maxBounces(): number {
    return this.bounces;
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
    if (!this.camera || !this.compiled || !this.films.full) return false;
    const { width, height } = this.films.full;
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

  // ---- backdrop ------------------------------------------------------------

  /** What is on screen (the shown film over the old backdrop) becomes the backdrop. */
  private captureBackdrop(): void {
    const job = this.shownJob;
    if (!job) return;
    this.backdrop = compositeBackdrop(job.film.sums, job.width, job.height, this.backdrop);
  }

  // ---- per frame ---------------------------------------------------------

  /**
   * Blanks the display after a reset, uploads the rows that changed since
   * the last draw and draws; with
   * `force`, draws even when nothing changed. Returns whether it drew.
   */
  private present(job: FilmJob, force: boolean): boolean {
    const cleared = job.takeCleared();
    const dirty = job.takeDirtyRows();
    if (!force && !cleared && dirty.length === 0 && !this.displayDirty) return false;
    if (cleared) this.display.clear(job.width, job.height, this.backdrop);
    this.display.draw(job.film.sums, job.width, job.height, this.exposure, dirty);
    this.displayDirty = false;
    this.shownJob = job;
    return true;
  }

  private readonly frame = (now: number): void => {
    this.raf = 0;
    if (this.destroyed) return;
    this.framesCount++;
    try {
      if (this.films.follow(now, this.target)) this.restart();
    } catch (e) {
      this.filmFailed(e);
    }
    // The speed measurements may hand over to another film (a restart):
    // this frame then draws that one, over the picture captured as backdrop.
    const before = this.activeJob();
    const paused = this.isPaused;
    if (before && this.firstPass.advance(now, before, this.target, paused, this.interacting)) {
      this.restart();
    }
    const job = this.activeJob();
    // No scene yet: setScene's restart wakes the loop. A resize waiting to
    // settle is checked again on the next frame.
    if (!job) {
      if (this.films.resizePending) this.wake();
      return;
    }
    const segments = job.takeSegments();
    this.segmentsTotal += segments;
    this.rays.add(now, segments);
    const t0 = performance.now();
    const drew = this.present(job, false);
    if (drew) {
      this.frameMs = performance.now() - t0;
      this.frames.add(now, 1);
      this.changedSinceNoise = true;
    }
    // Preview passes are not the image's samples: the full film has none yet.
    const spp = this.films.previewing ? 0 : job.passesDone();
    if (drew) this.firstPass.drew(now, job, spp);
    // Once converged (or paused) nothing changes, so the film is not read
    // again for the noise estimate.
    if (this.changedSinceNoise && now - this.noiseAt > NOISE_INTERVAL_MS) {
      this.noiseAt = now;
      this.changedSinceNoise = false;
      // Every 4th pixel is plenty for a figure shown with two digits.
      this.noise = estimateNoise(job.film, 4);
    }
    // Progress only when it says something new, at most ~10 times a second;
    // the last step (the target reached) goes out at once.
    const progressChanged = spp !== this.lastProgressSpp || this.target !== this.lastProgressTarget;
    if (progressChanged && (now - this.lastProgressAt > 100 || spp >= this.target)) {
      this.lastProgressAt = now;
      this.lastProgressSpp = spp;
      this.lastProgressTarget = this.target;
      this.emit('progress', this.progressInfo(spp));
    }
    if (!this.convergedSent && !this.films.previewing && spp >= this.target) {
      this.convergedSent = true;
      this.emit('converged', this.progressInfo(spp));
    }
    // Another frame only while the picture can still change: samples are
    // (or may soon be) arriving, a draw or an event is owed, a resize is
    // settling or the pointer drags the preview.
    const tracing = !this.isPaused && spp < this.target;
    const owed =
      spp !== this.lastProgressSpp || this.target !== this.lastProgressTarget || this.displayDirty;
    if (
      drew ||
      segments > 0 ||
      tracing ||
      owed ||
      job.busy() ||
      (this.firstPass.active && !this.isPaused) ||
      this.films.resizePending ||
      this.films.wantPreview ||
      this.films.previewing
    ) {
      this.wake();
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
      ...this.progressInfo(job && !this.films.previewing ? job.passesDone() : 0),
      fps: this.frames.rate(now),
      frameMs: this.frameMs,
      width: job?.width ?? 0,
      height: job?.height ?? 0,
      workers: this.pool.size,
      memoryBytes: this.films.memoryBytes + textureBytes + (this.backdrop?.rgba.byteLength ?? 0),
      rejected: job?.rejected() ?? 0,
      paused: this.isPaused,
    };
  }

  /**
   * Animation frames the controller has run: constant while it idles
   * (paused, converged, hidden), for tests and benchmarks.
   */
  framesRun(): number {
    return this.framesCount;
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
    return this.segmentsTotal;
  }

  /** Fractional passes of the active film (for a smooth progress bar). */
  progress(): number {
    return this.films.previewing ? 0 : (this.activeJob()?.progress() ?? 0);
  }

  /**
   * The render scale in use, whether it was chosen automatically, and the
   * measured speed (samples per second) it was chosen from.
   */
  renderScaleInfo(): { scale: number; auto: boolean; samplesPerSecond: number } {
    return {
      scale: this.films.renderScale,
      auto: this.films.autoScale,
      samplesPerSecond: this.firstPass.rate,
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
      version: this.version,
      width: job.width,
      height: job.height,
      sums: job.film.sums,
      hi: job.film.hi,
      lo: job.film.lo,
      spp: job.passesDone(),
      seconds: this.clock.seconds(performance.now()),
      camera: this.camera,
      bounces: this.bounces,
      seed: this.seed,
    };
  }

  // ---- output ------------------------------------------------------------

  readLinear(): { width: number; height: number; rgb: Float32Array } {
    const job = this.films.full;
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
    const job = this.films.full;
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
    // A scene still loading is dropped (and its fetch aborted).
    this.newSceneRequest();
    cancelAnimationFrame(this.raf);
    this.raf = 0;
    this.resizeObserver?.disconnect();
    this.modelJob?.cancel();
    this.detachControls?.();
    this.films.park();
    this.pool.unregister(this.client);
    releasePool(this.pool);
    this.display.destroy();
  }
}
