/**
 * Messages between the page and the denoise workers (denoise-worker.ts), which run Open
 * Image Denoise's "RT" U-Net (src/core/denoise) off the page's thread and off the render
 * workers, so that a denoised picture never stalls the render or the page. Each request
 * names the tiles (of the plan its tile options make) that one worker runs.
 */
import type { TileOptions } from '../../src/core/denoise/tiles.ts';

/** One image to denoise: mean radiance, albedo and normal, RGB row-major (whole images). */
export interface DenoiseRequest {
  type: 'denoise';
  id: number;
  width: number;
  height: number;
  color: Float32Array;
  albedo: Float32Array;
  normal: Float32Array;
  /** The tiles this worker runs, indices into planTiles(width, height, tileOptions). */
  tiles: number[];
  tileOptions: TileOptions;
  /**
   * One Int32 holding the id of the request still wanted (isolated pages): the worker
   * asks it between the network's layers and drops this request once it changed.
   */
  stop: SharedArrayBuffer | null;
}

export type DenoiseReply =
  | { type: 'ready' }
  /** The denoised radiance, RGB row-major, written in the request's tiles only (transferred). */
  | { type: 'done'; id: number; tiles: number[]; rgb: Float32Array; ms: number }
  /** Dropped half way: a newer picture is wanted (DenoiseRequest.stop). */
  | { type: 'cancelled'; id: number }
  | { type: 'error'; id: number; message: string };

/**
 * Tiles of at most this many pixels (OIDN's tiling, src/core/denoise/tiles.ts): the
 * small network's workspace is about 350 bytes a pixel, so a tile stays under ~100 MB
 * however large the canvas; images up to 512² are one tile, for any number of workers.
 */
export const BROWSER_TILE_PIXELS = 512 * 512;
export const BROWSER_MIN_TILE_SIDE = 512;
