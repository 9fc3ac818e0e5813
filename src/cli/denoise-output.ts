/**
 * `--denoise` and `--raw FILE.pfm` (render and merge): `--out` becomes the image denoised
 * by Open Image Denoise's "RT" network (src/core/denoise, docs/denoise.md), run on worker
 * threads (denoise-pool.ts), from the film's mean radiance and, where the film carries
 * them, its first-hit albedo and normal (integrator/aux.ts). `--raw` keeps the noisy
 * image. Denoising is biased (docs/denoise.md says where it misleads), so the raw image
 * and the `.film` stay the record of the render: a `.film` output is never denoised.
 */
import { readFile } from 'node:fs/promises';
import type { Film } from '../core/film/film.ts';
import { denoiseInWorkers } from './denoise-pool.ts';
import { vendorFolder } from './vendor-folder.ts';

/** What was denoised: the inputs the network took. */
export type DenoiseInputs = 'colour' | 'colour, albedo and normal';

/**
 * The film's mean radiance denoised on `threads` worker threads: with albedo and normal
 * (rt_hdr_alb_nrm) when the film carries them, else from the colour alone (rt_hdr).
 */
export async function denoiseFilm(
  film: Film,
  threads: number,
  workerUrl: URL,
): Promise<{ image: Float32Array; inputs: DenoiseInputs }> {
  const aux = film.auxHi !== null;
  const tza = new Uint8Array(
    await readFile(
      vendorFolder('oidn-weights', 'rt_hdr.tza') + (aux ? 'rt_hdr_alb_nrm.tza' : 'rt_hdr.tza'),
    ),
  );
  const image = await denoiseInWorkers(
    {
      width: film.width,
      height: film.rows,
      color: film.mean(),
      albedo: aux ? film.auxMean(0) : null,
      normal: aux ? film.auxMean(3) : null,
    },
    tza,
    { threads, workerUrl },
  );
  // The network's output is finite for finite input; this is the guarantee that no
  // Inf or NaN is ever written silently.
  let bad = 0;
  for (const v of image) if (!Number.isFinite(v)) bad++;
  if (bad > 0)
    throw new Error(`the denoiser gave ${bad} values that are not finite; nothing was written`);
  return { image, inputs: aux ? 'colour, albedo and normal' : 'colour' };
}
