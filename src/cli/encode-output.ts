/**
 * The bytes of a render's output, chosen by the file's extension: PFM
 * (the mean radiance, float32), PNG (tonemapped, 8-bit sRGB) or `.film`
 * (the exact sums with their header, for merging and resuming). The same
 * film gives the same bytes, whether it was rendered in one run, resumed,
 * or merged from parts.
 */
import { deflateSync } from 'node:zlib';
import { encodeFilmFile, type FilmHeader } from '../core/film/film-file.ts';
import { encodePfm } from '../core/io/pfm.ts';
import { encodePng } from '../core/io/png.ts';
import { toDisplayByte, tonemapSums } from '../core/io/tonemap.ts';
import type { Film } from '../core/film/film.ts';

/** Whether `path` names a `.film` output (exact sums and a header). */
export function isFilmPath(path: string): boolean {
  return /\.film$/i.test(path);
}

export function encodeOutput(
  path: string,
  film: Film,
  /** The `.film` header, made only when the output is a `.film`. */
  header: () => FilmHeader,
  exposure: number,
): Uint8Array {
  if (isFilmPath(path)) return encodeFilmFile(header(), film);
  if (/\.pfm$/i.test(path)) return encodePfm(film.width, film.rows, film.mean());
  const rgba = new Uint8Array(film.width * film.rows * 4);
  tonemapSums(film.sums, exposure, rgba);
  return encodePng(film.width, film.rows, rgba, (raw) => deflateSync(raw));
}

/** An image (RGB float32, row 0 at the top) as PFM, or as a tonemapped PNG (`--denoise`). */
export function encodeImage(
  path: string,
  width: number,
  height: number,
  rgb: Float32Array,
  exposure: number,
): Uint8Array {
  if (/\.pfm$/i.test(path)) return encodePfm(width, height, rgb);
  const rgba = new Uint8Array(width * height * 4);
  for (let p = 0, n = width * height; p < n; p++) {
    rgba[p * 4] = toDisplayByte(rgb[p * 3], exposure);
    rgba[p * 4 + 1] = toDisplayByte(rgb[p * 3 + 1], exposure);
    rgba[p * 4 + 2] = toDisplayByte(rgb[p * 3 + 2], exposure);
    rgba[p * 4 + 3] = 255;
  }
  return encodePng(width, height, rgba, (raw) => deflateSync(raw));
}
