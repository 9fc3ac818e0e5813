/**
 * OIDN's tiling (core/unet_filter.cpp, UNetFilter::init and execute), for images larger
 * than one tile (and, in the browser, to spread a large image over denoise workers). Tiles overlap by the network's
 * half receptive field rounded up to the alignment (174 / 2 → 96 pixels), so each
 * output pixel is computed from all the input that can reach it; tile origins are
 * multiples of 16, so every tile's poolings fall on the same grid as the whole image's.
 * The plan depends only on the image size and the options, never on the worker count:
 * the same tiles, hence the same bits, for any number of workers.
 */
import { TILE_ALIGNMENT } from './unet.ts';

/** OIDN's receptive field of the base U-Net, in pixels (unet_filter.h). */
export const RECEPTIVE_FIELD = 174;
export const TILE_OVERLAP = Math.ceil(RECEPTIVE_FIELD / 2 / TILE_ALIGNMENT) * TILE_ALIGNMENT;

export interface DenoiseTile {
  /** Input region read from the image (overlap included). */
  readonly srcX: number;
  readonly srcY: number;
  readonly srcW: number;
  readonly srcH: number;
  /** Where that region sits in the tile buffer (aligned to its bottom-right, as OIDN). */
  readonly bufX: number;
  readonly bufY: number;
  /** Output region written to the image, and where it is in the tile buffer. */
  readonly outX: number;
  readonly outY: number;
  readonly outW: number;
  readonly outH: number;
  readonly outBufX: number;
  readonly outBufY: number;
}

export interface TilePlan {
  readonly tileW: number;
  readonly tileH: number;
  readonly tiles: readonly DenoiseTile[];
}

export interface TileOptions {
  /** Largest tile in pixels (OIDN's default 2160²). */
  maxTilePixels?: number;
  /** Smallest tile side OIDN splits down to (768 there; at least 4 × overlap). */
  minTileSide?: number;
}

const roundUp = (a: number, b: number): number => Math.ceil(a / b) * b;
const ceilDiv = (a: number, b: number): number => Math.ceil(a / b);

export function planTiles(width: number, height: number, options: TileOptions = {}): TilePlan {
  const maxPixels = options.maxTilePixels ?? 2160 * 2160;
  const minSide = roundUp(Math.max(options.minTileSide ?? 768, 4 * TILE_OVERLAP), TILE_ALIGNMENT);
  const o2 = 2 * TILE_OVERLAP;
  let tileH = roundUp(height, TILE_ALIGNMENT);
  let tileW = roundUp(width, TILE_ALIGNMENT);
  let countH = 1;
  let countW = 1;
  // Split the longer side until a tile is small enough (UNetFilter::init's loop).
  while (tileH * tileW > maxPixels) {
    if (tileH > minSide && tileH > tileW) {
      const next = ceilDiv(height + o2 * countH, countH + 1);
      tileH = Math.min(Math.max(roundUp(next, TILE_ALIGNMENT), minSide), tileH - TILE_ALIGNMENT);
      countH = Math.max(ceilDiv(height - o2, tileH - o2), 1);
    } else if (tileW > minSide) {
      const next = ceilDiv(width + o2 * countW, countW + 1);
      tileW = Math.min(Math.max(roundUp(next, TILE_ALIGNMENT), minSide), tileW - TILE_ALIGNMENT);
      countW = Math.max(ceilDiv(width - o2, tileW - o2), 1);
    } else break;
  }
  const tiles: DenoiseTile[] = [];
  for (let i = 0; i < countH; i++) {
    const y = i * (tileH - o2);
    const beginH = i > 0 ? TILE_OVERLAP : 0;
    const endH = i < countH - 1 ? TILE_OVERLAP : 0;
    const srcH = Math.min(height - y, tileH);
    const bufY = tileH - roundUp(srcH, TILE_ALIGNMENT);
    for (let j = 0; j < countW; j++) {
      const x = j * (tileW - o2);
      const beginW = j > 0 ? TILE_OVERLAP : 0;
      const endW = j < countW - 1 ? TILE_OVERLAP : 0;
      const srcW = Math.min(width - x, tileW);
      const bufX = tileW - roundUp(srcW, TILE_ALIGNMENT);
      tiles.push({
        srcX: x,
        srcY: y,
        srcW,
        srcH,
        bufX,
        bufY,
        outX: x + beginW,
        outY: y + beginH,
        outW: srcW - beginW - endW,
        outH: srcH - beginH - endH,
        outBufX: bufX + beginW,
        outBufY: bufY + beginH,
      });
    }
  }
  return { tileW, tileH, tiles };
}
