/**
 * The display step: from the film's sums (RGBA, A = samples) to pixels on
 * the canvas. Two implementations draw the same picture: WebGL2 (upload an
 * RGBA32F texture, tone map in a shader) and Canvas 2D (tone map on the CPU
 * with the core's tonemapSums).
 */
import type { Backdrop } from './backdrop.ts';
import type { DisplayMode } from './types.ts';

export interface DisplayPixels {
  width: number;
  height: number;
  /** RGBA8, row 0 at the top. */
  rgba: Uint8Array;
}

export interface Display {
  readonly mode: DisplayMode;
  /**
   * Draws a film of filmWidth × filmHeight onto the whole canvas (a smaller
   * film, the low-resolution preview, is scaled up); pixels without a
   * sample show the backdrop given to `clear`. `dirtyRows` lists the
   * rows whose sums changed since the previous draw as flat [y0, y1, …]
   * spans, so only those are uploaded or tone mapped; null means all.
   */
  draw(
    sums: Float32Array,
    filmWidth: number,
    filmHeight: number,
    exposure: number,
    dirtyRows: readonly number[] | null,
  ): void;
  /**
   * The film (of this size) is all zeros now: until its pixels get samples
   * they show `backdrop` (the last picture, scaled), or black without one.
   * Much cheaper than drawing every row of zeros; a draw follows.
   */
  clear(filmWidth: number, filmHeight: number, backdrop: Backdrop | null): void;
  /** The canvas's pixels as last drawn. */
  readPixels(): DisplayPixels;
  destroy(): void;
}
