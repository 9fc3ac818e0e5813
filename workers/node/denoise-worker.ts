/**
 * worker_threads entry of the denoiser (src/cli/denoise-pool.ts). workerData brings the
 * weights (a TZA file's bytes) and the job: image size, input scale, tile options and the
 * shared colour, albedo, normal and output buffers. The worker parses the weights and
 * allocates one workspace for the job's tile size, then runs each tile it is sent
 * ({ tile }) into the shared output and answers { done: tile }. Tiles write disjoint
 * output regions and each tile's arithmetic is fixed (src/core/denoise), so which worker
 * runs which tile changes no bit.
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
const ws = allocDenoiseWorkspace(job);
const output = new Float32Array(data.output);
parentPort!.on('message', (m: { tile: number }) => {
  runDenoiseTile(job, m.tile, ws, output);
  parentPort!.postMessage({ done: m.tile } satisfies DenoiseWorkerReply);
});
