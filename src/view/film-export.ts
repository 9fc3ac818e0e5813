/**
 * The full film as files: its linear mean radiance (for PFM) and a PNG
 * tone mapped at the display's exposure, at the film's own size whatever
 * the canvas shows. The PNG is the picture on screen: the denoised one while
 * it is shown (`sums`, RGBA with A = 1); the PFM is always the raw, unbiased film.
 */
import { tonemapSums } from '../core/index.ts';
import type { FilmJob } from './film-job.ts';

/** Linear mean radiance, RGB float32, row 0 at the top (empty without a film). */
export function linearImage(job: FilmJob | null): {
  width: number;
  height: number;
  rgb: Float32Array;
} {
  if (!job) return { width: 0, height: 0, rgb: new Float32Array(0) };
  return { width: job.width, height: job.height, rgb: job.film.mean() };
}

export function pngBlob(
  job: FilmJob | null,
  exposure: number,
  sums: Float32Array = job?.film.sums ?? new Float32Array(0),
): Promise<Blob> {
  if (!job) return Promise.reject(new Error('no image yet'));
  const image = new ImageData(job.width, job.height);
  tonemapSums(sums, exposure, image.data);
  const canvas = document.createElement('canvas');
  canvas.width = job.width;
  canvas.height = job.height;
  canvas.getContext('2d')!.putImageData(image, 0, 0);
  return new Promise((resolve, reject) =>
    canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('PNG encoding failed'))), 'image/png'),
  );
}
