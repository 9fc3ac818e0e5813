/**
 * The denoiser across worker_threads: the images go into shared memory once, each worker
 * (workers/node/denoise-worker.ts) builds the network and one tile workspace, and tiles
 * are handed out in order to whichever worker is free (src/core/denoise/denoise.ts,
 * denoiseTiles). The tile plan depends on the image and the tile options only, so the
 * result is the same bits for any number of threads.
 */
import { Worker } from 'node:worker_threads';
import { denoiseTiles, prepareDenoise, type DenoiseImages } from '../core/denoise/denoise.ts';
import type { TileOptions } from '../core/denoise/tiles.ts';
import { parseTza } from '../core/denoise/tza.ts';
import { unetWeights } from '../core/denoise/unet-weights.ts';
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
  const data: DenoiseWorkerData = {
    weights: tza,
    width: images.width,
    height: images.height,
    inputScale: job.inputScale,
    tiles: options.tiles ?? {},
    color: shared(images.color),
    albedo: images.albedo ? shared(images.albedo) : null,
    normal: images.normal ? shared(images.normal) : null,
    output: out,
  };
  const url = options.workerUrl ?? new URL('./denoise-worker.js', import.meta.url);
  const count = Math.max(1, Math.min(options.threads, job.plan.tiles.length));
  const workers = Array.from({ length: count }, () => new Worker(url, { workerData: data }));
  // A worker that throws or exits mid-job fails the whole call with its error (nothing hangs).
  let fail: (e: Error) => void = () => {};
  const failed = new Promise<never>((_, reject) => (fail = reject));
  failed.catch(() => {}); // observed by the races below; terminate()'s exits come after
  for (const w of workers) {
    w.on('error', (e: Error) => fail(e));
    w.on('exit', (code) =>
      fail(new Error(`denoise worker exited (code ${code}) before the image was done`)),
    );
  }
  const free = [...workers];
  const waiting: ((w: Worker) => void)[] = [];
  const release = (w: Worker): void => {
    const next = waiting.shift();
    if (next) next(w);
    else free.push(w);
  };
  const acquire = (): Promise<Worker> =>
    free.length ? Promise.resolve(free.pop()!) : new Promise((resolve) => waiting.push(resolve));
  try {
    await denoiseTiles(
      job,
      async (tile) => {
        const w = await acquire();
        const done = new Promise<void>((resolve, reject) => {
          w.once('message', (m: DenoiseWorkerReply) =>
            m.done === tile
              ? resolve()
              : reject(new Error(`denoise worker answered tile ${m.done} for ${tile}`)),
          );
        });
        w.postMessage({ tile });
        await Promise.race([done, failed]);
        release(w);
      },
      count,
    );
  } finally {
    await Promise.all(workers.map((w) => w.terminate()));
  }
  return new Float32Array(out);
}
