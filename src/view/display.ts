/**
 * The display step: from the film's sums (RGBA, A = samples) to pixels on
 * the canvas. Two implementations draw the same picture: WebGL2 (upload an
 * RGBA32F texture, tone map in a shader) and Canvas 2D (tone map on the CPU
 * with the core's tonemapSums).
 */
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
   * film, the low-resolution preview, is scaled up). `dirtyRows` lists the
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
   * Forgets the previous image: the film (of this size) is all zeros now.
   * Much cheaper than drawing every row of zeros; a draw follows.
   */
  clear(filmWidth: number, filmHeight: number): void;
  /** The canvas's pixels as last drawn. */
  readPixels(): DisplayPixels;
  destroy(): void;
}
