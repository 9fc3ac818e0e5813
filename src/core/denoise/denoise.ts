/**
 * Denoising an HDR image with OIDN's "RT" network, tile by tile (OIDN core/unet_filter.cpp,
 * UNetFilter::execute): the input scale comes from the whole image's autoexposure, once;
 * each tile is then encoded into the network's input (transfer.ts), run (unet.ts) and
 * decoded into its own, disjoint region of the output. Tiles share nothing but read-only
 * inputs, so any executor may run them in any order and on any thread (the browser's
 * denoise workers each take some), and the output's bits do not depend on it. Threads
 * that share memory may also run one tile together, in bands of rows (UNetBand; the
 * command line's pool, src/cli/denoise-pool.ts).
 */
import { at } from './planes.ts';
import { planTiles, type TileOptions, type TilePlan } from './tiles.ts';
import { autoexposure, decodeHdr, encodeAlbedo, encodeHdr, encodeNormal } from './transfer.ts';
import {
  allocUNetWorkspace,
  bandRows,
  runUNet,
  unetWorkspaceBytes,
  type UNetBand,
  type UNetWorkspace,
} from './unet.ts';
import type { UNetWeights } from './unet-weights.ts';

export interface DenoiseImages {
  readonly width: number;
  readonly height: number;
  /** Linear HDR radiance, RGB, row-major, row 0 at the top. */
  readonly color: Float32Array;
  /** First-hit albedo in [0, 1] (needs weights for 6 or 9 inputs). */
  readonly albedo?: Float32Array | null;
  /** First-hit shading normal in [-1, 1] (needs albedo and weights for 9 inputs). */
  readonly normal?: Float32Array | null;
}

export interface DenoiseJob {
  readonly images: DenoiseImages;
  readonly weights: UNetWeights;
  readonly plan: TilePlan;
  /** Multiplies colour before encoding (OIDN's inputScale; autoexposure when not given). */
  readonly inputScale: number;
}

export function prepareDenoise(
  images: DenoiseImages,
  weights: UNetWeights,
  options: TileOptions & { inputScale?: number } = {},
): DenoiseJob {
  const { width, height, color, albedo, normal } = images;
  if (!(Number.isInteger(width) && Number.isInteger(height) && width > 0 && height > 0))
    throw new RangeError(`denoise: bad image size ${width}×${height}`);
  const n = width * height * 3;
  for (const [name, img] of [
    ['color', color],
    ['albedo', albedo],
    ['normal', normal],
  ] as const)
    if (img && img.length !== n)
      throw new RangeError(`denoise: ${name} has ${img.length} floats, expected ${n}`);
  const inputs = 3 + (albedo ? 3 : 0) + (normal ? 3 : 0);
  if (normal && !albedo)
    throw new RangeError('denoise: a normal image needs an albedo image (as in OIDN)');
  if (inputs !== weights.inputChannels)
    throw new RangeError(
      `denoise: the weights take ${weights.inputChannels} input channels, the images give ${inputs}`,
    );
  const inputScale = options.inputScale ?? autoexposure(color, width, height);
  return { images, weights, plan: planTiles(width, height, options), inputScale };
}

/**
 * A workspace for the job's tile size (allocate once per thread, reuse for every tile).
 * Threads that run tiles together in bands pass the same `shared` memory, of
 * `denoiseWorkspaceBytes(job)`.
 */
export function allocDenoiseWorkspace(job: DenoiseJob, shared?: ArrayBufferLike): UNetWorkspace {
  return allocUNetWorkspace(job.weights, job.plan.tileH, job.plan.tileW, shared);
}

export function denoiseWorkspaceBytes(job: DenoiseJob): number {
  return unetWorkspaceBytes(job.weights, job.plan.tileH, job.plan.tileW);
}

/**
 * Denoises tile `index` of the job into `output` (RGB, the image's size). Returns false,
 * leaving the tile's output unwritten, when `stop` (asked between layers) said to stop.
 * With `band`, this thread is one of `band.count` that run the tile together on a shared
 * workspace (unet.ts, UNetBand): each encodes, computes and decodes its band of rows. A
 * band cannot stop early (runUNet refuses `stop` with a band).
 */
export function runDenoiseTile(
  job: DenoiseJob,
  index: number,
  ws: UNetWorkspace,
  output: Float32Array,
  stop?: () => boolean,
  band?: UNetBand,
): boolean {
  const tile = job.plan.tiles[index];
  if (!tile) throw new RangeError(`denoise: no tile ${index}`);
  const { width, color, albedo, normal } = job.images;
  const { input } = ws;
  const scale = job.inputScale;
  // The tile's padding is zero in the encoded domain, as OIDN's input process: each band
  // clears its rows of the buffer (with their border columns, which stay zero), then
  // encodes the image rows that fall in them.
  const [b0, b1] = bandRows(ws.h, band);
  for (let c = 0; c < input.c; c++) input.data.fill(0, at(input, c, b0, -1), at(input, c, b1, -1));
  const y0 = Math.max(0, b0 - tile.bufY);
  const y1 = Math.min(tile.srcH, b1 - tile.bufY);
  for (let y = y0; y < y1; y++) {
    for (let x = 0; x < tile.srcW; x++) {
      const p = 3 * ((tile.srcY + y) * width + tile.srcX + x);
      const q = at(input, 0, tile.bufY + y, tile.bufX + x);
      const plane = input.plane;
      for (let c = 0; c < 3; c++) input.data[q + c * plane] = encodeHdr(color[p + c]! * scale);
      if (albedo)
        for (let c = 0; c < 3; c++) input.data[q + (3 + c) * plane] = encodeAlbedo(albedo[p + c]!);
      if (normal)
        for (let c = 0; c < 3; c++) input.data[q + (6 + c) * plane] = encodeNormal(normal[p + c]!);
    }
  }
  band?.sync();
  if (!runUNet(job.weights, ws, stop, band)) return false;
  const out = ws.output;
  const outputScale = scale !== 0 ? 1 / scale : 0;
  const [o0, o1] = bandRows(tile.outH, band);
  for (let y = o0; y < o1; y++) {
    for (let x = 0; x < tile.outW; x++) {
      const p = 3 * ((tile.outY + y) * width + tile.outX + x);
      const q = at(out, 0, tile.outBufY + y, tile.outBufX + x);
      for (let c = 0; c < 3; c++)
        output[p + c] = decodeHdr(out.data[q + c * out.plane]!) * outputScale;
    }
  }
  return true;
}

/** Denoises the whole image on this thread. */
export function denoise(
  images: DenoiseImages,
  weights: UNetWeights,
  options: TileOptions & { inputScale?: number } = {},
): Float32Array {
  const job = prepareDenoise(images, weights, options);
  const ws = allocDenoiseWorkspace(job);
  const output = new Float32Array(images.width * images.height * 3);
  for (let i = 0; i < job.plan.tiles.length; i++) runDenoiseTile(job, i, ws, output);
  return output;
}
