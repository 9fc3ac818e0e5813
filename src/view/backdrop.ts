/**
 * The backdrop: the last picture on screen, kept as linear radiance and
 * shown, scaled to the canvas, under every pixel the current film has no
 * sample for yet. A restart (camera step, new settings, the switch from
 * the drag preview to the full film) therefore never shows black where
 * there was an image: the new pass refines on top of the old picture,
 * pixel by pixel, as its samples arrive.
 *
 * Only the display uses it; the film, and so the saved and compared
 * images, never contain a backdrop value.
 */
import { toDisplayByte } from '../core/index.ts';

export interface Backdrop {
  width: number;
  height: number;
  /**
   * Linear mean RGB per pixel, row 0 at the top; A is 1 where the pixel
   * holds a picture and 0 where none was ever shown (drawn black).
   */
  rgba: Float32Array;
}

/** Index of the nearest source texel for target coordinate x of `to` texels from `from` texels. */
function nearest(x: number, to: number, from: number): number {
  return Math.min(from - 1, Math.floor(((x + 0.5) * from) / to));
}

/**
 * What the display shows for a film with `sums` (RGBA, A = samples) over
 * backdrop `under`, as a new backdrop: the film's mean where it has a
 * sample, `under` (nearest texel) elsewhere. At the film's resolution when
 * every pixel has a sample or `under` is no larger, else at `under`'s, so
 * a drag that restarts before a pass completes does not coarsen the
 * picture step by step.
 */
export function compositeBackdrop(
  sums: Float32Array,
  width: number,
  height: number,
  under: Backdrop | null,
): Backdrop | null {
  const n = width * height;
  let covered = 0;
  for (let i = 3; i < n * 4; i += 4) if (sums[i] > 0) covered++;
  if (covered === 0) return under;
  const useFilm = covered === n || !under || under.width * under.height <= n;
  const w = useFilm ? width : under.width;
  const h = useFilm ? height : under.height;
  const out = new Float32Array(w * h * 4);
  for (let y = 0; y < h; y++) {
    const fy = useFilm ? y : nearest(y, h, height);
    const uy = under ? nearest(y, h, under.height) : 0;
    for (let x = 0; x < w; x++) {
      const fx = useFilm ? x : nearest(x, w, width);
      const f = (fy * width + fx) * 4;
      const o = (y * w + x) * 4;
      const count = sums[f + 3];
      if (count > 0) {
        const inv = 1 / count;
        out[o] = sums[f] * inv;
        out[o + 1] = sums[f + 1] * inv;
        out[o + 2] = sums[f + 2] * inv;
        out[o + 3] = 1;
      } else if (under) {
        const u = (uy * under.width + nearest(x, w, under.width)) * 4;
        out[o] = under.rgba[u];
        out[o + 1] = under.rgba[u + 1];
        out[o + 2] = under.rgba[u + 2];
        out[o + 3] = under.rgba[u + 3];
      }
    }
  }
  return { width: w, height: h, rgba: out };
}

/**
 * Tone maps rows [y0, y1) of a film (RGBA sums, A = samples) into RGBA8
 * `out` (the film's size), taking `backdrop` where a pixel has no sample
 * yet: the Canvas 2D twin of the WebGL2 shader.
 */
export function tonemapOverBackdrop(
  sums: Float32Array,
  width: number,
  height: number,
  y0: number,
  y1: number,
  backdrop: Backdrop | null,
  exposure: number,
  out: Uint8ClampedArray,
): void {
  for (let y = y0; y < y1; y++) {
    const by = backdrop ? nearest(y, height, backdrop.height) : 0;
    for (let x = 0; x < width; x++) {
      const i = (y * width + x) * 4;
      const count = sums[i + 3];
      let r = 0;
      let g = 0;
      let b = 0;
      if (count > 0) {
        const inv = 1 / count;
        r = sums[i] * inv;
        g = sums[i + 1] * inv;
        b = sums[i + 2] * inv;
      } else if (backdrop) {
        const u = (by * backdrop.width + nearest(x, width, backdrop.width)) * 4;
        const a = backdrop.rgba[u + 3];
        r = backdrop.rgba[u] * a;
        g = backdrop.rgba[u + 1] * a;
        b = backdrop.rgba[u + 2] * a;
      }
      out[i] = toDisplayByte(r, exposure);
      out[i + 1] = toDisplayByte(g, exposure);
      out[i + 2] = toDisplayByte(b, exposure);
      out[i + 3] = 255;
    }
  }
}
