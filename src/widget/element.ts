/**
 * <pathwise-view>: a custom element wrapping one PathTracerController.
 * Attributes configure it, the controller's events are re-dispatched on the
 * element, and the element decides *when* to trace: never while disconnected,
 * off screen, in a hidden tab or paused by the author.
 */
import type { LoadStage } from '../core/index.ts';
import { createPathTracer } from '../view/index.ts';
import { attachCameraControls } from '../view/interaction.ts';
import type {
  FallbackInfo,
  LoadProgressInfo,
  PathTracerController,
  PathTracerEventMap,
  PathTracerOptions,
  ProgressInfo,
} from '../view/types.ts';
import { ViewAccessibility } from './accessibility.ts';
import {
  DEFAULT_EXPOSURE,
  DEFAULT_SPP,
  OBSERVED_ATTRIBUTES,
  parseAdaptive,
  parseAutoplay,
  parseNumber,
  parsePositive,
  writeBoolean,
  writeNumber,
  type ObservedAttribute,
} from './attributes.ts';
import { ELEMENT_CSS } from './styles.ts';
import { ThreeLink } from './three-link.ts';
import { VisibilityWatcher } from './visibility.ts';

/** Events of <pathwise-view>: the controller's, re-dispatched on the element. */
export interface PathwiseViewEventMap
  extends Omit<HTMLElementEventMap, keyof PathTracerEventMap>, PathTracerEventMap {}

/**
 * Importing this module must not throw where there is no DOM (server-side
 * rendering, Node tests): the class then extends an inert stand-in and is
 * simply never registered.
 */
const ElementBase: typeof HTMLElement =
  typeof HTMLElement === 'undefined' ? (class {} as unknown as typeof HTMLElement) : HTMLElement;

const FORWARDED_EVENTS = [
  'load',
  'progress',
  'converged',
  'error',
  'fallback',
  'loadprogress',
  'warning',
  'denoised',
] as const;

/** Words for a loading stage, shown while a model loads. */
const STAGE_WORDS: Record<LoadStage, string> = {
  read: 'reading files',
  parse: 'parsing',
  textures: 'decoding textures',
  geometry: 'building geometry',
  compile: 'building the BVH',
};

export class PathwiseViewElement extends ElementBase {
  static get observedAttributes(): readonly string[] {
    return OBSERVED_ATTRIBUTES;
  }

  /**
   * Creates render workers, for hosts whose bundler or CDN breaks the
   * default worker URL; read when tracing starts. The page's worker pool is
   * shared, so the first element (or createPathTracer call) to start decides.
   */
  workerFactory: (() => Worker) | undefined = undefined;

  private canvas: HTMLCanvasElement;
  /** Whether a tracer has drawn on `canvas` (a canvas keeps its first context for good). */
  private canvasUsed = false;
  private readonly messageBox: HTMLDivElement;
  /** Load progress of a model (parse, textures, BVH), shown until it loads or fails. */
  private readonly statusBox: HTMLDivElement;
  private readonly visibility: VisibilityWatcher;
  private readonly a11y: ViewAccessibility;
  private tracer: ReturnType<typeof createPathTracer> | null = null;
  /** Detaches the pointer controls while `camera-controls` is on. */
  private detachControls: (() => void) | null = null;
  private sceneObject: unknown = undefined;
  private readonly three = new ThreeLink();
  private lastProgress: ProgressInfo | null = null;
  private workerUrlOverride: string | URL | undefined = undefined;
  /** Bumped on every scene request so a slow, superseded load cannot report over a newer one. */
  private sceneRequest = 0;
  /** Error events seen from the controller, to tell reported failures from silent ones. */
  private errorEvents = 0;
  private started = false;

  constructor() {
    super();
    const root = this.attachShadow({ mode: 'open' });
    const style = document.createElement('style');
    style.textContent = ELEMENT_CSS;
    this.canvas = createCanvas();
    this.messageBox = document.createElement('div');
    this.messageBox.setAttribute('part', 'message');
    this.messageBox.setAttribute('role', 'alert');
    this.messageBox.hidden = true;
    this.statusBox = document.createElement('div');
    this.statusBox.setAttribute('part', 'status');
    this.statusBox.setAttribute('role', 'status');
    this.statusBox.hidden = true;
    root.append(style, this.canvas, this.statusBox, this.messageBox);
    this.a11y = new ViewAccessibility(this, this.canvas, root);
    this.visibility = new VisibilityWatcher(this, () => this.applyRunState());
  }

  // ---- attribute-backed properties -------------------------------------

  /**
   * URL of a pathwise-scene/1 JSON file, or of a glTF model (`.glb`, or `.gltf` with its
   * buffers and images beside it: framed by its bounds in a studio environment);
   * ignored while `scene` is set.
   */
  get src(): string {
    return this.getAttribute('src') ?? '';
  }
  set src(value: string) {
    this.setAttribute('src', value);
  }

  /**
   * Target passes, the samples per pixel (default 512; past the adaptive pilot, the most
   * any pixel holds); tracing stops there and `converged` fires.
   */
  get spp(): number {
    return parsePositive(this.getAttribute('spp')) ?? DEFAULT_SPP;
  }
  set spp(value: number) {
    writeNumber(this, 'spp', value);
  }

  /** Maximum path bounces; null means the scene's own setting. */
  get bounces(): number | null {
    return parseNumber(this.getAttribute('bounces')) ?? null;
  }
  set bounces(value: number | null) {
    writeNumber(this, 'bounces', value);
  }

  /** Display gain on linear radiance (default 1); changing it never restarts accumulation. */
  get exposure(): number {
    return parseNumber(this.getAttribute('exposure')) ?? DEFAULT_EXPOSURE;
  }
  set exposure(value: number) {
    writeNumber(this, 'exposure', value);
  }

  /** Random seed; null means the tracer's default. */
  get seed(): number | null {
    return parseNumber(this.getAttribute('seed')) ?? null;
  }
  set seed(value: number | null) {
    writeNumber(this, 'seed', value);
  }

  /** Orbit on drag, dolly on wheel. */
  get cameraControls(): boolean {
    return this.hasAttribute('camera-controls');
  }
  set cameraControls(value: boolean) {
    writeBoolean(this, 'camera-controls', value);
  }

  /**
   * Show a denoised picture while the view rests (PathTracerOptions.denoise;
   * docs/denoise.md). A boolean attribute: present means on.
   */
  get denoise(): boolean {
    return this.hasAttribute('denoise');
  }
  set denoise(value: boolean) {
    writeBoolean(this, 'denoise', value);
  }

  /**
   * Adaptive sampling (PathTracerOptions.adaptive; docs/adaptive-sampling.md): default
   * true; `adaptive="false"` samples every pixel in every pass. A change starts over.
   */
  get adaptive(): boolean {
    return parseAdaptive(this.getAttribute('adaptive'));
  }
  set adaptive(value: boolean) {
    this.setAttribute('adaptive', String(value));
  }

  /** Start tracing as soon as the scene loads (default true; `autoplay="false"` opts out). */
  get autoplay(): boolean {
    return parseAutoplay(this.getAttribute('autoplay'));
  }
  set autoplay(value: boolean) {
    this.setAttribute('autoplay', String(value));
  }

  /** Paused by the author (independent of the automatic off-screen/hidden-tab pause). */
  get paused(): boolean {
    return this.hasAttribute('paused');
  }
  set paused(value: boolean) {
    writeBoolean(this, 'paused', value);
  }

  /**
   * Render resolution relative to the element's size × devicePixelRatio
   * (capped at 2); null (no attribute) chooses it from the measured speed.
   */
  get renderScale(): number | null {
    return parsePositive(this.getAttribute('render-scale')) ?? null;
  }
  set renderScale(value: number | null) {
    writeNumber(this, 'render-scale', value);
  }

  /** Text alternative for the picture (attribute `alt`); default: the scene's name. */
  get alt(): string {
    return this.getAttribute('alt') ?? '';
  }
  set alt(value: string) {
    this.setAttribute('alt', value);
  }

  /**
   * The render worker script (pathwise/worker), when the default URL is
   * broken; may be on a CDN. Read when tracing starts (attribute `worker-url`).
   */
  get workerUrl(): string | URL | undefined {
    return this.workerUrlOverride ?? this.getAttribute('worker-url') ?? undefined;
  }
  set workerUrl(value: string | URL | undefined) {
    this.workerUrlOverride = value;
  }

  // ---- property-only state ---------------------------------------------

  /** A scene object (pathwise-scene/1); takes precedence over `src`. */
  get scene(): unknown {
    return this.sceneObject;
  }
  set scene(value: unknown) {
    this.sceneObject = value;
    if (this.tracer) this.requestScene();
  }

  /**
   * A three.js scene (any Object3D) to path-trace, with `threeCamera`; takes precedence
   * over `scene` and `src`. Converted by pathwise/three (docs/three.md); what cannot be
   * mapped is reported in one `warning` event.
   */
  get threeScene(): object | null {
    return this.three.scene;
  }
  set threeScene(value: object | null) {
    this.three.scene = value;
    if (this.tracer && this.three.active) this.requestScene();
  }

  /**
   * The three.js PerspectiveCamera the view follows: moving it (OrbitControls, say)
   * restarts accumulation from the new view without reloading the scene.
   */
  get threeCamera(): object | null {
    return this.three.camera;
  }
  set threeCamera(value: object | null) {
    const first = this.three.camera === null;
    this.three.camera = value;
    if (this.tracer && this.three.active && first) this.requestScene();
  }

  /** Converts `threeScene` again: call it after changing its geometry, materials or lights. */
  threeChanged(): void {
    if (this.tracer && this.three.active) this.requestScene();
  }

  /** The underlying controller, for camera and other advanced controls; null while disconnected. */
  get controller(): PathTracerController | null {
    return this.tracer;
  }

  /** How it runs here (display and compute path), once tracing has started. */
  get mode(): FallbackInfo | null {
    return this.tracer?.mode ?? null;
  }

  /** The latest progress report, or null before the first one. */
  get progress(): ProgressInfo | null {
    return this.lastProgress;
  }

  // ---- methods ----------------------------------------------------------

  /** Discards the accumulated samples and starts over. */
  reset(): void {
    this.tracer?.reset();
  }

  pause(): void {
    this.paused = true;
  }

  resume(): void {
    this.paused = false;
  }

  /** The current image as PNG (tone-mapped with the current exposure). */
  toBlob(): Promise<Blob> {
    if (!this.tracer) return Promise.reject(this.notRunningError());
    return this.tracer.toBlob();
  }

  /** The current linear mean radiance as a PFM file. */
  toPFM(): Uint8Array {
    if (!this.tracer) throw this.notRunningError();
    return this.tracer.toPFM();
  }

  // ---- lifecycle ----------------------------------------------------------

  connectedCallback(): void {
    if (!this.started) {
      this.started = true;
      // autoplay="false" means "start paused": expressed through the public
      // `paused` state so that resume() is the one way to start.
      if (!this.autoplay) this.paused = true;
    }
    this.a11y.update();
    // Creation waits a microtask so that properties set right after the
    // element is created or upgraded (scene, workerUrl) are seen at start.
    queueMicrotask(() => {
      if (this.isConnected && !this.tracer) this.startTracer();
    });
    this.visibility.start();
  }

  disconnectedCallback(): void {
    this.visibility.stop();
    // A move within the document disconnects and reconnects synchronously;
    // only a real removal should pay for freeing and re-creating workers.
    queueMicrotask(() => {
      if (!this.isConnected) this.stopTracer();
    });
  }

  attributeChangedCallback(name: string, oldValue: string | null, value: string | null): void {
    if (oldValue === value) return;
    if ((name === 'alt' || name === 'camera-controls') && this.isConnected) this.a11y.update();
    if (!this.tracer) return;
    const tracer = this.tracer;
    switch (name as ObservedAttribute) {
      case 'src':
        if (!this.hasSceneObject()) this.requestScene();
        break;
      case 'spp':
        tracer.setTargetSpp(this.spp);
        break;
      case 'bounces': {
        const bounces = this.bounces ?? tracer.scene?.settings.maxBounces;
        if (bounces !== undefined) tracer.setBounces(bounces);
        break;
      }
      case 'exposure':
        tracer.setExposure(this.exposure);
        break;
      case 'seed':
        tracer.setSeed(this.seed ?? 0);
        break;
      case 'render-scale':
        tracer.setRenderScale(this.renderScale);
        break;
      case 'camera-controls':
        this.applyCameraControls();
        break;
      case 'denoise':
        tracer.setDenoise(this.denoise);
        break;
      case 'adaptive':
        tracer.setAdaptive(this.adaptive);
        break;
      case 'paused':
        this.applyRunState();
        break;
      case 'autoplay':
      case 'alt':
        break;
    }
  }

  // ---- internals ----------------------------------------------------------

  private startTracer(): void {
    const options: PathTracerOptions = {
      spp: this.spp,
      exposure: this.exposure,
      autoplay: this.shouldRun(),
      cameraControls: false,
      denoise: this.denoise,
      adaptive: this.adaptive,
    };
    if (this.bounces !== null) options.bounces = this.bounces;
    if (this.renderScale !== null) options.renderScale = this.renderScale;
    if (this.seed !== null) options.seed = this.seed;
    // A bare model's environment (docs/gltf.md, Punctual lights): read when it loads.
    if (this.getAttribute('environment') === 'none') options.environment = 'none';
    // A bare model's material variant (docs/gltf.md, Material variants): read when it loads.
    const variant = this.getAttribute('variant');
    if (variant !== null) options.variant = variant;
    // A worker URL goes to the pool as is: it starts one on another origin
    // through a same-origin shim, and reports a URL it cannot start as an
    // `error` event (shown here) rather than throwing at this point.
    const workerUrl = this.workerUrl;
    if (this.workerFactory) options.workerFactory = this.workerFactory;
    else if (workerUrl !== undefined) options.workerUrl = workerUrl;
    let tracer: ReturnType<typeof createPathTracer>;
    try {
      // A re-connected element starts on a fresh canvas: the old one's
      // context belonged to the destroyed tracer.
      if (this.canvasUsed) {
        const canvas = createCanvas();
        this.canvas.replaceWith(canvas);
        this.canvas = canvas;
        this.a11y.setCanvas(canvas);
      }
      this.canvasUsed = true;
      tracer = createPathTracer(this.canvas, options);
    } catch (err) {
      this.showError(errorMessage(err));
      return;
    }
    this.tracer = tracer;
    for (const type of FORWARDED_EVENTS) tracer.addEventListener(type, this.forward);
    this.applyCameraControls();
    this.requestScene();
  }

  private stopTracer(): void {
    const tracer = this.tracer;
    if (!tracer) return;
    this.tracer = null;
    this.three.stop();
    this.sceneRequest++;
    this.detachControls?.();
    this.detachControls = null;
    for (const type of FORWARDED_EVENTS) tracer.removeEventListener(type, this.forward);
    tracer.destroy();
  }

  /**
   * Loads `scene` if set, else `src`. The controller reports failures as an
   * `error` event, which `forward` shows and re-dispatches; a rejection that
   * came without one is reported here, so no failure leaves a blank box.
   */
  private requestScene(): void {
    const tracer = this.tracer;
    if (!tracer) return;
    const request = ++this.sceneRequest;
    let pending: Promise<void>;
    if (this.three.active) {
      pending = this.three.load(tracer, (messages) =>
        this.dispatchEvent(new CustomEvent('warning', { detail: { messages } })),
      );
      this.three.watch(() => this.tracer);
    } else if (this.hasSceneObject()) {
      this.three.stop();
      pending = tracer.setScene(this.sceneObject);
    } else if (this.src !== '') {
      this.three.stop();
      pending = tracer.load(this.src);
    } else {
      return;
    }
    const first = tracer.scene === null;
    const errorsBefore = this.errorEvents;
    pending.then(
      () => {
        if (request !== this.sceneRequest) return;
        // The controller applies its `bounces` option to the first scene
        // only; later scenes bring their own unless the attribute says else.
        if (!first && this.bounces !== null) tracer.setBounces(this.bounces);
        this.applyRunState();
      },
      (err: unknown) => {
        if (request === this.sceneRequest && this.errorEvents === errorsBefore) {
          this.showError(errorMessage(err));
        }
      },
    );
  }

  private readonly forward = (event: Event) => {
    const detail = (event as CustomEvent<unknown>).detail;
    switch (event.type) {
      case 'loadprogress': {
        const p = detail as LoadProgressInfo;
        const count = p.total > 1 ? ` ${p.done}/${p.total}` : '';
        this.statusBox.textContent = `Loading: ${STAGE_WORDS[p.stage] ?? p.stage}${count}`;
        this.statusBox.hidden = false;
        break;
      }
      case 'load':
        this.statusBox.hidden = true;
        this.hideMessage();
        this.a11y.setSceneName((detail as { scene: { name?: string } }).scene.name ?? '');
        break;
      case 'progress':
      case 'converged':
        this.lastProgress = detail as ProgressInfo;
        break;
      case 'error':
        // A bad scene or URL, or a worker failure: never leave a blank box.
        this.errorEvents++;
        this.statusBox.hidden = true;
        this.showMessage((detail as { message: string }).message);
        break;
    }
    this.dispatchEvent(new CustomEvent(event.type, { detail }));
  };

  private showError(message: string): void {
    this.errorEvents++;
    this.showMessage(message);
    this.dispatchEvent(new CustomEvent('error', { detail: { message } }));
  }

  private showMessage(message: string): void {
    this.messageBox.textContent = message;
    this.messageBox.hidden = false;
  }

  private hideMessage(): void {
    this.messageBox.hidden = true;
    this.messageBox.textContent = '';
  }

  private hasSceneObject(): boolean {
    return this.sceneObject !== undefined && this.sceneObject !== null;
  }

  private shouldRun(): boolean {
    return !this.paused && this.isConnected && this.visibility.visible;
  }

  private applyRunState(): void {
    const tracer = this.tracer;
    if (!tracer) return;
    const run = this.shouldRun();
    if (run && tracer.paused) tracer.resume();
    else if (!run && !tracer.paused) tracer.pause();
  }

  /**
   * The element attaches the view's pointer controls itself (the controller
   * gets `cameraControls: false`) so that toggling the attribute takes
   * effect at once, without re-creating the tracer.
   */
  private applyCameraControls(): void {
    if (this.cameraControls && this.tracer && !this.detachControls) {
      this.detachControls = attachCameraControls(this.tracer, this.canvas);
    } else if (!this.cameraControls && this.detachControls) {
      this.detachControls();
      this.detachControls = null;
    }
  }

  private notRunningError(): Error {
    return new Error('pathwise-view: no image yet (the element is not connected)');
  }
}

// Typed addEventListener/removeEventListener for the element's own events.
export interface PathwiseViewElement {
  addEventListener<K extends keyof PathwiseViewEventMap>(
    type: K,
    listener: (this: PathwiseViewElement, ev: PathwiseViewEventMap[K]) => unknown,
    options?: boolean | AddEventListenerOptions,
  ): void;
  addEventListener(
    type: string,
    listener: EventListenerOrEventListenerObject,
    options?: boolean | AddEventListenerOptions,
  ): void;
  removeEventListener<K extends keyof PathwiseViewEventMap>(
    type: K,
    listener: (this: PathwiseViewElement, ev: PathwiseViewEventMap[K]) => unknown,
    options?: boolean | EventListenerOptions,
  ): void;
  removeEventListener(
    type: string,
    listener: EventListenerOrEventListenerObject,
    options?: boolean | EventListenerOptions,
  ): void;
}

declare global {
  interface HTMLElementTagNameMap {
    'pathwise-view': PathwiseViewElement;
  }
}

function createCanvas(): HTMLCanvasElement {
  const canvas = document.createElement('canvas');
  canvas.setAttribute('part', 'canvas');
  return canvas;
}

function errorMessage(err: unknown): string {
  if (err instanceof Error) return err.message;
  return String(err);
}
