/** Denoiser feature maps for tests (src/core/denoise/planes.ts). */
import { allocPlanes, at, type Planes } from '../../src/core/denoise/planes.ts';

/** c channels of h × w, every interior value drawn from `next`; the border stays zero. */
export function randomPlanes(c: number, h: number, w: number, next: () => number): Planes {
  const p = allocPlanes(c, h, w);
  for (let ch = 0; ch < c; ch++)
    for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) p.data[at(p, ch, y, x)] = next();
  return p;
}
