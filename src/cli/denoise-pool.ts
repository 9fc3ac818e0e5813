/**
 * The denoiser across worker_threads: the images go into shared memory once, and so does
 * one tile workspace; each worker (workers/node/denoise-worker.ts) builds the network and
 * takes one band of rows of every layer of every tile, the bands meeting at a barrier
 * after each layer (src/core/denoise/unet.ts, UNetBand). Tiles run one after the other,
 * all threads on each, so an image of one tile (up to OIDN's 2160² by default) uses every
 * thread, and no pixel is computed twice as overlapped tiles would be. Each value is
 * computed as one thread computes it and the tile plan depends on the image and the tile
 * options only, so the result is the same bits for any number of threads.
 */
import { Worker } from 'node:worker_threads';
import {
  denoiseWorkspaceBytes,
  prepareDenoise,
  type DenoiseImages,
} from '../core/denoise/denoise.ts';
import type { TileOptions } from '../core/denoise/tiles.ts';
import { parseTza } from '../core/denoise/tza.ts';
import { unetWeights } from '../core/denoise/unet-weights.ts';
import { abortBarrier, BARRIER_WORDS } from '../../workers/node/barrier.ts';
import type { DenoiseWorkerData, DenoiseWorkerReply } from '../../workers/node/denoise-worker.ts';

export interface DenoisePoolOptions {
  threads: number;
  /** The bundled worker (dist/cli/denoise-worker.js beside the command line). */
  workerUrl?: URL;
  tiles?: TileOptions;
  inputScale?: number;
}

function shared(a: Float32Array): SharedArrayBuffer {
  const sab = new SharedArrayBuffer(a.byteLength);
  new Float32Array(sab).set(a);
  return sab;
}

/** Denoises `images` with the TZA weights `tza` on `threads` worker threads. */
export async function denoiseInWorkers(
  images: DenoiseImages,
  tza: Uint8Array,
  options: DenoisePoolOptions,
): Promise<Float32Array> {
  // Validate and plan here, so that bad input is one error before any thread starts.
  const job = prepareDenoise(images, unetWeights(parseTza(tza)), {
    ...options.tiles,
    inputScale: options.inputScale,
  });
  const out = new SharedArrayBuffer(images.width * images.height * 3 * 4);
  // No more bands than rows of 4×4 blocks at full resolution: a thread past that would
  // only parse the weights and wait at every barrier.
  const count = Math.max(1, Math.min(Math.floor(options.threads), job.plan.tileH / 4));
  const sync = new SharedArrayBuffer(BARRIER_WORDS * 4);
  const data: Omit<DenoiseWorkerData, 'band'> = {
    weights: tza,
    width: images.width,
    height: images.height,
    inputScale: job.inputScale,
    tiles: options.tiles ?? {},
    color: shared(images.color),
    albedo: images.albedo ? shared(images.albedo) : null,
    normal: images.normal ? shared(images.normal) : null,
    output: out,
    bands: count,
    memory: new SharedArrayBuffer(denoiseWorkspaceBytes(job)),
    sync,
  };
  const url = options.workerUrl ?? new URL('./denoise-worker.js', import.meta.url);
  const workers = Array.from(
    { length: count },
    (_, band) => new Worker(url, { workerData: { ...data, band } satisfies DenoiseWorkerData }),
  );
  // A worker that throws or exits mid-job fails the whole call with its error, and the
  // others, which may be waiting for it at the barrier, are released (nothing hangs).
  let fail: (e: Error) => void = () => {};
  const failed = new Promise<never>((_, reject) => (fail = reject));
  failed.catch(() => {}); // observed by the races below; terminate()'s exits come after
  const failWith = (e: Error): void => {
    abortBarrier(new Int32Array(sync));
    fail(e);
  };
  for (const w of workers) {
    w.on('error', (e: Error) => failWith(e));
    w.on('exit', (code) =>
      failWith(new Error(`denoise worker exited (code ${code}) before the image was done`)),
    );
  }
  try {
    for (let tile = 0; tile < job.plan.tiles.length; tile++) {
      const done = workers.map(
        (w) =>
          new Promise<void>((resolve, reject) => {
            w.once('message', (m: DenoiseWorkerReply) =>
              m.done === tile
                ? resolve()
                : reject(new Error(`denoise worker answered tile ${m.done} for ${tile}`)),
            );
            w.postMessage({ tile });
          }),
      );
      await Promise.race([Promise.all(done), failed]);
    }
  } finally {
    await Promise.all(workers.map((w) => w.terminate()));
  }
  return new Float32Array(out);
}
