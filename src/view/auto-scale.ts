/**
 * The automatic render scale: as many pixels as the measured speed traces
 * in one pass within PASS_BUDGET_S, aiming at a first complete image
 * within about 0.3 s of the scene on an idle two-core machine (start-up,
 * the quick pass, one full pass; bench/first-image.mjs measures it), after
 * which the noise falls at a pace the user can watch. The speed is measured twice, at no extra cost
 * (first-pass.ts): on the quick first pass in the preview film, which sizes
 * the first full image, and again over the full film's next passes once the
 * JIT has warmed up; the first measurement runs low, so the second may
 * raise the scale once, and the image refines on top of the first one.
 */

/**
 * devicePixelRatio beyond this is not rendered by default: a DPR-3 phone
 * would otherwise trace 9× the pixels of its CSS size for detail the eye
 * barely resolves. The render-scale setting can still go up to it.
 */
export const DEFAULT_MAX_PIXEL_RATIO = 2;
/** Seconds one pass of the full film should take at the measured speed. */
export const PASS_BUDGET_S = 0.2;
/**
 * The automatic scale never goes below this many pixels (256²), or the
 * canvas's own size when smaller: a small view is always rendered at full
 * size (the quick pass of a tiny preview times the JIT's warm-up more than
 * the tracer), and a very slow or busy machine still gets a usable picture.
 */
export const MIN_AUTO_PIXELS = 65_536;
/**
 * With the denoiser on (the `denoise` option), the automatic scale also keeps one denoise
 * of the full film within this long, so that a denoised picture follows a camera stop
 * within about two seconds. bench/denoise-scale.mjs measured the demo's denoised error
 * after 5 s on a 2-core machine (Cornell, the error plot's grid, medians of 3). With the
 * direct convolution it was flat at 7–8e-5 for films of 192×128 to 382×256 and ten times
 * worse at 478×320, where one denoise took 3.5 s. With the Winograd convolution
 * (December 5) it is flat at 5.9–7.5e-5 from 192×128 to 574×384, whose first denoised
 * picture came at 2.4 s. Full resolution did not win.
 */
export const DENOISE_BUDGET_MS = 1200;
/**
 * The denoiser's cost per pixel until it is measured on this machine: with the Winograd
 * convolution 286×192 took 0.35–0.44 s and 478×320 0.75–0.95 s, 0.005–0.008 ms a pixel,
 * with two render workers beside it on two cores (tests/timing, December 5); the direct
 * convolution took 0.018.
 */
export const DENOISE_MS_PER_PIXEL = 0.008;

/** The most pixels the automatic scale gives a film that is denoised at `msPerPixel`. */
export function denoisePixelCap(msPerPixel = DENOISE_MS_PER_PIXEL): number {
  return DENOISE_BUDGET_MS / msPerPixel;
}

/** The speed is measured over at least this long (rAF granularity is ~16 ms). */
export const PROBE_MIN_MS = 20;
/** The warm measurement runs over this long, from the end of the full film's first pass. */
export const STEADY_PROBE_MS = 300;
/** The warm measurement changes the scale only for at least this many times the pixels. */
export const RESCALE_MIN_GAIN = 1.3;

/**
 * The render scale (relative to CSS size × capped devicePixelRatio) whose
 * pass takes `budgetS` at `samplesPerSecond`, for a canvas of `cssPixels`
 * × pixelRatio² device pixels: at most 1, and at least the scale of
 * MIN_AUTO_PIXELS. `maxPixels` caps the film (the denoiser's budget,
 * denoisePixelCap), below the floor too.
 */
export function chooseRenderScale(
  samplesPerSecond: number,
  cssPixels: number,
  pixelRatio: number,
  budgetS = PASS_BUDGET_S,
  maxPixels = Infinity,
): number {
  const full = cssPixels * pixelRatio * pixelRatio;
  if (!(full > 0)) return 1;
  const cap = Math.min(1, Math.sqrt(maxPixels / full));
  const floor = Math.min(1, Math.sqrt(MIN_AUTO_PIXELS / full), cap);
  const scale = samplesPerSecond > 0 ? Math.sqrt((samplesPerSecond * budgetS) / full) : 0;
  return Math.max(floor, Math.min(cap, scale));
}

/**
 * Samples per second of one film's passes, from its fractional progress
 * (passes averaged over stripes) between the first frame at which the
 * progress reached `from` and a frame at least `minMs` later with at least
 * one whole pass done. With `from` > 0 the window opens only after that
 * much work, once the JIT has compiled the tracer's hot loops (the first
 * pass after start-up runs several times slower than the next ones).
 */
export class SpeedProbe {
  private t0 = -1;
  private p0 = 0;
  private readonly from: number;
  private readonly minMs: number;
  private readonly start: number;

  /** `start`: when the film began (for a film that finishes before a window fits). */
  constructor(from = Number.MIN_VALUE, minMs = PROBE_MIN_MS, start = -1) {
    this.from = from;
    this.minMs = minMs;
    this.start = start;
  }

  /**
   * Feeds one frame; returns samples per second once measured, else null.
   * `finished`: the film reached its target, so no window can open any
   * more; the rate is then taken from `start` (start-up included: low).
   */
  update(
    now: number,
    progress: number,
    passesDone: number,
    pixels: number,
    finished = false,
  ): number | null {
    if (finished && passesDone >= 1 && this.start >= 0 && now > this.start) {
      return (progress * pixels) / ((now - this.start) / 1000);
    }
    if (progress < this.from) return null;
    if (this.t0 < 0) {
      this.t0 = now;
      this.p0 = progress;
      return null;
    }
    const ms = now - this.t0;
    if (passesDone < 1 || ms < this.minMs || progress <= this.p0) return null;
    return ((progress - this.p0) * pixels) / (ms / 1000);
  }
}
