/**
 * worker_threads entry of the denoiser (src/cli/denoise-pool.ts). workerData brings the
 * weights (a TZA file's bytes), the job (image size, input scale, tile options, the shared
 * colour, albedo, normal and output buffers) and this thread's band: its index among
 * `bands` threads, the shared workspace memory and the barrier's words. Every thread runs
 * every tile it is sent ({ tile }) together with the others, computing its band of rows
 * of each layer (src/core/denoise/unet.ts, UNetBand), and answers { done: tile }. Each
 * value is computed as one thread would compute it, so the number of threads changes no
 * bit.
 */
import { parentPort, workerData } from 'node:worker_threads';
import {
  allocDenoiseWorkspace,
  prepareDenoise,
  runDenoiseTile,
} from '../../src/core/denoise/denoise.ts';
import type { TileOptions } from '../../src/core/denoise/tiles.ts';
import { parseTza } from '../../src/core/denoise/tza.ts';
import { unetWeights } from '../../src/core/denoise/unet-weights.ts';
import { barrier } from './barrier.ts';

export interface DenoiseWorkerData {
  weights: Uint8Array;
  width: number;
  height: number;
  inputScale: number;
  tiles: TileOptions;
  color: SharedArrayBuffer;
  albedo: SharedArrayBuffer | null;
  normal: SharedArrayBuffer | null;
  output: SharedArrayBuffer;
  /** This thread's band, of `bands`. */
  band: number;
  bands: number;
  /** The tile workspace's feature maps, shared by the bands (denoiseWorkspaceBytes). */
  memory: SharedArrayBuffer;
  /** The barrier's words (barrier.ts). */
  sync: SharedArrayBuffer;
}

export interface DenoiseWorkerReply {
  done: number;
}

const data = workerData as DenoiseWorkerData;
const weights = unetWeights(parseTza(data.weights));
const job = prepareDenoise(
  {
    width: data.width,
    height: data.height,
    color: new Float32Array(data.color),
    albedo: data.albedo ? new Float32Array(data.albedo) : null,
    normal: data.normal ? new Float32Array(data.normal) : null,
  },
  weights,
  { ...data.tiles, inputScale: data.inputScale },
);
const ws = allocDenoiseWorkspace(job, data.memory);
const output = new Float32Array(data.output);
const words = new Int32Array(data.sync);
const band = { index: data.band, count: data.bands, sync: () => barrier(words, data.bands) };
parentPort!.on('message', (m: { tile: number }) => {
  runDenoiseTile(job, m.tile, ws, output, undefined, band);
  parentPort!.postMessage({ done: m.tile } satisfies DenoiseWorkerReply);
});
