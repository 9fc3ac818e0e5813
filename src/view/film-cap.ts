/**
 * How large a film the browser renders: the accumulator cap. A canvas can
 * be enormous (a huge CSS size × devicePixelRatio), and so can a fixed
 * size in the options; a film that size would take gigabytes and crash
 * the tab. So the full film's accumulator (its sums and exact-sum planes,
 * Film.byteLength) is held to MAX_FILM_BYTES, and each side to
 * MAX_FILM_SIDE (WebGL2 textures and 2D canvases are limited per side).
 *
 * A size taken from the canvas is scaled down to fit, keeping its aspect
 * ratio; the controller says so with a `fallback` event carrying the
 * reduced render scale. A fixed size (options.width/height) is the caller's
 * explicit request: one that does not fit is an `error`, not silently
 * shrunk. Memory that cannot be had even under the cap (the allocation
 * throws) is handled the same way: a smaller film, or an error.
 */
import { Film } from '../core/index.ts';

/** The full film's accumulator is at most this many bytes (256 MiB). */
export const MAX_FILM_BYTES = 256 * 1024 * 1024;
/** And at most this many pixels on a side. */
export const MAX_FILM_SIDE = 8192;

export function mib(bytes: number): string {
  const m = bytes / (1024 * 1024);
  return `${m < 10 ? m.toFixed(1) : Math.round(m)} MiB`;
}

/** The most pixels a film may have under MAX_FILM_BYTES (fewer with albedo and normal planes). */
export function maxFilmPixels(aux = false): number {
  return Math.floor(MAX_FILM_BYTES / Film.byteLength(1, 1, aux));
}

/** Why a film of w × h may not be made, or null when it may. */
export function filmSizeProblem(
  width: number,
  height: number,
  maxSide = MAX_FILM_SIDE,
  aux = false,
): string | null {
  const bytes = Film.byteLength(width, height, aux);
  if (bytes > MAX_FILM_BYTES) {
    return `a ${width}×${height} render needs ${mib(bytes)} for its accumulator${aux ? ' (with the denoiser’s albedo and normal)' : ''}, over the cap of ${mib(MAX_FILM_BYTES)} (${maxFilmPixels(aux)} pixels)`;
  }
  if (width > maxSide || height > maxSide) {
    return `a ${width}×${height} render is over the cap of ${maxSide} pixels a side`;
  }
  return null;
}

/**
 * The factor (≤ 1) by which w × h must shrink in each direction to fit
 * the caps, with `pixelFraction` (≤ 1) of the pixel budget available.
 */
export function fitFactor(
  width: number,
  height: number,
  pixelFraction = 1,
  maxSide = MAX_FILM_SIDE,
  aux = false,
): number {
  const pixels = maxFilmPixels(aux) * pixelFraction;
  return Math.min(1, Math.sqrt(pixels / (width * height)), maxSide / Math.max(width, height));
}
