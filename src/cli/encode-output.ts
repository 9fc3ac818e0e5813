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
import { tonemapSums } from '../core/io/tonemap.ts';
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
