/**
 * Messages between the page and the denoise worker (denoise-worker.ts), which runs Open
 * Image Denoise's "RT" U-Net (src/core/denoise) off the page's thread and off the render
 * workers, so that a denoised picture never stalls the render or the page.
 */

/** One image to denoise: mean radiance, albedo and normal, RGB row-major (transferred). */
export interface DenoiseRequest {
  type: 'denoise';
  id: number;
  width: number;
  height: number;
  color: Float32Array;
  albedo: Float32Array;
  normal: Float32Array;
  /**
   * One Int32 holding the id of the request still wanted (isolated pages): the worker
   * asks it between the network's layers and drops this request once it changed.
   */
  stop: SharedArrayBuffer | null;
}

export type DenoiseReply =
  | { type: 'ready' }
  /** The denoised radiance, RGB row-major (transferred), and the network's time on the worker. */
  | { type: 'done'; id: number; rgb: Float32Array; ms: number }
  /** Dropped half way: a newer picture is wanted (DenoiseRequest.stop). */
  | { type: 'cancelled'; id: number }
  | { type: 'error'; id: number; message: string };

/**
 * Tiles of at most this many pixels (OIDN's tiling, src/core/denoise/tiles.ts): the
 * small network's workspace is about 350 bytes a pixel, so a tile stays under ~100 MB
 * however large the canvas; images up to 512² are one tile.
 */
export const BROWSER_TILE_PIXELS = 512 * 512;
export const BROWSER_MIN_TILE_SIDE = 512;
