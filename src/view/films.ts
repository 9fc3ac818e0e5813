/**
 * The films of one controller: the full-resolution film, sized from the
 * canvas (CSS size × capped devicePixelRatio × render scale) or fixed by
 * the options, and the low-resolution preview used while the pointer
 * drags and for the first, quick pass (see controller.ts). Exactly one is
 * active; the other is parked (configuration version -1), so no worker
 * spends time on it.
 */
import { chooseStripeRows } from '../../workers/browser/render-protocol.ts';
import { DEFAULT_MAX_PIXEL_RATIO } from './auto-scale.ts';
import { Film } from '../core/index.ts';
import {
  filmSizeProblem,
  fitFactor,
  maxFilmPixels,
  mib,
  MAX_FILM_BYTES,
  MAX_FILM_SIDE,
} from './film-cap.ts';
import type { FilmJob } from './film-job.ts';
import { SharedFilmJob } from './shared-job.ts';
import { TransferFilmJob } from './transfer-job.ts';
import type { ComputeMode, PathTracerOptions } from './types.ts';

/** Preview films are at least this many times smaller in each direction. */
const PREVIEW_DIVISOR = 4;
/**
 * …and hold at most this many pixels, so a preview pass takes a frame or
 * two even when the user raised the render scale (~12 ms at the 1.4 M
 * samples/s of two cores).
 */
const PREVIEW_MAX_PIXELS = 16_384;
/** Films made smaller after failed allocations are at least this many pixels. */
const MIN_FALLBACK_PIXELS = 4096;
/** A new canvas size must hold this long before the film follows it. */
const RESIZE_SETTLE_MS = 200;
/**
 * Shared-memory stripes are this many rows high at most per 256 rows of
 * image: thin stripes let the spread-out pass order (stripeOrder) cover the
 * frame evenly; a claim costs microseconds next to a row's milliseconds.
 */
const SHARED_STRIPES_TARGET = 256;

/** No film could be made: the message says why (the cap, or the memory). */
export class FilmMemoryError extends Error {}

export class Films {
  full: FilmJob | null = null;
  preview: FilmJob | null = null;
  /** The preview is the active film. */
  previewing = false;
  /** The pointer is moving (or the first pass is wanted quickly): the next restart uses the preview film. */
  wantPreview = false;
  /** Render scale in use; chosen from the measured speed while `autoScale` holds. */
  renderScale: number;
  /** The scale is the automatic one (no renderScale option, not set by the user). */
  autoScale: boolean;
  private readonly canvas: HTMLCanvasElement;
  private readonly options: PathTracerOptions;
  private readonly compute: ComputeMode;
  private readonly workers: () => number;
  private readonly maxPixelRatio: number;
  /**
   * The full film records first-hit albedo and normal (the denoiser's guides): set while
   * denoising is on; a full film without them is remade at the next restart.
   */
  aux = false;
  /**
   * The full film is sampled adaptively (PathTracerOptions.adaptive, pilot-gate.ts); a
   * full film made otherwise is remade at the next restart.
   */
  adaptive: boolean;
  /** The automatic scale's cap on the full film's pixels (the denoiser's budget while it is on). */
  maxAutoPixels = Infinity;
  /** See PathTracerOptions.sizeStep; takes effect when the full film is next sized. */
  sizeStep: number;
  private pendingSize = '';
  private pendingSince = 0;
  /** Share of the pixel cap still allowed: halved after each failed allocation. */
  private memoryFraction = 1;
  /** The largest film side the display takes (its texture limit), at most MAX_FILM_SIDE. */
  maxSide = MAX_FILM_SIDE;
  /**
   * Why the full film is smaller than the canvas asks (the accumulator cap,
   * or memory that could not be had) and the render scale that results;
   * null when it is not.
   */
  capped: { reason: string; scale: number } | null = null;

  constructor(
    canvas: HTMLCanvasElement,
    options: PathTracerOptions,
    compute: ComputeMode,
    workers: () => number,
  ) {
    this.canvas = canvas;
    this.options = options;
    this.compute = compute;
    this.workers = workers;
    this.adaptive = options.adaptive !== false;
    this.autoScale = options.renderScale === undefined && !this.fixedSize;
    // Until a speed is measured, the automatic scale is the largest one: the
    // quick first pass runs in the preview film, which it sizes.
    this.renderScale = options.renderScale ?? 1;
    this.maxPixelRatio = options.maxPixelRatio ?? DEFAULT_MAX_PIXEL_RATIO;
    this.sizeStep = Math.max(1, Math.floor(options.sizeStep ?? 1));
  }

  active(): FilmJob | null {
    return this.previewing ? this.preview : this.full;
  }

  get memoryBytes(): number {
    return (this.full?.memoryBytes ?? 0) + (this.preview?.memoryBytes ?? 0);
  }

  get fixedSize(): boolean {
    return !!(this.options.width && this.options.height);
  }

  /** The canvas's CSS size and the capped devicePixelRatio that multiplies it. */
  cssSize(): { width: number; height: number; pixelRatio: number } {
    const dpr = typeof devicePixelRatio === 'number' && devicePixelRatio > 0 ? devicePixelRatio : 1;
    return {
      width: this.canvas.clientWidth || this.canvas.width || 300,
      height: this.canvas.clientHeight || this.canvas.height || 150,
      pixelRatio: Math.min(dpr, this.maxPixelRatio),
    };
  }

  /**
   * The full render size: fixed, or the canvas's CSS size × capped
   * devicePixelRatio × renderScale, held to the accumulator cap (capped
   * says when and why).
   */
  fullSize(scale = this.renderScale): [number, number] {
    const o = this.options;
    if (o.width && o.height) return [Math.floor(o.width), Math.floor(o.height)];
    const css = this.cssSize();
    const wanted = css.pixelRatio * scale;
    let s = wanted;
    let size = this.sizeAt(css, s);
    // The cap: scaled down to fit, the aspect ratio kept (film-cap.ts).
    const factor = fitFactor(size[0], size[1], this.memoryFraction, this.maxSide, this.aux);
    if (factor < 1) {
      s *= factor;
      size = this.sizeAt(css, s);
      // Rounding to the size step may land just over: a little less then.
      while (s > 1e-6 && this.overCap(size[0], size[1])) {
        s *= 0.98;
        size = this.sizeAt(css, s);
      }
    }
    this.capped =
      factor < 1
        ? {
            scale: (scale * s) / wanted,
            reason:
              this.memoryFraction < 1
                ? `memory for a larger film could not be had, so the render scale is reduced to ${((scale * s) / wanted).toFixed(3)} (${size[0]}×${size[1]})`
                : `the canvas asks for more than the accumulator cap (${mib(MAX_FILM_BYTES)}, ${this.maxSide} pixels a side), so the render scale is reduced to ${((scale * s) / wanted).toFixed(3)} (${size[0]}×${size[1]})`,
          }
        : null;
    return size;
  }

  private overCap(width: number, height: number): boolean {
    const f = fitFactor(width, height, this.memoryFraction, this.maxSide, this.aux);
    return f < 1;
  }

  /**
   * The size at `s` film pixels per CSS pixel. With a size step the height
   * is a multiple of it and the width even, so that film pixels tile a
   * centred grid exactly (the demo compares its image with references cell
   * by cell); the aspect ratio stays within a pixel of the canvas's.
   */
  private sizeAt(css: { width: number; height: number }, s: number): [number, number] {
    let w = Math.max(1, Math.round(css.width * s));
    let h = Math.max(1, Math.round(css.height * s));
    const step = this.sizeStep;
    if (step > 1) {
      const aspect = css.width / css.height;
      h = Math.max(step, Math.round(h / step) * step);
      w = Math.max(2, 2 * Math.round((h * aspect) / 2));
    }
    return [w, h];
  }

  /**
   * A film job of w × h. Memory that cannot be had (the allocation throws a
   * RangeError, SharedArrayBuffer's included) is reported in plain words.
   */
  private make(
    width: number,
    height: number,
    target: number,
    aux: boolean,
    adaptive: boolean,
  ): FilmJob {
    try {
      if (this.compute === 'shared') {
        const rows = Math.max(1, Math.floor(height / SHARED_STRIPES_TARGET));
        return new SharedFilmJob(width, height, rows, target, aux, adaptive);
      }
      // Each transferred stripe is a message both ways: keep them few.
      const rows = chooseStripeRows(height, this.workers());
      return new TransferFilmJob(width, height, rows, target, aux, adaptive);
    } catch (e) {
      if (!(e instanceof RangeError)) throw e;
      const what = this.compute === 'shared' ? 'shared memory (SharedArrayBuffer)' : 'memory';
      throw new FilmMemoryError(
        `could not allocate ${what} for a ${width}×${height} film (${mib(Film.byteLength(width, height, aux))}): ${e.message}`,
      );
    }
  }

  /**
   * Makes sure the full film matches the wanted size (the canvas's backing
   * store follows); returns true when it was remade. Throws, with the
   * reason, when no film can be made: a fixed size over the cap, or memory
   * that cannot be had; a canvas-derived size is halved in pixels after a
   * failed allocation and tried again first.
   */
  ensureFull(target: number): boolean {
    let [w, h] = this.fullSize();
    const full = this.full;
    if (
      full &&
      full.width === w &&
      full.height === h &&
      (full.aux || !this.aux) &&
      full.adaptive === this.adaptive
    ) {
      return false;
    }
    if (this.fixedSize) {
      const problem = filmSizeProblem(w, h, this.maxSide, this.aux);
      if (problem) throw new FilmMemoryError(problem);
    }
    let made: FilmJob;
    for (;;) {
      try {
        made = this.make(w, h, target, this.aux, this.adaptive);
        break;
      } catch (e) {
        if (!(e instanceof FilmMemoryError) || this.fixedSize || w * h <= MIN_FALLBACK_PIXELS) {
          throw e;
        }
        this.memoryFraction = Math.min(this.memoryFraction, (w * h) / maxFilmPixels(this.aux)) / 2;
        [w, h] = this.fullSize();
      }
    }
    this.full?.setVersion(-1);
    this.full = made;
    this.preview?.setVersion(-1);
    this.preview = null;
    this.canvas.width = w;
    this.canvas.height = h;
    return true;
  }

  /** The preview's size for a full film of w × h. */
  static previewSize(w: number, h: number): [number, number] {
    const f = Math.max(PREVIEW_DIVISOR, Math.sqrt((w * h) / PREVIEW_MAX_PIXELS));
    return [Math.max(1, Math.round(w / f)), Math.max(1, Math.round(h / f))];
  }

  private ensurePreview(target: number): FilmJob {
    // Before the full film exists (the quick first pass, which measures the
    // speed the automatic scale needs) the preview follows the largest size.
    const [fw, fh] = this.full ? [this.full.width, this.full.height] : this.fullSize();
    const [w, h] = Films.previewSize(fw, fh);
    if (!this.preview || this.preview.width !== w || this.preview.height !== h) {
      // The preview lives for a drag's few passes: uniform, no pilot to wait for.
      const made = this.make(w, h, target, false, false);
      this.preview?.setVersion(-1);
      this.preview = made;
    }
    if (!this.full) {
      this.canvas.width = fw;
      this.canvas.height = fh;
    }
    return this.preview;
  }

  /** For a restart: the film to render (the preview while wanted); the other is parked. */
  select(target: number): FilmJob {
    if (this.fixedSize) {
      // A fixed size that cannot be had fails before any preview of it.
      const [w, h] = this.fullSize();
      const problem = filmSizeProblem(w, h, this.maxSide, this.aux);
      if (problem) throw new FilmMemoryError(problem);
    }
    this.previewing = this.wantPreview;
    if (this.previewing) {
      this.full?.setVersion(-1);
      return this.ensurePreview(target);
    }
    this.ensureFull(target);
    this.preview?.setVersion(-1);
    return this.full!;
  }

  /** A new canvas size is waiting to settle (follow must be called again). */
  get resizePending(): boolean {
    return this.pendingSize !== '';
  }

  /**
   * Follows the canvas size once it has settled for RESIZE_SETTLE_MS: a
   * window dragged wider would otherwise reallocate and restart the render
   * every frame. A one-pixel difference (rounding of CSS size ×
   * devicePixelRatio) is not worth a restart. Returns true when the full
   * film was remade (the caller restarts).
   */
  follow(now: number, target: number): boolean {
    if (this.fixedSize || !this.full || this.previewing) return false;
    const [w, h] = this.fullSize();
    if (Math.abs(w - this.full.width) <= 1 && Math.abs(h - this.full.height) <= 1) {
      this.pendingSize = '';
      return false;
    }
    const key = `${w}x${h}`;
    if (key !== this.pendingSize) {
      this.pendingSize = key;
      this.pendingSince = now;
      return false;
    }
    if (now - this.pendingSince < RESIZE_SETTLE_MS) return false;
    this.pendingSize = '';
    return this.ensureFull(target);
  }

  /** Parks both films (the controller is going away). */
  park(): void {
    this.full?.setVersion(-1);
    this.preview?.setVersion(-1);
  }
}
