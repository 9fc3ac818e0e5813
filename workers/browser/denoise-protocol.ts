/**
 * Messages between the page and the denoise workers (denoise-worker.ts), which run Open
 * Image Denoise's "RT" U-Net (src/core/denoise) off the page's thread and off the render
 * workers, so that a denoised picture never stalls the render or the page. Each request
 * names the tiles (of the plan DENOISE_TILE_OPTIONS make) that one worker runs.
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
  /** The tiles this worker runs, indices into planTiles(width, height, DENOISE_TILE_OPTIONS). */
  tiles: number[];
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
 * The one tile plan of every image (OIDN's tiling, src/core/denoise/tiles.ts): tiles of
 * at most 512² pixels, so that with the small network's workspace of about 350 bytes a
 * pixel a tile stays under ~100 MB however large the canvas. It is the same whatever the
 * number of workers: the Winograd convolution's bits depend on the tile a pixel is
 * computed in (src/core/denoise/winograd.ts), so a plan that split the image for more
 * workers would give other bits; workers share out the tiles of this one plan.
 */
export const DENOISE_TILE_OPTIONS: TileOptions = {
  maxTilePixels: 512 * 512,
  minTileSide: 512,
};
