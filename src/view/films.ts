/**
 * The films of one controller: the full-resolution film, sized from the
 * canvas (CSS size × devicePixelRatio × render scale) or fixed by the
 * options, and the low-resolution preview used while the pointer drags.
 * Exactly one is active; the other is parked (configuration version -1),
 * so no worker spends time on it.
 */
import { chooseStripeRows } from '../../workers/render-protocol.ts';
import type { FilmJob } from './film-job.ts';
import { SharedFilmJob } from './shared-job.ts';
import { TransferFilmJob } from './transfer-job.ts';
import type { ComputeMode, PathTracerOptions } from './types.ts';

/** Preview films are this many times smaller in each direction. */
const PREVIEW_DIVISOR = 4;
/** A new canvas size must hold this long before the film follows it. */
const RESIZE_SETTLE_MS = 200;

export class Films {
  full: FilmJob | null = null;
  preview: FilmJob | null = null;
  /** The preview is the active film. */
  previewing = false;
  /** The pointer is moving: the next restart switches to the preview film. */
  wantPreview = false;
  renderScale: number;
  private readonly canvas: HTMLCanvasElement;
  private readonly options: PathTracerOptions;
  private readonly compute: ComputeMode;
  private readonly workers: () => number;
  private pendingSize = '';
  private pendingSince = 0;

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
    this.renderScale = options.renderScale ?? 1;
  }

  active(): FilmJob | null {
    return this.previewing ? this.preview : this.full;
  }

  get memoryBytes(): number {
    return (this.full?.memoryBytes ?? 0) + (this.preview?.memoryBytes ?? 0);
  }

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

  private make(width: number, height: number, target: number): FilmJob {
    const rows = chooseStripeRows(height, this.workers());
    return this.compute === 'shared'
      ? new SharedFilmJob(width, height, rows, target)
      : new TransferFilmJob(width, height, rows, target);
  }

  /**
   * Makes sure the full film matches the wanted size (the canvas's backing
   * store follows); returns true when it was remade.
   */
  ensureFull(target: number): boolean {
    const [w, h] = this.fullSize();
    if (this.full && this.full.width === w && this.full.height === h) return false;
    this.full?.setVersion(-1);
    this.full = this.make(w, h, target);
    this.preview?.setVersion(-1);
    this.preview = null;
    this.canvas.width = w;
    this.canvas.height = h;
    return true;
  }

  private ensurePreview(target: number): FilmJob {
    const full = this.full!;
    const w = Math.max(1, Math.round(full.width / PREVIEW_DIVISOR));
    const h = Math.max(1, Math.round(full.height / PREVIEW_DIVISOR));
    if (!this.preview || this.preview.width !== w || this.preview.height !== h) {
      this.preview = this.make(w, h, target);
    }
    return this.preview;
  }

  /** For a restart: the film to render (the preview while dragging); the other is parked. */
  select(target: number): FilmJob {
    this.ensureFull(target);
    if (this.wantPreview) this.previewing = true;
    const active = this.previewing ? this.ensurePreview(target) : this.full!;
    const parked = this.previewing ? this.full : this.preview;
    parked?.setVersion(-1);
    return active;
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
    if ((this.options.width && this.options.height) || !this.full || this.previewing) return false;
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
