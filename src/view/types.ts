/**
 * The browser-side API shared by the demo (src/app) and the widget
 * (src/widget): `createPathTracer(canvas, options)` returns a
 * PathTracerController. This file is the contract; src/view implements it.
 */
import type {
  BareModelChoices,
  CameraDesc,
  LoadStage,
  Scene,
  SceneFileReader,
} from '../core/index.ts';

export type DisplayMode = 'webgl2' | 'canvas2d';
export type ComputeMode = 'shared' | 'transfer';

export interface FallbackInfo {
  display: DisplayMode;
  compute: ComputeMode;
  /** Plain words: why this mode runs (e.g. "page is not cross-origin isolated"). */
  reason: string;
  /**
   * Set when the render is smaller than the canvas asks, because of the
   * accumulator cap or memory that could not be had: the render scale in
   * use (relative to CSS size × devicePixelRatio).
   */
  renderScale?: number;
}

export interface ProgressInfo {
  /** Passes every pixel has had: its samples, or for an adaptive render the most any pixel holds. */
  spp: number;
  /** Mean samples per pixel: `spp` for a uniform render, fewer past an adaptive one's pilot. */
  samples: number;
  target: number;
  /** Segments (camera, bounce and shadow rays) per second, recent average. */
  raysPerSecond: number;
  /**
   * The RMS over pixels of each pixel's standard error (from its samples' variance),
   * over the image's mean luminance (core/film/noise.ts estimateNoise): the typical
   * error of one pixel, relative to the image's brightness. (The demo's Noise is its
   * error plot's per-cell figure instead.)
   */
  noise: number;
}

export interface RenderStatsInfo extends ProgressInfo {
  fps: number;
  /** Main-thread milliseconds per frame for upload + display. */
  frameMs: number;
  width: number;
  height: number;
  workers: number;
  memoryBytes: number;
  rejected: number;
  paused: boolean;
  /** The denoised picture on screen: the samples it was made from and the network's time. */
  denoised: { spp: number; ms: number } | null;
}

/** A denoised picture replaced the noisy one (the `denoise` option). */
export interface DenoisedInfo {
  spp: number;
  width: number;
  height: number;
  /** The network's time on its worker. */
  ms: number;
  /** From the film's last restart (a camera step, say) to this picture, in ms. */
  sinceRestartMs: number;
}

/**
 * The options of createPathTracer. A bare glTF model's choices (`environment`,
 * `variant`: core's BareModelChoices, docs/gltf.md) are read when a model loads.
 */
export interface PathTracerOptions extends BareModelChoices {
  /** A scene object (validated on load) or a URL to fetch. */
  scene?: unknown;
  src?: string;
  /**
   * How the mesh and environment-map files named by `scene` are read; default: URLs
   * relative to the page. A scene loaded from `src` reads them relative to its own URL.
   */
  files?: SceneFileReader;
  /**
   * Target passes, the samples per pixel of a uniform render; tracing stops there
   * (default 512). Past an adaptive render's pilot a pixel holds at most that many.
   */
  spp?: number;
  /** Max bounces; default from the scene. */
  bounces?: number;
  /** Display exposure (linear gain), default 1; never resets accumulation. */
  exposure?: number;
  seed?: number;
  /**
   * Render resolution relative to the canvas's CSS size × devicePixelRatio
   * (capped at maxPixelRatio). Left out, it is chosen from the speed
   * measured on the first pass, so that one pass takes about 0.2 s.
   */
  renderScale?: number;
  /** devicePixelRatio above this is not rendered (default 2). */
  maxPixelRatio?: number;
  /**
   * Round the render height to a multiple of this and the width to an even
   * number (keeping the aspect ratio). The demo uses it so that its pixels
   * tile the grid on which it compares the image with a reference.
   */
  sizeStep?: number;
  /** Fixed render size; overrides the canvas-derived size (tests, benchmarks). */
  width?: number;
  height?: number;
  /** Worker count; default navigator.hardwareConcurrency. */
  workers?: number;
  display?: 'auto' | DisplayMode;
  /** 'off' forces the transferable-stripe fallback even when isolated. */
  shared?: 'auto' | 'off';
  /** Where the worker script is, or a factory, for bundlers/CDNs that break the default URL. */
  workerUrl?: string | URL;
  workerFactory?: () => Worker;
  autoplay?: boolean;
  /** Orbit on drag, dolly on wheel. */
  cameraControls?: boolean;
  /**
   * While the view rests (from the second pass on), new samples are drawn at most this
   * often, in ms (default 100): each draw takes the page's thread from the render
   * workers. 0 draws every animation frame.
   */
  restDrawMs?: number;
  /**
   * Adaptive sampling (docs/adaptive-sampling.md): after a uniform pilot of 16 passes, each
   * pixel takes the later passes at a rate set by its neighbours' pilot error, as
   * `pathwise render --adaptive on` does, bit for bit. Default true; false samples
   * every pixel in every pass.
   */
  adaptive?: boolean;
  /**
   * Show a denoised picture while the view rests (Open Image Denoise's network on a
   * worker of its own, guided by the first-hit albedo and normal the film then records;
   * docs/denoise.md says what it costs and when it misleads). Default false.
   */
  denoise?: boolean;
  /**
   * Denoise threads (default: a quarter of the cores, 1 to 4). The image's tiles are
   * dealt out to them; the picture is the same bits for any number.
   */
  denoiseWorkers?: number;
}

/** A stage of loading a scene or model (core/scene/load/load.ts LoadStage), `done` of `total`. */
export interface LoadProgressInfo {
  stage: LoadStage;
  done: number;
  total: number;
}

export interface PathTracerEventMap {
  /**
   * `skippedTriangles`: zero-area triangles the scene's meshes dropped (the spec asks for
   * a report); `warnings`: what the scene's glTF files use that pathwise ignores or skips
   * (extensions, primitive modes), one line each, also sent as a `warning` event.
   */
  load: CustomEvent<{ scene: Scene; skippedTriangles: number; warnings: string[] }>;
  /** Loading a glTF model: reading, parse, textures, geometry, compile (the BVH build). */
  loadprogress: CustomEvent<LoadProgressInfo>;
  /** The loaded scene's warnings, when it has any (see `load`). */
  warning: CustomEvent<{ messages: string[] }>;
  progress: CustomEvent<ProgressInfo>;
  converged: CustomEvent<ProgressInfo>;
  denoised: CustomEvent<DenoisedInfo>;
  error: CustomEvent<{ message: string }>;
  fallback: CustomEvent<FallbackInfo>;
}

export interface PathTracerController extends EventTarget {
  readonly canvas: HTMLCanvasElement;
  readonly mode: FallbackInfo;
  readonly scene: Scene | null;
  /**
   * Validates and loads a scene: an object, its JSON text, or the bytes of a file (a
   * Uint8Array or a File/Blob, held to the 16 MiB bound and strict UTF-8 like the command
   * line), reading the mesh and map files it names through `files` (default: URLs
   * relative to the page). Rejects with the loader's message, keeping the current scene.
   */
  setScene(scene: unknown, files?: SceneFileReader): Promise<void>;
  /** Fetches a scene; the files it names are fetched relative to its URL. */
  load(url: string): Promise<void>;
  reset(): void;
  pause(): void;
  resume(): void;
  readonly paused: boolean;
  setTargetSpp(spp: number): void;
  setBounces(bounces: number): void;
  setExposure(exposure: number): void;
  setSeed(seed: number): void;
  /** A fixed render scale, or null for the automatic one (see PathTracerOptions.renderScale). */
  setRenderScale(scale: number | null): void;
  /** Turns adaptive sampling on or off (see PathTracerOptions.adaptive); the render starts over. */
  setAdaptive(on: boolean): void;
  readonly adaptive: boolean;
  /** Turns the denoised picture on or off (see PathTracerOptions.denoise). */
  setDenoise(on: boolean): void;
  readonly denoise: boolean;
  setWorkers(count: number): Promise<void>;
  getCamera(): CameraDesc;
  setCamera(camera: CameraDesc): void;
  /** Orbit around the target by pixel deltas; dolly by a factor. */
  orbit(dxPixels: number, dyPixels: number): void;
  dolly(factor: number): void;
  setAperture(aperture: number): void;
  /** Sets the focus distance to the surface under canvas point (x, y) in CSS pixels. */
  focusAt(x: number, y: number): boolean;
  stats(): RenderStatsInfo;
  /** Linear mean radiance, RGB float32, row 0 at the top. */
  readLinear(): { width: number; height: number; rgb: Float32Array };
  /** The picture on screen as PNG (the denoised one while it is shown), at the film's size. */
  toBlob(): Promise<Blob>;
  toPFM(): Uint8Array;
  destroy(): void;
}
